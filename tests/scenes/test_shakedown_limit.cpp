// Melan's bound of a shipped scene from its elastic press (roller shakedown-limit; docs/validation.md,
// "Melan's bound"): the deep strip of problems/shakedown_p45.toml (47a above a bonded base) against
// Johnson's limits of the half-plane, the back-stress bound against the same theorem on McEwen's
// stresses, the surface limit 1/mu as the mesh is refined, and the scene errors.
#include <catch2/catch.hpp>

#include <cmath>
#include <iostream>
#include <string>

#include <fmt/format.h>

#include "../support/mcewen.hpp"
#include "roller/core/error.hpp"
#include "roller/io/scene_loader.hpp"
#include "roller/steady/shakedown_limit.hpp"

using namespace roller;
using Catch::Contains;

namespace {

Scene shipped(const std::string& name, const std::vector<SceneOverride>& overrides = {}) {
  return load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/" + name + ".toml", overrides);
}

ShakedownLimitResult limit_of(const Scene& scene, Real traction) {
  ShakedownLimitSettings s;
  s.traction = traction;
  return compute_shakedown_limit(scene, s);
}

// The back-stress bound of the half-plane, from McEwen's stresses (k = 1, rows every 0.01 a).
Real mcewen_kinematic_limit(Real mu) {
  std::vector<MelanRow> rows;
  for (int j = 20; j <= 70; ++j) {
    MelanRow row;
    row.depth = 0.01 * j;
    for (int i = 0; i <= 800; ++i) {
      row.x.push_back(-4.0 + 0.01 * i);
      row.stress.push_back(test::mcewen_stress(row.x.back(), row.depth, mu, 0.3));
      row.yield_stress.push_back(std::sqrt(3.0));
    }
    rows.push_back(row);
  }
  return melan_limit(rows, ShakedownBound::Kinematic).load_factor();
}

// Melan's bound of the half-plane under the Hertz pressure and Carter's traction Q = ratio P (k = 1,
// rows every 0.01 a from 0.2 a to 0.7 a): McEwen's sliding field less the stick zone's, a semi-ellipse
// of half-width c and peak mu c/a, whose field is the unit traction's scaled by c in x, z and
// stress. McEwen's traction (mu > 0) points to -x, so the stick zone lies at x = -(a - c).
Real carter_half_plane_limit(Real mu, Real ratio) {
  const Real c = std::sqrt(1.0 - ratio / mu), d = -(1.0 - c);
  std::vector<MelanRow> rows;
  for (int j = 20; j <= 70; ++j) {
    MelanRow row;
    row.depth = 0.01 * j;
    for (int i = 0; i <= 800; ++i) {
      const Real x = -4.0 + 0.01 * i, z = row.depth;
      const Vec4 unit_traction =
          test::mcewen_stress((x - d) / c, z / c, 1.0, 0.3) - test::mcewen_stress((x - d) / c, z / c, 0.0, 0.3);
      row.x.push_back(x);
      row.stress.push_back(test::mcewen_stress(x, z, mu, 0.3) - mu * c * unit_traction);
      row.yield_stress.push_back(std::sqrt(3.0));
    }
    rows.push_back(row);
  }
  return melan_limit(rows, ShakedownBound::Elastic).load_factor();
}

}  // namespace

TEST_CASE("shakedown-limit of the deep strip: Johnson's limits without and with sliding traction",
          "[scenes][melan][slow]") {
  const auto [mu, johnson] = GENERATE(table<Real, Real>({{0.0, 4.00}, {0.1, 3.56}, {0.2, 3.20}, {0.3, 2.89}}));
  const ShakedownLimitResult r = limit_of(shipped("shakedown_p45"), mu);
  const MelanRowLimit& c = r.elastic.rows[r.elastic.critical_row];
  std::cout << fmt::format("p45, q = {} p: p0/k = {:.4f} (Johnson {:.2f}) at {:.3f} a; first yield {:.3f}\n", mu,
                           r.p0_over_k(r.elastic), johnson, c.depth / r.load.half_width,
                           r.elastic.first_yield() * r.scene_p0_over_k(r.elastic));
  CHECK(r.scene_p0_over_k(r.elastic) == Approx(4.5).epsilon(1e-4));  // the scene's own load
  CHECK(r.p0_over_k(r.elastic) == Approx(johnson).epsilon(0.01));
  CHECK(c.depth / r.load.half_width == Approx(0.5).margin(0.2));  // below the surface, near 0.5 a
  CHECK_FALSE(r.kinematic);                                       // perfectly plastic: no back-stress bound
}

