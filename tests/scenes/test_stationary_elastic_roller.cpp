// The stationary pass with an elastic roller (docs/model.md, Stationary pass; Elastic roller): the
// roller's rim compliance at the contact's nodes joins the strip's in the condensed contact. On
// problems/carter.toml's elastic strip (nu = 0.49) under P = 10 600 N/mm: two-body Hertz, a very
// stiff roller against the rigid one, and Carter's steady rolling with identical materials (the
// roller of the strip's E and nu: no normal-tangential coupling), with the two-body a.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "../support/stick_zone.hpp"
#include "roller/analysis/hertz.hpp"
#include "roller/driver/simulation.hpp"
#include "roller/io/scene_loader.hpp"

using namespace roller;

namespace {

constexpr Real kForce = 10600.0;

// One stationary pass of carter.toml, the travel segment's own keys `travel`, the roller's E and nu
// (E = 0: rigid).
Simulation pass(const std::string& travel, Real roller_e, Real roller_nu, Real friction = 0.15) {
  std::vector<SceneOverride> o{
      {"passes.method", "\"stationary\""},
      {"passes.count", "1"},
      {"contact.friction", fmt::format("{}", friction)},
      {"roller.path",
       fmt::format("[{{steps=[1,4], fy={0}}}, {{steps=[5,94], dx=34.0, fy={0}, {1}}}]", kForce, travel)}};
  if (roller_e > 0.0) {
    o.push_back({"roller.E", fmt::format("{}", roller_e)});
    o.push_back({"roller.nu", fmt::format("{}", roller_nu)});
  }
  Simulation sim(load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/carter.toml", o));
  const Simulation::StepRecord r = sim.advance_step(1);
  INFO(r.message);
  REQUIRE(r.converged());
  return sim;
}

}  // namespace

// a and p0 of the ellipse fitted to the nodal forces (tests/support/stick_zone.hpp).
TEST_CASE("stationary elastic roller: two-body Hertz half-width and peak pressure within 0.5 %",
          "[scenes][stationary][elastic_roller]") {
  for (auto [e, nu] : {std::pair{2.1e5, 0.3}, {7.0e4, 0.33}}) {
    const Simulation sim = pass("slip=0.0", e, nu, 0.0);
    const test::StickZone z = test::measure_stick_zone(sim.state().contact, 0.0);
    const HertzSolution h = hertz_line_contact(kForce, sim.scene().roller->radius, sim.scene().contact_modulus());
    INFO("E_roller " << e << ": a = " << z.a << " (Hertz " << h.half_width << "), p0 = " << z.contact.peak << " (Hertz "
                     << h.peak << ")");
    CHECK(force_on_roller(sim.state().contact).y() == Approx(kForce).epsilon(1e-9));
    CHECK(std::abs(z.a / h.half_width - 1.0) < 0.005);
    CHECK(std::abs(z.contact.peak / h.peak - 1.0) < 0.005);
  }
}

TEST_CASE("stationary elastic roller: E = 1e9 MPa gives the rigid roller's contact to 1e-3",
          "[scenes][stationary][elastic_roller]") {
  const Simulation rigid = pass("slip=0.0013", 0.0, 0.0), stiff = pass("slip=0.0013", 1e9, 0.3);
  REQUIRE(rigid.state().contact.size() == stiff.state().contact.size());
  for (std::size_t i = 0; i < rigid.state().contact.size(); ++i) {
    INFO("node at x = " << rigid.state().contact[i].position.x());
    CHECK((stiff.state().contact[i].force - rigid.state().contact[i].force).norm() <= 1e-3 * 3000.0);
  }
  CHECK(stiff.state().pose.centre.y() < rigid.state().pose.centre.y());  // the rim gives a little
}

TEST_CASE("stationary elastic roller: Carter's steady rolling with identical materials",
          "[scenes][stationary][elastic_roller][friction]") {
  // The roller of the strip's E = 2.1e5 MPa and nu = 0.49 under Q = 0.64 mu P: the creep and the stick
  // zone against Carter's with the two-body a (E* = E / (2 (1 - nu^2))).
  const Real mu = 0.15, q = 0.64 * mu * kForce;
  const Simulation sim = pass(fmt::format("fx={}", -q), 2.1e5, 0.49);
  const Real radius = sim.scene().roller->radius;
  const test::StickZone z = test::measure_stick_zone(sim.state().contact, mu);
  const HertzSolution hertz = hertz_line_contact(kForce, radius, sim.scene().contact_modulus());
  const Real creep = sim.state().pass_records.back().creep;
  const Real creep_carter = mu * hertz.half_width / radius * (1.0 - std::sqrt(1.0 - 0.64));
  INFO("a = " << z.a << " (two-body Hertz " << hertz.half_width << "), creep " << creep << " (Carter " << creep_carter
              << "), c = " << z.c << " (Carter " << z.a * std::sqrt(1.0 - 0.64) << ")");
  // Measured (a and c from the fitted ellipses): a -0.11 %, the creep -0.97 %, c -3.4 %. At refine 2
  // and 3 a -0.06 / -0.07 %, the creep -0.70 / -0.07 %, c -3.5 / -3.5 %: the stick zone's shortfall
  // is not the mesh's, and not understood (docs/validation.md, Elastic roller).
  CHECK(force_on_roller(sim.state().contact).x() == Approx(-q).epsilon(1e-9));
  CHECK(std::abs(z.a / hertz.half_width - 1.0) < 0.01);
  CHECK(std::abs(creep / creep_carter - 1.0) < 0.02);
  CHECK(std::abs(z.c / (z.a * std::sqrt(1.0 - 0.64)) - 1.0) < 0.04);
  CHECK(std::abs((z.d_abs + z.c) - (z.contact.centre + z.a)) < 0.2);  // at the leading edge, to a node
}
