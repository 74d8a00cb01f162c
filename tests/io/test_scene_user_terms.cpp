// Input in the users' terms: a load given as the Hertz peak pressure or as p0/k, --set reaching a
// block of an array of tables, a path segment beyond the run refused, an absent [output] table
// with its computed defaults, and the warnings for values that look like a slip of units.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "../support/scene_errors.hpp"
#include "roller/analysis/hertz.hpp"
#include "roller/io/scene_loader.hpp"
#include "roller/io/scene_warnings.hpp"
#include "roller/mesh/strip_mesher.hpp"

using namespace roller;

namespace {

const std::string kBurnishing = std::string(ROLLER_SOURCE_DIR) + "/problems/burnishing.toml";

const std::string kRoller = R"(
title = "rolled"
[mesh]
length = 20.0
height = 5.0
nx = 200
ny = 10
[material]
E = 2.1e5
nu = 0.3
yield_stress = 300.0
[steps]
count = 4
[[displacement]]
nodes = "bottom"
y = 0.0
x = 0.0
[roller]
radius = 50.0
[[roller.path]]
steps = [1, 2]
LOAD
[[roller.path]]
steps = [3, 4]
dx = 1.0
)";

std::string with_load(const std::string& load) {
  std::string text = kRoller;
  return text.replace(text.find("LOAD"), 4, load);
}

}  // namespace

TEST_CASE("a load given as p0 or p0/k is the force with that Hertz peak pressure", "[io][scene][loads]") {
  const Scene by_p0 = parse_scene(with_load("p0 = 800.0"), "p0.toml");
  const Real e_star = 2.1e5 / (1.0 - 0.3 * 0.3);
  REQUIRE(by_p0.roller->path[0].fy);
  CHECK(hertz_line_contact(*by_p0.roller->path[0].fy, 50.0, e_star).peak == Approx(800.0).epsilon(1e-12));
  // p0/k with k = sigma_y / sqrt(3): 4.0 is Johnson's shakedown limit of a frictionless line contact.
  const Scene by_ratio = parse_scene(with_load("p0_over_k = 4.0"), "p0k.toml");
  const Real k = 300.0 / std::sqrt(3.0);
  CHECK(hertz_line_contact(*by_ratio.roller->path[0].fy, 50.0, e_star).peak / k == Approx(4.0).epsilon(1e-12));
  // The resolved scene keeps the force with the formula that gave it, and loads back to it.
  const std::string resolved = scene_to_toml(by_ratio);
  CHECK(resolved.find("# roller.path[0].fy = ") != std::string::npos);
  CHECK(resolved.find("p0_over_k = 4: k = yield_stress/sqrt(3)") != std::string::npos);
  CHECK(parse_scene(resolved, "resolved.toml").roller->path[0].fy == by_ratio.roller->path[0].fy);
}

TEST_CASE("a load given twice, or p0/k without a yield stress, is refused", "[io][scene][loads][errors]") {
  CHECK_THAT(test::error_of(with_load("fy = 400.0\np0 = 800.0")),
             Catch::Contains("give the segment's vertical force once"));
  CHECK_THAT(test::error_of(with_load("p0 = 800.0\np0_over_k = 4.0")), Catch::Contains("once"));
  CHECK_THAT(test::error_of(with_load("p0 = -1.0")), Catch::Contains("roller.path[0].p0"));
  std::string elastic = with_load("p0_over_k = 4.0");
  elastic.replace(elastic.find("yield_stress = 300.0"), 20, "");
  CHECK_THAT(test::error_of(elastic), Catch::Contains("p0/k needs a yield stress"));
}

