// The shakedown verdict on synthetic per-pass sequences.
#include <catch2/catch.hpp>

#include <cmath>

#include "roller/analysis/shakedown.hpp"

using namespace roller;
using Catch::Contains;

namespace {

// Passes whose mean plastic increment follows `mean(n)` and whose net band shear strain is
// `net_share` of the accumulated plastic shear.
std::vector<PassRecord> sequence(int n, Real (*mean)(int), Real net_share) {
  std::vector<PassRecord> out;
  for (int k = 1; k <= n; ++k) {
    PassRecord r;
    r.pass = k;
    r.mean_plastic_increment = mean(k);
    r.max_plastic_increment = 3.0 * mean(k);
    r.band_plastic_increment = 2.0 * mean(k);
    r.residual_shear_increment = net_share * std::sqrt(3.0) * r.band_plastic_increment;
    out.push_back(r);
  }
  return out;
}

}  // namespace

TEST_CASE("shakedown verdict: increments dying out are elastic shakedown", "[analysis][shakedown]") {
  const auto r = classify_passes(sequence(
      5, [](int k) { return 1e-3 * std::pow(0.1, k - 1); }, 0.9));
  CHECK(r.verdict == ShakedownVerdict::ElasticShakedown);
  CHECK_THAT(r.criterion, Contains("0.0001 of pass 1's in pass 5"));
  // No plastic strain at all.
  const auto none = classify_passes(sequence(
      3, [](int) { return 0.0; }, 0.0));
  CHECK(none.verdict == ShakedownVerdict::ElasticShakedown);
  CHECK_THAT(none.criterion, Contains("no plastic strain"));
}

TEST_CASE("shakedown verdict: steady increments with no net strain are plastic shakedown, with net strain ratchetting",
          "[analysis][shakedown]") {
  auto steady = [](int k) { return 1e-3 * (1.0 + 0.5 / k); };
  CHECK(classify_passes(sequence(5, steady, 0.02)).verdict == ShakedownVerdict::PlasticShakedown);
  const auto ratchet = classify_passes(sequence(5, steady, 0.8));
  CHECK(ratchet.verdict == ShakedownVerdict::Ratchetting);
  CHECK_THAT(ratchet.criterion, Contains("0.8 of its accumulated"));
}

TEST_CASE("shakedown verdict: increments that still fall give no verdict, whatever their net shear",
          "[analysis][shakedown]") {
  // Halved every pass, not below 1 % of pass 1 by the last: under a sliding traction the net shear
  // is most of the plastic shear, and these are not ratchetting.
  const auto falling = classify_passes(sequence(
      4, [](int k) { return 1e-3 * std::pow(0.5, k - 1); }, 0.9));
  CHECK(falling.verdict == ShakedownVerdict::Undetermined);
  CHECK_THAT(falling.criterion, Contains("still falls: 0.5 of pass 3's (settled: >= 0.75); run more passes"));
  // The same with enough passes: below 1 % of pass 1.
  CHECK(classify_passes(sequence(
                            8, [](int k) { return 1e-3 * std::pow(0.5, k - 1); }, 0.9))
            .verdict == ShakedownVerdict::ElasticShakedown);
  // Falling fast once, then settled (the transient passes 5 % above Melan's limit:
  // 1.3e-3 2.1e-4 1.5e-4 1.4e-4 1.3e-4): ratchetting by the net shear.
  auto settling = [](int k) {
    const Real m[] = {1.3e-3, 2.1e-4, 1.5e-4, 1.4e-4, 1.3e-4};
    return m[k - 1];
  };
  CHECK(classify_passes(sequence(5, settling, 0.3)).verdict == ShakedownVerdict::Ratchetting);
  CHECK(classify_passes(sequence(3, settling, 0.3)).verdict == ShakedownVerdict::Undetermined);  // 0.71
}

TEST_CASE("shakedown verdict: fewer than three passes are undetermined", "[analysis][shakedown]") {
  const auto r = classify_passes(sequence(
      2, [](int) { return 1e-3; }, 0.9));
  CHECK(r.verdict == ShakedownVerdict::Undetermined);
  CHECK_THAT(r.criterion, Contains("at least 3"));
}
