// problems/wheel_rail_r260.toml is the source case's elastic wheel on the rail, and holds the R260
// rail steel of problems/ratchet_rail.toml: both checked here from the numbers of the source case
// (the scene's comment; docs/validation.md, Wheel on rail). Its passes are a study
// (docs/validation.md), not a test: ten of them take minutes.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "roller/analysis/hertz.hpp"
#include "roller/io/scene_loader.hpp"

using namespace roller;

TEST_CASE("the wheel-rail scene: the source's elastic wheel and creepage, the rail is R260", "[scenes][wheel_rail]") {
  const Scene scene = load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/wheel_rail_r260.toml");
  const Scene rail = load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/ratchet_rail.toml");
  // The source: 18222 N/mm, a steel wheel (E 210 GPa, nu 0.3) of radius 333.26 mm, its bore 200 mm.
  const Real load = 18222.0;
  REQUIRE(scene.roller->elastic());
  CHECK(scene.roller->radius == 333.26);
  CHECK(scene.roller->inner_radius == 100.0);
  CHECK(scene.roller->youngs_modulus == 210000.0);
  CHECK(scene.roller->poisson_ratio == 0.3);
  const HertzSolution wheel = hertz_line_contact(load, scene.roller->radius, scene.contact_modulus());
  CHECK(wheel.half_width == Approx(8.236).epsilon(1e-3));
  CHECK(wheel.peak == Approx(1408.6).epsilon(1e-3));
  // The roller touches the rail's top at the start.
  REQUIRE(scene.roller->start_centre);
  CHECK(scene.roller->start_centre->y() - scene.roller->radius == Approx(scene.mesh.height).margin(1e-9));
  // The travel segment's load and the source's creepage, beyond mu a / R: full slip, mu = 0.5.
  const PathSegment& travel = scene.roller->path.at(1);
  REQUIRE(travel.fy);
  CHECK(*travel.fy == load);
  CHECK_FALSE(travel.fx);
  CHECK_FALSE(travel.q_over_p);
  CHECK(travel.slip_start == 0.015);
  CHECK(travel.slip_end == 0.015);
  CHECK(scene.contact.friction == 0.5);
  CHECK(travel.slip_end > scene.contact.friction * wheel.half_width / scene.roller->radius);
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