TEST_CASE("command-line overrides reach a block of an array of tables (--set roller.path[1].fy)",
          "[io][scene][overrides]") {
  const Scene s = load_scene(kBurnishing, {{"roller.path[1].fy", "300.0"}, {"roller.path[0].p0_over_k", "3.0"}});
  CHECK(*s.roller->path[1].fy == 300.0);
  CHECK(s.roller->path[2].dy == 0.1);  // the other blocks as written
  const Real k = s.material.yield_stress / std::sqrt(3.0);
  CHECK(hertz_line_contact(*s.roller->path[0].fy, s.roller->radius, s.material.plane_strain_modulus()).peak / k ==
        Approx(3.0).epsilon(1e-12));
  // An override of the force replaces the block's force, however it was given; two overrides of
  // one force are refused (the later would hide the earlier).
  CHECK(*load_scene(kBurnishing, {{"roller.path[0].p0", "800.0"}}).roller->path[0].fy !=
        *load_scene(kBurnishing).roller->path[0].fy);
  CHECK_THROWS_WITH(load_scene(kBurnishing, {{"roller.path[0].p0_over_k", "3.0"}, {"roller.path[0].fy", "1.0"}}),
                    Catch::Contains("twice"));
  CHECK_THROWS_WITH(load_scene(kBurnishing, {{"roller.path[7].fy", "1.0"}}),
                    Catch::Contains("the scene has 3 [[path]] block(s), numbered from 0"));
  CHECK_THROWS_WITH(load_scene(kBurnishing, {{"roller.path[x].fy", "1.0"}}), Catch::Contains("name[N]"));
  CHECK_THROWS_WITH(load_scene(kBurnishing, {{"mesh[0].nx", "1"}}), Catch::Contains("not an array of tables"));
}

TEST_CASE("a path segment beyond the run's steps is refused unless --steps shortened the run", "[io][scene][errors]") {
  std::string text = with_load("fy = 400.0");
  text.replace(text.find("steps = [3, 4]"), 14, "steps = [3, 6]");
  CHECK_THAT(test::error_of(text), Catch::Contains("roller.path[1].steps = [3, 6]: the segment ends after the run's "
                                                   "last step 4"));
  // The file's own path within its steps, the run cut short: allowed.
  CHECK(test::error_of(with_load("fy = 400.0"), {{"steps.count", "2"}}).empty());
  // A path set longer than both: refused.
  CHECK_THAT(test::error_of(with_load("fy = 400.0"), {{"roller.path[1].steps", "[3, 9]"}}),
             Catch::Contains("after --set/--steps"));
}

TEST_CASE("an absent [output] table takes its computed defaults: a multi-pass run writes each pass's end",
          "[io][scene]") {
  const Scene s = load_scene(kBurnishing);  // no [output] table, 3 passes of 15 steps
  REQUIRE(s.passes.count == 3);
  CHECK(s.output.every == s.steps.n_steps);
  CHECK(parse_scene(with_load("fy = 400.0"), "one_pass.toml").output.every == 1);
}

TEST_CASE("values that look like a slip of units are warned about, naming the key", "[io][scene][warnings]") {
  const Scene good = parse_scene(with_load("fy = 400.0"), "good.toml");
  CHECK(scene_warnings(good, make_strip_mesh(good.mesh)).empty());
  std::string gpa = with_load("fy = 400.0");
  gpa.replace(gpa.find("E = 2.1e5"), 9, "E = 210.0");
  const Scene in_gpa = parse_scene(gpa, "gpa.toml");
  const auto w_gpa = scene_warnings(in_gpa, make_strip_mesh(in_gpa.mesh));
  REQUIRE(w_gpa.size() >= 1);
  CHECK_THAT(w_gpa[0], Catch::Contains("material.E = 210 MPa") && Catch::Contains("GPa"));
  std::string metres = with_load("fy = 400.0");
  metres.replace(metres.find("radius = 50.0"), 13, "radius = 0.05");
  const Scene in_metres = parse_scene(metres, "metres.toml");
  const auto w_metres = scene_warnings(in_metres, make_strip_mesh(in_metres.mesh));
  REQUIRE(!w_metres.empty());
  CHECK_THAT(w_metres[0], Catch::Contains("roller.radius = 0.05 mm") && Catch::Contains("metres"));
  // A light load on a coarse mesh: a contact of a node or two.
  std::string light = with_load("fy = 1.0");
  const Scene coarse = parse_scene(light, "light.toml");
  const auto w_light = scene_warnings(coarse, make_strip_mesh(coarse.mesh));
  REQUIRE(w_light.size() == 1);
  CHECK_THAT(w_light[0], Catch::Contains("the contact will span about"));
}