// A steel roller on the steel strip: the same force on half the modulus, so Hertz's p0 falls by
// sqrt(2) and the contact widens as much; the strip's stresses under the semi-elliptic pressure are
// the half-plane's at any p0, so Johnson's limit p0/k = 4 holds as for the rigid roller.
TEST_CASE("shakedown-limit with an elastic roller: Johnson's limit in the two bodies' p0",
          "[scenes][melan][elastic_roller][slow]") {
  const ShakedownLimitResult rigid = limit_of(shipped("shakedown_p45"), 0.0);
  const ShakedownLimitResult steel =
      limit_of(shipped("shakedown_p45", {{"roller.E", "2.1e5"}, {"roller.nu", "0.3"}}), 0.0);
  std::cout << fmt::format(
      "p45 frictionless, steel roller: P = {:.6g} N/mm, a = {:.4g} mm, p0/k = {:.4f} (rigid {:.4f})\n", steel.load.load,
      steel.load.half_width, steel.p0_over_k(steel.elastic), rigid.p0_over_k(rigid.elastic));
  CHECK(steel.load.load == Approx(rigid.load.load).epsilon(1e-6));  // the scene's force
  CHECK(steel.load.hertz_peak == Approx(rigid.load.hertz_peak / std::sqrt(2.0)).epsilon(1e-6));
  CHECK(steel.load.half_width == Approx(rigid.load.half_width * std::sqrt(2.0)).epsilon(1e-6));
  // The press's own peak pressure is the two-body contact's.
  CHECK(steel.load.computed_peak == Approx(steel.load.hertz_peak).epsilon(0.02));
  CHECK(steel.p0_over_k(steel.elastic) == Approx(4.0).epsilon(0.01));
  CHECK(steel.p0_over_k(steel.elastic) == Approx(rigid.p0_over_k(rigid.elastic)).epsilon(0.01));
}

TEST_CASE("shakedown-limit with kinematic hardening: the back-stress bound of the half-plane",
          "[scenes][melan][slow]") {
  const Real mu = 0.2;
  const ShakedownLimitResult r = limit_of(shipped("shakedown_kinematic_p45"), mu);
  REQUIRE(r.kinematic);
  const Real half_plane = mcewen_kinematic_limit(mu);
  std::cout << fmt::format("kinematic p45, q = {} p: elastic {:.4f}, kinematic {:.4f}; half-plane {:.4f}\n", mu,
                           r.p0_over_k(r.elastic), r.p0_over_k(*r.kinematic), half_plane);
  CHECK(r.p0_over_k(*r.kinematic) == Approx(half_plane).epsilon(0.01));
  CHECK(r.p0_over_k(*r.kinematic) > 1.1 * r.p0_over_k(r.elastic));
}

TEST_CASE("shakedown-limit under a strong traction: the surface row governs, Johnson's 1/mu where nu = 0.5",
          "[scenes][melan][slow]") {
  // The surface itself is a row of the bound (the half-plane's surface stress under the press's
  // contact, fitted as an ellipse): the limit no longer waits for a finer top row. Before it the
  // top row's centroids, half an element down, gave 2.19 at mu = 0.5 (+9.5 %, unsafe).
  for (const Real mu : {0.4, 0.5}) {
    const ShakedownLimitResult r = limit_of(shipped("shakedown_p45", {{"material.nu", "0.49"}}), mu);
    const MelanRowLimit& c = r.elastic.rows[r.elastic.critical_row];
    CHECK(c.depth == 0.0);
    CHECK(r.p0_over_k(r.elastic) == Approx(1.0 / mu).epsilon(0.01));
    // With nu = 0.3 the out-of-plane stress nu (sigma_xx + sigma_yy), which varies along the whole
    // contact where the in-plane shear is critical, lowers it: McEwen's surface row through the same
    // bound (python/tests/test_line_contact_shakedown.py: 2.315 and 1.881 by a grid search).
    MelanRow surface;
    for (Real x = -4.0; x <= 4.0; x += 0.005) {
      Vec4 s = test::mcewen_stress(x, 0.0, mu, 0.3);
      surface.x.push_back(x);
      surface.stress.push_back(s);
      surface.yield_stress.push_back(std::sqrt(3.0));  // k = 1: the load factor is p0/k
    }
    const Real half_plane = melan_row_limit(surface, ShakedownBound::Elastic).load_factor;
    CHECK(half_plane < 0.95 / mu);
    const ShakedownLimitResult steel = limit_of(shipped("shakedown_p45"), mu);
    CHECK(steel.elastic.rows[steel.elastic.critical_row].depth == 0.0);
    CHECK(steel.p0_over_k(steel.elastic) == Approx(half_plane).epsilon(0.01));
  }
}

