// A roller under a prescribed force (roller.path fy): Hertz's press-in reaches the force within
// the solver tolerance and leaves the same contact as the depth-controlled press-in that reached
// the same force, with both backends; the offset survives a lift; loads nothing carries stop.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "../support/run_scene.hpp"
#include "roller/analysis/hertz.hpp"

using namespace roller;
using test::run_scene;

namespace {

Real fitted_half_width(const Simulation& sim) {
  std::vector<PressureSample> samples = sim.pressure_profile();
  std::sort(samples.begin(), samples.end(), [](const auto& a, const auto& b) { return a.x < b.x; });
  const Real e_star = sim.scene().material.plane_strain_modulus();
  return compare_with_hertz(samples, sim.roller_force().y(), sim.scene().roller->radius, e_star).half_width;
}

}  // namespace

TEST_CASE("force control: Hertz under a prescribed force matches the depth-controlled press-in", "[contact][force]") {
  for (const std::string backend : {"ipopt", "penalty"}) {
    INFO(backend);
    // One increment each: the strip's rate form makes the state depend slightly on the loading
    // path (ramping the force or the depth differ by 1e-5 in a after 4 steps), one step compares
    // like with like.
    const std::vector<SceneOverride> base{{"contact.backend", "\"" + backend + "\""}, {"steps.count", "1"}};
    std::vector<SceneOverride> pressed = base;
    pressed.push_back({"roller.path", "[{steps=[1,1], dy=-0.1}]"});
    const Simulation depth = run_scene("hertz", pressed);
    const Real p = depth.roller_force().y();
    std::vector<SceneOverride> loaded = base;
    loaded.push_back({"roller.path", fmt::format("[{{steps=[1,1], fy={:.17g}}}]", p)});
    const Simulation force = run_scene("hertz", loaded);
    // The force reached: the tolerance is 1e-6 of the largest prescribed force.
    CHECK(std::abs(force.roller_force().y() - p) <= 1e-6 * p);
    CHECK(force.prescribed_force(1).value() == p);
    // The same indentation and contact: centre height within 1e-5 of the 0.1 mm press-in, the
    // same nodes in contact, the fitted half-width within 1e-6.
    CHECK(force.pose().centre.y() == Approx(depth.pose().centre.y()).margin(1e-6));
    CHECK(force.load_offset() == Approx(-0.1).margin(1e-6));
    const Real a_depth = fitted_half_width(depth), a_force = fitted_half_width(force);
    CHECK(a_force == Approx(a_depth).epsilon(1e-6));
    REQUIRE(force.contact().size() == depth.contact().size());
    for (std::size_t i = 0; i < depth.contact().size(); ++i)
      CHECK(force.contact()[i].contact.status == depth.contact()[i].contact.status);
  }
}

TEST_CASE("force control: the offset is kept after the loaded segment, a lift starts from it", "[contact][force]") {
  // Press to P over steps 1-2, hold the position in step 3 (no segment), lift 0.2 mm in step 4.
  const Simulation sim =
      run_scene("hertz", {{"roller.path", "[{steps=[1,2], fy=4000.0}, {steps=[4,4], dy=0.2}]"}, {"steps.count", "4"}});
  // After the lift the roller is 0.2 mm above where the load left it, i.e. above the surface.
  CHECK(sim.roller_force().y() == Approx(0.0).margin(1e-6 * 4000.0));
  CHECK(sim.pose().centre.y() == Approx(200.0 + sim.load_offset() + 0.2).margin(1e-12));
  CHECK(sim.load_offset() < -0.05);
  CHECK_FALSE(sim.prescribed_force(3).has_value());
  CHECK_FALSE(sim.prescribed_force(4).has_value());
}

TEST_CASE("force control: a load nothing carries stops the step with a message", "[contact][force]") {
  // The roller beside the strip: no node ever touches it.
  Simulation sim(load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/hertz.toml",
                            {{"roller.centre", "[500.0, 200.0]"}, {"roller.path", "[{steps=[1,4], fy=1000.0}]"}}));
  const Simulation::StepResult r = sim.advance_step(1);
  CHECK_FALSE(r.converged);
  CHECK_THAT(r.message, Catch::Contains("nothing carries the load"));
}

TEST_CASE("force control: the prescribed force ramps from the last earlier force segment", "[contact][force]") {
  RollerSpec spec;
  spec.path.resize(4);
  const int steps[4][2] = {{1, 4}, {5, 6}, {7, 8}, {9, 9}};
  for (int i = 0; i < 4; ++i) {
    spec.path[i].first_step = steps[i][0];
    spec.path[i].last_step = steps[i][1];
  }
  spec.path[0].fy = 400.0;  // 0 -> 400 over steps 1-4
  spec.path[1].dx = 2.0;    // motion: no force control
  spec.path[2].fy = 200.0;  // from 400 (the last force segment) down to 200
  spec.path[3].friction = 0.3;
  CHECK(prescribed_vertical_force(spec, 1.0).value() == Approx(100.0));
  CHECK(prescribed_vertical_force(spec, 2.5).value() == Approx(250.0));  // within a cut step
  CHECK(prescribed_vertical_force(spec, 4.0).value() == Approx(400.0));
  CHECK_FALSE(prescribed_vertical_force(spec, 5.0).has_value());
  CHECK_FALSE(prescribed_vertical_force(spec, 6.0).has_value());
  CHECK(prescribed_vertical_force(spec, 7.0).value() == Approx(300.0));
  CHECK(prescribed_vertical_force(spec, 8.0).value() == Approx(200.0));
  CHECK_FALSE(prescribed_vertical_force(spec, 9.0).has_value());
  CHECK_FALSE(prescribed_vertical_force(spec, 12.0).has_value());
  CHECK(friction_in_step(spec, 9, 0.1) == 0.3);
  CHECK(friction_in_step(spec, 8, 0.1) == 0.1);
  CHECK(friction_in_step(spec, 20, 0.1) == 0.1);
  std::string why;
  CHECK(spec.is_valid(&why));
  spec.path[0].dy = -0.1;  // both the motion and the force
  CHECK_FALSE(spec.is_valid(&why));
  CHECK_THAT(why, Catch::Contains("roller.path[0].fy = 400") && Catch::Contains("either dy"));
}
