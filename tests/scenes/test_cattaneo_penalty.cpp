// Cattaneo–Mindlin partial slip with the penalty backend: stick and slip zones exist and the
// stick zone matches c/a = sqrt(1 - Q/(mu P)).
#include <catch2/catch.hpp>

#include <cmath>

#include "../support/run_scene.hpp"
#include "roller/analysis/contact_zones.hpp"

using namespace roller;

TEST_CASE("Cattaneo (penalty): stick zone c/a = sqrt(1 - Q/(mu P))", "[contact][cattaneo][slow]") {
  const Simulation sim = test::run_scene("cattaneo", {{"mesh.refine", "2"}, {"contact.backend", "\"penalty\""}});
  const Real mu = sim.scene().contact.friction;
  std::vector<Real> x;
  std::vector<bool> in_contact, stick;
  int n_stick = 0, n_slip = 0;
  for (const auto& c : sim.state().contact) {
    x.push_back(c.position.x());
    in_contact.push_back(c.contact.status != ContactStatus::Open);
    stick.push_back(c.contact.status == ContactStatus::Stick);
    n_stick += c.contact.status == ContactStatus::Stick;
    n_slip += c.contact.status == ContactStatus::Slip;
  }
  CHECK(n_stick > 0);
  CHECK(n_slip > 0);
  const Vec2 f = force_on_roller(sim.state().contact);
  const Real q_ratio = std::abs(f.x()) / (mu * f.y());
  const ZoneExtent a = zone_extent(x, in_contact);
  const ZoneExtent c = zone_extent(x, stick);
  const Real expected = std::sqrt(1.0 - q_ratio);
  INFO("Q/(mu P) = " << q_ratio << ", a = " << a.half_width() << ", c = " << c.half_width()
                     << ", c/a = " << c.half_width() / a.half_width() << " (Cattaneo " << expected << ")");
  CHECK(q_ratio > 0.3);
  CHECK(q_ratio < 0.7);
  // Zone boundaries are resolved to half a node spacing on each side (contact_zones.hpp).
  CHECK(std::abs(c.half_width() / a.half_width() - expected) < 0.08);
}

TEST_CASE("frictionless rigid translation of strip and roller together gives no tangential force", "[contact]") {
  // Press, then translate the strip's base and the roller together by 0.05 mm in x: the relative
  // configuration is unchanged, so the contact forces must not change and no tangential force
  // may appear.
  const std::string text = R"(
kinematics = "small"
[mesh]
length = 40.0
height = 10.0
nx = 40
ny = 10
[material]
E = 2.1e5
nu = 0.3
[steps]
count = 4
[[displacement]]
nodes = "bottom"
y = 0.0
x = { value = 0.05, ramp = [3, 4] }
[roller]
radius = 50.0
centre = [20.0, 60.0]
[[roller.path]]
steps = [1, 2]
dy = -0.02
[[roller.path]]
steps = [3, 4]
dx = 0.05
slip = 1.0
[contact]
friction = 0.0
)";
  Simulation sim(parse_scene(text, "translation.toml"));
  for (int step = 1; step <= 2; ++step) REQUIRE(sim.advance_step(step).converged());
  const Vec2 before = force_on_roller(sim.state().contact);
  for (int step = 3; step <= 4; ++step) REQUIRE(sim.advance_step(step).converged());
  const Vec2 after = force_on_roller(sim.state().contact);
  REQUIRE(before.y() > 0.0);
  CHECK(std::abs(after.x()) < 1e-6 * after.y());
  CHECK((after - before).norm() < 1e-6 * before.norm());
  for (const auto& c : sim.state().contact) CHECK(c.contact.tangential_force == 0.0);
}
