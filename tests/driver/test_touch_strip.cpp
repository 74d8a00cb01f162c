// roller.touch_strip: the start centre moves vertically until the roller touches the strip as it
// is, and a roller with no strip under it is refused with the key named.
#include <catch2/catch.hpp>

#include <string>

#include "roller/core/error.hpp"
#include "roller/driver/simulation.hpp"
#include "roller/io/scene_loader.hpp"

using namespace roller;

namespace {

Simulation hertz_with(const std::string& centre) {
  return Simulation(load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/hertz.toml",
                               {{"roller.centre", centre}, {"roller.touch_strip", "true"}}));
}

}  // namespace

TEST_CASE("roller.touch_strip lowers or raises the start onto the strip's surface", "[driver][roller]") {
  // Hertz: a 200 x 100 mm strip, R = 100: touching the flat top at y = 200 from either side, over
  // a node (between two nodes of a coarse part of the top the circle touches both a little lower).
  for (const char* centre : {"[100.0, 210.0]", "[100.0, 195.0]", "[0.0, 230.0]"}) {
    INFO(centre);
    const Simulation sim = hertz_with(centre);
    CHECK(sim.state().pose.centre.y() == Approx(200.0).epsilon(1e-12));
    CHECK(sim.program().pose(0.0).centre.y() == Approx(200.0).epsilon(1e-12));
  }
  // Over the strip's corner the highest candidate under the roller is the corner node.
  const Simulation corner = hertz_with("[250.0, 400.0]");
  CHECK(corner.state().pose.centre.y() == Approx(100.0 + std::sqrt(100.0 * 100.0 - 50.0 * 50.0)).epsilon(1e-12));
}

TEST_CASE("roller.touch_strip without a strip under the roller names the key", "[driver][roller]") {
  CHECK_THROWS_WITH(hertz_with("[400.0, 300.0]"),
                    Catch::Contains("roller.touch_strip = true: no contact candidate lies under the roller"));
}
