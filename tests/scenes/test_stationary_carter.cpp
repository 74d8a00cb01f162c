// The stationary pass on the roller's contact with Coulomb friction found (docs/model.md,
// Stationary pass): Carter's steady rolling on problems/carter.toml's elastic strip (nu = 0.49,
// where the normal and tangential problems uncouple), the roller held at P and rolled with a
// prescribed creep, under a horizontal force (the creep an outcome), and sliding. The zones are
// measured as for the transient runs (tests/support/stick_zone.hpp).
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <fmt/format.h>

#include "../support/stick_zone.hpp"
#include "roller/driver/simulation.hpp"
#include "roller/io/scene_loader.hpp"

using namespace roller;

namespace {

constexpr Real kForce = 10600.0;  // P [N/mm]: about the 0.1 mm press of carter.toml

// One stationary pass of carter.toml with the travel segment's own keys `travel` (after dx, fy).
Simulation carter_pass(const std::string& travel, int refine = 1) {
  Simulation sim(
      load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/carter.toml",
                 {{"passes.method", "\"stationary\""},
                  {"passes.count", "1"},
                  {"mesh.refine", std::to_string(refine)},
                  {"roller.path",
                   fmt::format("[{{steps=[1,4], fy={0}}}, {{steps=[5,94], dx=34.0, fy={0}, {1}}}]", kForce, travel)}}));
  REQUIRE(sim.advance_step(1).converged());
  return sim;
}

}  // namespace

TEST_CASE("stationary Carter: a prescribed creep carries Carter's Q, the stick zone at the leading edge",
          "[scenes][stationary][friction]") {
  const Simulation sim = carter_pass("slip=0.0013");
  const Real mu = sim.scene().contact.friction, radius = sim.scene().roller->radius;
  const Vec2 f = force_on_roller(sim.state().contact);
  const test::StickZone z = test::measure_stick_zone(sim.state().contact, mu);
  const Real q_ratio = std::abs(f.x()) / (mu * f.y());
  // Carter: c/a = 1 - s R / (mu a), Q/(mu P) = 1 - (c/a)^2, with the measured a.
  const Real c_carter = z.a - 0.0013 * radius / mu;
  const Real q_carter = 1.0 - (c_carter / z.a) * (c_carter / z.a);
  INFO("a = " << z.a << ", Q/(mu P) = " << q_ratio << " (Carter " << q_carter << "), c = " << z.c << " (Carter "
              << c_carter << "), the stick zone's leading edge " << z.d_abs + z.c - z.contact.centre);
  CHECK(f.y() == Approx(kForce).epsilon(1e-9));
  CHECK(f.x() < 0.0);                                 // the roller turns slower than it rolls: the strip holds it back
  CHECK(std::abs(q_ratio / q_carter - 1.0) < 0.035);  // measured +2.9 %
  CHECK(std::abs(z.c / c_carter - 1.0) < 0.02);
  CHECK(std::abs((z.d_abs + z.c) - (z.contact.centre + z.a)) < 0.2);  // at the leading edge, to a node
  CHECK(z.n_slip > 0);
  // Coulomb's law node by node: |F_T| <= mu F_N where it sticks, = where it slips, against the slip.
  for (const NodeContactRecord& c : sim.state().contact) {
    const Real ft = c.contact.tangential_force, fn = c.contact.normal_force;
    if (c.contact.status == ContactStatus::Stick) {
      CHECK(std::abs(ft) <= mu * fn * (1.0 + 1e-12));
      CHECK(std::abs(c.contact.slip) <= 1e-10);
    }
    if (c.contact.status == ContactStatus::Slip) {
      CHECK(std::abs(ft) == Approx(mu * fn).epsilon(1e-12));
      CHECK(ft * c.contact.slip < 0.0);
    }
  }
}

TEST_CASE("stationary Carter: under a horizontal force the creep is an outcome on Carter's law",
          "[scenes][stationary][friction]") {
  const Real mu = 0.15, q = 0.64 * mu * kForce;
  Real last_error = 1.0;
  for (const int refine : {1, 2}) {
    const Simulation sim = carter_pass(fmt::format("fx={}", -q), refine);
    const Real radius = sim.scene().roller->radius;
    const Vec2 f = force_on_roller(sim.state().contact);
    const test::StickZone z = test::measure_stick_zone(sim.state().contact, mu);
    const Real creep = sim.state().pass_records.back().creep;
    const Real creep_carter = mu * z.a / radius * (1.0 - std::sqrt(1.0 - q / (mu * kForce)));
    const Real error = std::abs(creep / creep_carter - 1.0);
    INFO("refine " << refine << ": a = " << z.a << ", creep " << creep << " (Carter " << creep_carter
                   << "), c = " << z.c << " (Carter " << z.a * std::sqrt(1.0 - 0.64) << ")");
    CHECK(f.x() == Approx(-q).epsilon(1e-9));
    CHECK(f.y() == Approx(kForce).epsilon(1e-9));
    CHECK(error < 0.8 * last_error);  // converging with the node spacing (measured 3.7 %, then 2.8 %)
    CHECK(error < 0.04);
    CHECK(std::abs(z.c / (z.a * std::sqrt(1.0 - 0.64)) - 1.0) < 0.02);
    last_error = error;
  }
}

TEST_CASE("stationary Carter: a sliding roller slips everywhere, its traction mu p against the slip",
          "[scenes][stationary][friction]") {
  const Simulation sim = carter_pass("slip=1.0");
  const Real mu = sim.scene().contact.friction;
  Real normal = 0.0, tangential = 0.0;
  for (const NodeContactRecord& c : sim.state().contact) {
    if (c.contact.status == ContactStatus::Open) continue;
    CHECK(c.contact.status == ContactStatus::Slip);
    CHECK(c.contact.slip < 0.0);  // the strip slides back under the roller
    normal += c.contact.normal_force;
    tangential += c.contact.tangential_force;
  }
  CHECK(tangential == Approx(mu * normal).epsilon(1e-12));
  CHECK(force_on_roller(sim.state().contact).y() == Approx(kForce).epsilon(1e-9));
}
