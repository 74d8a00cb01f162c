// Melan's bound on McEwen's closed-form stresses of a Hertz line contact (k = 1, a = 1, p0 = 1),
// against Johnson's limits (Contact Mechanics, ch. 9: 4.0 frictionless, 3.56, 3.20, 2.89 under
// sliding at mu = 0.1, 0.2, 0.3) and against what the theorem implies by itself.
#include <catch2/catch.hpp>

#include <cmath>
#include <iostream>

#include <fmt/format.h>

#include "../support/mcewen.hpp"
#include "roller/analysis/melan.hpp"

using namespace roller;

namespace {

constexpr Real kNu = 0.3;
const Real kYield = std::sqrt(3.0);  // k = sigma_y / sqrt(3) = 1: load factors are p0/k

MelanRow mcewen_row(Real z, Real mu, Real back_stress_bound = std::numeric_limits<Real>::infinity()) {
  MelanRow row;
  row.depth = z;
  row.back_stress_bound = back_stress_bound;
  for (int i = 0; i <= 800; ++i) {
    const Real x = -4.0 + 0.01 * i;
    row.x.push_back(x);
    row.stress.push_back(test::mcewen_stress(x, z, mu, kNu));
    row.yield_stress.push_back(kYield);
  }
  return row;
}

// Rows from the surface to 1.5 a every 0.02 a.
std::vector<MelanRow> mcewen_rows(Real mu) {
  std::vector<MelanRow> rows;
  for (int j = 0; j <= 75; ++j) rows.push_back(mcewen_row(0.02 * j, mu));
  return rows;
}

}  // namespace

// Slow: 11 s in Release, 228 s under the sanitizers (four maps of 76 rows); the rows' solver runs there in the
// single rows below.
TEST_CASE("Melan's bound of a Hertz line contact: Johnson's limits without and with sliding traction",
          "[melan][slow]") {
  const auto [mu, johnson, depth] =
      GENERATE(table<Real, Real, Real>({{0.0, 4.00, 0.50}, {0.1, 3.56, 0.45}, {0.2, 3.20, 0.41}, {0.3, 2.89, 0.36}}));
  const MelanLimit limit = melan_limit(mcewen_rows(mu), ShakedownBound::Elastic);
  const MelanRowLimit& critical = limit.rows[limit.critical_row];
  std::cout << fmt::format("mu = {}: p0/k = {:.4f} (Johnson {:.2f}) at depth {:.2f} a, first yield {:.3f}\n", mu,
                           limit.load_factor(), johnson, critical.depth, limit.first_yield());
  // Johnson's values carry three digits; the grid's rows lie 0.02 a apart.
  CHECK(limit.load_factor() == Approx(johnson).epsilon(0.005));
  CHECK(critical.depth == Approx(depth).margin(0.021));
  // The residual stress keeps to the theorem's form: no vertical or shear component.
  CHECK(critical.residual_stress[1] == 0.0);
  CHECK(critical.residual_stress[3] == 0.0);
  if (mu == 0.0) CHECK(limit.first_yield() == Approx(3.1).epsilon(0.02));  // Johnson: von Mises first yield
}

TEST_CASE("Melan's bound without friction is the orthogonal shear's: lambda max|tau_xz| = k at 0.5 a", "[melan]") {
  // The orthogonal shear reverses between +-0.25 p0 as the load passes and no residual stress of
  // the form rho_xx(z) changes it; the rest of the stress a residual stress can absorb there.
  const MelanRow row = mcewen_row(0.5, 0.0);
  Real tau = 0.0;
  for (const Vec4& s : row.stress) tau = std::max(tau, std::abs(s[3]));
  const MelanRowLimit r = melan_row_limit(row, ShakedownBound::Elastic);
  CHECK(tau == Approx(0.25).epsilon(1e-4));
  // Exactly 1 where tau peaks (there sigma_x = sigma_z); the 0.01 a grid samples near it.
  CHECK(r.load_factor * tau == Approx(1.0).epsilon(1e-4));
  CHECK(r.load_factor > r.first_yield);
}

