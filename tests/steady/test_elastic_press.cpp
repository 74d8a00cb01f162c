// The steady solves' elastic press (steady/elastic_press.hpp) solves through the contact session
// what a run of the elastic scene solves: the same increments, to the bit.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include "roller/driver/simulation.hpp"
#include "roller/io/scene_loader.hpp"
#include "roller/io/scene_strip.hpp"
#include "roller/steady/elastic_press.hpp"
#include "roller/steady/steady_load.hpp"

using namespace roller;

TEST_CASE("elastic press: the press of the steady solves is a run's increments of the elastic scene, to the bit",
          "[steady][session]") {
  const Scene shipped = load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/shakedown_p37.toml");
  const SteadyLoad steady = steady_load(shipped, std::nullopt);
  Scene elastic = elastic_frictionless_scene(shipped);
  elastic.steps.n_steps = steady.press_steps;
  Simulation run(elastic);
  const std::unique_ptr<StripModel> strip = make_scene_strip(elastic);
  ElasticPress press(elastic, strip->mesh());
  for (int step = 1; step <= steady.press_steps; ++step) {
    INFO("step " << step);
    REQUIRE(run.advance_step(step).converged());
    REQUIRE(press.press(step - 1, step).converged());
    CHECK(press.pose().centre == run.state().pose.centre);
    REQUIRE(press.contact().size() == run.state().contact.size());
    for (std::size_t i = 0; i < press.contact().size(); ++i)
      CHECK(press.contact()[i].force == run.state().contact[i].force);
  }
  CHECK(press.strip().total_displacement() == run.model().total_displacement());
  // It carries the travel's force, within force control's tolerance (1e-6 of it).
  CHECK(std::abs(force_on_roller(press.contact()).y() - *steady.force) <= 1e-6 * *steady.force);
}
