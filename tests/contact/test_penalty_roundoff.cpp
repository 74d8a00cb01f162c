// A penalty too stiff for double precision (docs/stability.md: Z1 at contact.penalty.factor = 1e12)
// must stop the step with that cause, not pass round-off noise off as a converged increment.
#include <catch2/catch.hpp>

#include "roller/driver/simulation.hpp"
#include "roller/io/scene_loader.hpp"

using namespace roller;

TEST_CASE("penalty backend: a penalty beyond double precision stops the step and names the factor",
          "[contact][penalty]") {
  Simulation sim(
      load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/z1_outf05.toml",
                 {{"contact.backend", "\"penalty\""}, {"contact.penalty.factor", "1e12"}, {"steps.max_cuts", "0"}}));
  const Simulation::StepRecord r = sim.advance_step(1);
  CHECK_FALSE(r.converged());
  CHECK_THAT(r.message, Catch::Contains("too stiff for double precision"));
  CHECK_THAT(r.message, Catch::Contains("contact.penalty.factor"));
}
