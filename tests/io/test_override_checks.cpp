// Overrides (--set, --steps, --refine, --contact, rollerpy's set=) are checked as the file's own
// values: a key given twice would let the later value hide a bad earlier one, and a pass scene's
// steps cannot be cut short.
#include <catch2/catch.hpp>

#include <string>

#include "../support/scene_errors.hpp"

using namespace roller;
using Catch::Contains;
using test::error_of;

namespace {

const std::string kStrip = R"(
kinematics = "small"
[mesh]
element = "Q4"
length = 40.0
height = 10.0
nx = 8
ny = 2
[material]
E = 2.1e5
nu = 0.3
yield_stress = 500.0
[steps]
count = 6
[[displacement]]
nodes = "bottom"
x = 0.0
y = 0.0
[roller]
radius = 20.0
centre = [10.0, 30.0]
[[roller.path]]
steps = [1, 2]
fy = 100.0
[[roller.path]]
steps = [3, 5]
dx = 10.0
fy = 100.0
[[roller.path]]
steps = [6, 6]
dy = 1.0
)";

}  // namespace

TEST_CASE("an override given twice is refused, the value it would hide named", "[io][scene][errors]") {
  // As `roller run --set steps.count=nan --steps 2` gives them: the later one would replace nan.
  CHECK_THAT(error_of(kStrip, {{"steps.count", "nan"}, {"steps.count", "2"}}),
             Contains("steps.count=nan") && Contains("steps.count=2") && Contains("twice"));
  CHECK_THAT(error_of(kStrip, {{"contact.backend", "inf"}, {"contact.backend", "\"penalty\""}}),
             Contains("contact.backend=inf") && Contains("twice"));
  CHECK_THAT(error_of(kStrip, {{"mesh.refine", "nan"}, {"mesh.refine", "1"}}), Contains("mesh.refine=nan"));
  // A segment's force is one value, whichever of fy, p0 and p0_over_k gives it.
  CHECK_THAT(error_of(kStrip, {{"roller.path[1].fy", "nan"}, {"roller.path[1].p0", "100"}}),
             Contains("roller.path[1].fy=nan") && Contains("twice"));
  // Different blocks or keys are different values; each alone is checked as the file's.
  CHECK(error_of(kStrip, {{"roller.path[0].fy", "90"}, {"roller.path[1].fy", "90"}}).empty());
  CHECK_THAT(error_of(kStrip, {{"steps.count", "nan"}}), Contains("steps.count"));
}

TEST_CASE("an override key without a name in one of its parts is refused", "[io][scene][errors]") {
  for (const char* key : {"", ".", "steps.", ".count", "steps..count"})
    CHECK_THAT(error_of(kStrip, {{key, "2"}}), Contains("expected a key of dotted names"));
}

TEST_CASE("fewer steps cut a single pass short but never a pass of a scene with [passes]", "[io][scene][errors]") {
  CHECK(error_of(kStrip, {{"steps.count", "3"}}).empty());  // one pass: run its first 3 steps
  const std::string passes = kStrip + "[passes]\ncount = 2\n";
  CHECK(error_of(passes).empty());
  CHECK_THAT(error_of(passes, {{"steps.count", "3"}}), Contains("steps.count = 3") && Contains("[passes]") &&
                                                           Contains("ends at step 6") &&
                                                           Contains("cannot be shortened") && Contains("passes.count"));
  CHECK(error_of(passes, {{"passes.count", "1"}}).empty());
  // A path given anew to fit the fewer steps is a shorter pass, not a cut one.
  CHECK(error_of(passes, {{"steps.count", "3"},
                          {"roller.path",
                           "[{ steps = [1, 1], fy = 100.0 }, { steps = [2, 2], dx = 5.0, fy = 100.0 }, "
                           "{ steps = [3, 3], dy = 1.0 }]"}})
            .empty());
  CHECK_THAT(error_of(kStrip + "[passes]\nmethod = \"stationary\"\n", {{"steps.count", "5"}}),
             Contains("cannot be shortened"));
}

TEST_CASE("the stationary method refuses a T3 mesh by its key", "[io][scene][errors]") {
  const std::string stationary = kStrip + "[passes]\nmethod = \"stationary\"\n";
  CHECK(error_of(stationary).empty());
  CHECK_THAT(error_of(stationary, {{"mesh.element", "\"T3\""}}),
             Contains("passes.method") && Contains("mesh.element = \"Q4\"") && Contains("\"T3\""));
}
