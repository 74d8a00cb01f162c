#pragma once
// Loads a scene of problems/ with overrides and runs all its steps (each must converge).
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "roller/driver/simulation.hpp"
#include "roller/io/scene_loader.hpp"

namespace roller::test {

inline Simulation run_scene(const std::string& name, const std::vector<SceneOverride>& overrides = {}) {
  Simulation sim(load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/" + name + ".toml", overrides));
  for (int step = 1; step <= sim.scene().total_steps(); ++step) REQUIRE(sim.advance_step(step).converged());
  return sim;
}

}  // namespace roller::test