TEST_CASE("shakedown-limit of rolling under a horizontal force: Carter's traction, the half-plane's limit",
          "[scenes][melan][slow]") {
  // mu = 0.2, fx = -Q along +x: Carter's stick zone c = a sqrt(1 - Q/(mu P)) at the leading edge.
  auto rolling_under = [](Real q_over_p) {
    return shipped("shakedown_p45",
                   {{"contact.friction", "0.2"},
                    {"roller.path", fmt::format("[{{ steps = [1, 3], fy = 7249.8292 }}, {{ steps = [4, 19], dx = 16.0, "
                                                "fy = 7249.8292, fx = {} }}, {{ steps = [20, 21], dy = 0.3 }}]",
                                                -q_over_p * 7249.8292)}});
  };
  for (const Real q_over_p : {0.1, 0.15}) {
    const ShakedownLimitResult r = compute_shakedown_limit(rolling_under(q_over_p), {});
    CHECK(r.load.shape == TractionShape::Carter);
    CHECK(r.load.traction == Approx(q_over_p).epsilon(1e-12));
    CHECK(r.load.stick_half_width == Approx(std::sqrt(1.0 - q_over_p / 0.2) * r.load.half_width).epsilon(1e-12));
    const Real half_plane = carter_half_plane_limit(0.2, q_over_p);
    const ShakedownLimitResult uniform = limit_of(shipped("shakedown_p45"), q_over_p);
    std::cout << fmt::format("p45, mu 0.2, Q = {} P: Carter {:.4f} (half-plane {:.4f}), uniform q = {} p {:.4f}\n",
                             q_over_p, r.p0_over_k(r.elastic), half_plane, q_over_p,
                             uniform.p0_over_k(uniform.elastic));
    CHECK(r.p0_over_k(r.elastic) == Approx(half_plane).epsilon(0.01));
  }
  // The traction ratio q_over_p is the same load as its fx: the same bound to the last bit.
  const ShakedownLimitResult by_ratio = compute_shakedown_limit(
      shipped("shakedown_p45", {{"contact.friction", "0.2"}, {"roller.path[1].q_over_p", "0.15"}}), {});
  const ShakedownLimitResult by_force = compute_shakedown_limit(rolling_under(0.15), {});
  CHECK(by_ratio.load.traction == 0.15);
  CHECK(by_ratio.load.shape == TractionShape::Carter);
  CHECK(by_ratio.p0_over_k(by_ratio.elastic) == Approx(by_force.p0_over_k(by_force.elastic)).epsilon(1e-12));
  // Q = mu P leaves no stick zone: Carter's traction is the sliding one, node for node.
  const ShakedownLimitResult carter_sliding = compute_shakedown_limit(rolling_under(0.2), {});
  const ShakedownLimitResult sliding = limit_of(shipped("shakedown_p45"), 0.2);
  CHECK(carter_sliding.load.stick_half_width == 0.0);
  CHECK(carter_sliding.p0_over_k(carter_sliding.elastic) == Approx(sliding.p0_over_k(sliding.elastic)).epsilon(1e-9));
}

TEST_CASE("shakedown-limit: scenes it cannot take are input errors naming the cause", "[scenes][melan]") {
  const std::string file = std::string(ROLLER_SOURCE_DIR) + "/problems/shakedown_p45.toml";
  SECTION("a roller that only presses") {
    const Scene s = load_scene(file, {{"roller.path", "[{ steps = [1, 21], fy = 7249.8 }]"}});
    CHECK_THROWS_WITH(limit_of(s, 0.0), Contains("needs a segment that rolls or slides"));
  }
  SECTION("an elastic strip") {
    Scene s = load_scene(file);
    s.material.plastic = false;
    CHECK_THROWS_WITH(compute_shakedown_limit(s, {}), Contains("the strip is elastic"));
  }
  SECTION("rolling with creep and no traction given") {
    const Scene s = load_scene(file, {{"roller.path",
                                       "[{ steps = [1, 3], fy = 7249.8 }, { steps = [4, 19], dx = 16.0, fy = 7249.8, "
                                       "slip = 0.01 }, { steps = [20, 21], dy = 0.3 }]"}});
    CHECK_THROWS_WITH(compute_shakedown_limit(s, {}), Contains("--traction"));
  }
}
