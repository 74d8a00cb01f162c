// problems/wheel_rail_r260.toml stands for an elastic wheel on the rail by a rigid roller with the
// same Hertz contact, and holds the R260 rail steel of problems/ratchet_rail.toml: both checked
// here from the numbers of the source case (the scene's comment; docs/validation.md, Wheel on rail).
// Its passes are a study (docs/validation.md), not a test: ten of them take minutes.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "roller/analysis/hertz.hpp"
#include "roller/io/scene_loader.hpp"

using namespace roller;

TEST_CASE("the wheel-rail scene: the rigid roller has the elastic wheel's Hertz contact, the rail is R260",
          "[scenes][wheel_rail]") {
  const Scene scene = load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/wheel_rail_r260.toml");
  const Scene rail = load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/ratchet_rail.toml");
  // The source: 18222 N/mm, a steel wheel (E 210 GPa, nu 0.3) of radius 333.26 mm on the rail.
  const Real load = 18222.0, wheel_radius = 333.26, wheel_modulus = 210000.0 / (1.0 - 0.09);
  const Real two_body = 1.0 / (1.0 / scene.contact_modulus() + 1.0 / wheel_modulus);
  const HertzSolution wheel = hertz_line_contact(load, wheel_radius, two_body);
  const HertzSolution roller = hertz_line_contact(load, scene.roller->radius, scene.contact_modulus());
  CHECK(roller.half_width == Approx(wheel.half_width).epsilon(1e-6));
  CHECK(roller.peak == Approx(wheel.peak).epsilon(1e-6));
  CHECK(wheel.half_width == Approx(8.236).epsilon(1e-3));
  CHECK(wheel.peak == Approx(1408.6).epsilon(1e-3));
  // The travel segment's load and its full-slip traction, mu = 0.5.
  const PathSegment& travel = scene.roller->path.at(1);
  REQUIRE(travel.fy);
  CHECK(*travel.fy == load);
  REQUIRE(travel.q_over_p);
  CHECK(*travel.q_over_p == scene.contact.friction);
  CHECK(scene.contact.friction == 0.5);
  // The rail steel verbatim.
  CHECK(scene.material.yield_stress == rail.material.yield_stress);
  CHECK(scene.material.n_back_stresses() == 6);
  for (int i = 0; i < 6; ++i) {
    CHECK(scene.material.back_stress_law(i).modulus == rail.material.back_stress_law(i).modulus);
    CHECK(scene.material.back_stress_law(i).recovery == rail.material.back_stress_law(i).recovery);
  }
  CHECK(scene.material.voce_saturation == rail.material.voce_saturation);
  CHECK(scene.material.voce_rate == rail.material.voce_rate);
  CHECK(scene.passes.count >= 10);
  REQUIRE(scene.fatigue);
}