TEST_CASE("Melan's bound with a back-stress: never below the elastic limit, and the two bounds of a saturating law",
          "[melan]") {
  const Real mu = GENERATE(0.0, 0.2);
  const MelanRow row = mcewen_row(mu == 0.0 ? 0.5 : 0.44, mu);
  const Real elastic = melan_row_limit(row, ShakedownBound::Elastic).load_factor;
  const Real kinematic = melan_row_limit(row, ShakedownBound::Kinematic).load_factor;
  std::cout << fmt::format("mu = {}: elastic {:.4f}, kinematic {:.4f}\n", mu, elastic, kinematic);
  CHECK(kinematic >= elastic * (1.0 - 1e-8));
  if (mu == 0.0) CHECK(kinematic == Approx(elastic).epsilon(1e-4));  // the same reversing shear decides
  if (mu > 0.0) CHECK(kinematic > 1.05 * elastic);  // the back-stress absorbs the traction's mean shear
  // A back-stress that saturates at almost nothing leaves the residual stresses alone; one that
  // saturates far away is the unbounded one.
  const Real tight = melan_row_limit(mcewen_row(row.depth, mu, 1e-6), ShakedownBound::Kinematic).load_factor;
  const Real loose = melan_row_limit(mcewen_row(row.depth, mu, 1e6), ShakedownBound::Kinematic).load_factor;
  CHECK(tight == Approx(elastic).epsilon(1e-4));
  CHECK(loose == Approx(kinematic).epsilon(1e-4));
}

TEST_CASE("Melan's bound: a stress a shift cancels does not limit, a row without stress is skipped", "[melan]") {
  MelanRow row;
  for (int i = 0; i < 5; ++i) {
    row.x.push_back(i);
    row.stress.push_back(Vec4(-300.0, 0.0, 0.0, 0.0));  // uniform along the row: rho_xx = +300 cancels it
    row.yield_stress.push_back(250.0);
  }
  const MelanRowLimit r = melan_row_limit(row, ShakedownBound::Elastic);
  CHECK(r.status == MelanRowStatus::Unlimited);
  CHECK(r.first_yield == Approx(250.0 / 300.0));
  MelanRow empty = row;
  for (Vec4& s : empty.stress) s.setZero();
  const MelanLimit both = melan_limit({row, empty}, ShakedownBound::Elastic);
  CHECK(both.critical_row == -1);
  CHECK(both.rows[1].status == MelanRowStatus::Unlimited);
}

TEST_CASE("Melan's bound: the strictest row found without solving every row", "[melan]") {
  std::vector<MelanRow> rows;
  for (int j = 0; j <= 25; ++j) rows.push_back(mcewen_row(0.04 * j, 0.2));
  const MelanLimit fast = melan_limit(rows, ShakedownBound::Elastic, MelanSearch::StrictestRow);
  const MelanLimit all = melan_limit(rows, ShakedownBound::Elastic, MelanSearch::EveryRow);
  CHECK(fast.critical_row == all.critical_row);
  CHECK(fast.load_factor() == all.load_factor());
  int skipped = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    REQUIRE(all.rows[i].status == MelanRowStatus::Solved);
    CHECK(all.rows[i].load_factor >= all.load_factor());
    CHECK(all.rows[i].load_factor >= all.rows[i].first_yield * (1.0 - 1e-9));  // no shift is a shift
    if (fast.rows[i].status == MelanRowStatus::NotLimiting) {
      ++skipped;
      CHECK(fast.rows[i].first_yield >= fast.load_factor());
    }
  }
  CHECK(skipped > 0);
}

TEST_CASE("McEwen's stresses of the tests satisfy equilibrium (central differences)", "[melan]") {
  // McEwen's tau_xz has the opposite sign of the x-z frame's (z into the solid).
  const Real h = 1e-5;
  for (const Real mu : {0.0, 0.3})
    for (const auto& [x, z] : std::vector<std::pair<Real, Real>>{{0.3, 0.4}, {-1.2, 0.5}, {1.5, 0.8}}) {
      const auto s = [&](Real dx, Real dz) { return test::mcewen_stress(x + dx, z + dz, mu, kNu); };
      const Vec4 dx = (s(h, 0) - s(-h, 0)) / (2 * h), dz = (s(0, h) - s(0, -h)) / (2 * h);
      CHECK(dx[0] - dz[3] == Approx(0.0).margin(1e-6));
      CHECK(dz[1] - dx[3] == Approx(0.0).margin(1e-6));
    }
}
