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
  CHECK_THAT(falling.criterion, Contains("still falls: 0.5 of pass 3's (settled: >= 0.95); run more passes"));
  // The same with enough passes: below 1 % of pass 1.
  CHECK(classify_passes(sequence(
                            8, [](int k) { return 1e-3 * std::pow(0.5, k - 1); }, 0.9))
            .verdict == ShakedownVerdict::ElasticShakedown);
  // Falling slowly below Melan's limit (the stationary map's p0/k = 3.4 at mu = 0.1, 5 % below):
  // 0.85 of the pass before in pass 8, still 2.4 % of pass 1's.
  auto slowly = [](int k) {
    const Real m[] = {3.56e-4, 9.43e-5, 4.13e-5, 2.37e-5, 1.58e-5, 1.22e-5, 1.01e-5, 8.65e-6};
    return m[k - 1];
  };
  CHECK(classify_passes(sequence(8, slowly, 0.94)).verdict == ShakedownVerdict::Undetermined);
  // Settling above it (p0/k = 3.0 at mu = 0.3, 3 % above): 0.96 of the pass before in pass 8,
  // ratchetting by the net shear; 0.90 in pass 5, not settled yet.
  auto settling = [](int k) {
    const Real m[] = {5.0e-4, 3.5e-4, 2.88e-4, 2.56e-4, 2.31e-4, 2.12e-4, 1.99e-4, 1.91e-4};
    return m[k - 1];
  };
  CHECK(classify_passes(sequence(8, settling, 0.98)).verdict == ShakedownVerdict::Ratchetting);
  CHECK(classify_passes(sequence(5, settling, 0.98)).verdict == ShakedownVerdict::Undetermined);
}

TEST_CASE("shakedown verdict: fewer than three passes are undetermined", "[analysis][shakedown]") {
  const auto r = classify_passes(sequence(
      2, [](int) { return 1e-3; }, 0.9));
  CHECK(r.verdict == ShakedownVerdict::Undetermined);
  CHECK_THAT(r.criterion, Contains("at least 3"));
}
