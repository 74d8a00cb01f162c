// The stationary pass at two places of the roller between two nodes (passes.stationary_phases,
// docs/model.md "Phases") on an elastic strip, where the copies do not meet: each is the one
// strip's pass with the roller's contact, the roller k/P of an element further along it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "roller/assembly/phased_strip.hpp"
#include "roller/driver/simulation.hpp"
#include "roller/io/roller_start.hpp"
#include "roller/io/scene_loader.hpp"
#include "roller/steady/stationary_passes.hpp"

using namespace roller;

namespace {

// The first pass's displacement (all dofs of every copy) of shakedown_p30, made elastic, with the
// roller's contact; `shift` moves the roller's start along x [mm].
VecX first_pass(int phases, Real shift, Real* element = nullptr) {
  Scene scene = load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/shakedown_p30.toml",
                           {{"passes.method", "\"stationary\""},
                            {"passes.stationary_contact", "\"roller\""},
                            {"passes.stationary_phases", std::to_string(phases)}});
  scene.material.plastic = false;
  scene.roller->start_centre = given_start_centre(scene) + Vec2(shift, 0.0);
  const Simulation sim(scene);
  StationaryPasses passes(sim.scene(), sim.model(), steady_load(sim.scene(), std::nullopt));
  if (element) *element = contact_element_length(sim.model().mesh(), passes.centre_x());
  const StationaryPasses::Pass pass = passes.run(sim.model(), VecX(), nullptr, nullptr);
  REQUIRE(pass.solve.converged());
  return pass.solve.displacement;
}

}  // namespace

TEST_CASE("stationary phases: on an elastic strip copy k is the one strip's pass with the roller k/P of an element on",
          "[scenes][stationary]") {
  Real h = 0.0;
  const VecX two = first_pass(2, 0.0, &h);
  const VecX at_node = first_pass(1, 0.0), half_on = first_pass(1, 0.5 * h);
  const Index n = at_node.size();
  REQUIRE(two.size() == 2 * n);
  const Real scale = at_node.cwiseAbs().maxCoeff();
  CHECK((two.head(n) - at_node).cwiseAbs().maxCoeff() <= 1e-6 * scale);
  CHECK((two.tail(n) - half_on).cwiseAbs().maxCoeff() <= 1e-6 * scale);
  // Half an element matters: the check above could not pass with the roller elsewhere.
  CHECK((half_on - at_node).cwiseAbs().maxCoeff() > 1e-3 * scale);
}

TEST_CASE("stationary phases: the loaded state a pass writes is the unshifted copy's, this strip's",
          "[scenes][stationary]") {
  // The fields of a phased pass's loaded state come from copy 0 of the P copies (a state of the
  // union does not fit the strip); its displacement is the one-phase pass's with the roller at a node.
  Scene scene = load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/shakedown_p30.toml",
                           {{"passes.method", "\"stationary\""},
                            {"passes.count", "1"},
                            {"output.every", "1"},
                            {"passes.stationary_contact", "\"roller\""},
                            {"passes.stationary_phases", "2"}});
  scene.material.plastic = false;
  Simulation sim(scene);
  const Simulation::StepRecord r = sim.advance_step(1);
  REQUIRE(r.converged());
  REQUIRE(r.loaded_fields);
  const VecX at_node = first_pass(1, 0.0);
  const auto field = std::find_if(r.loaded_fields->point_data.begin(), r.loaded_fields->point_data.end(),
                                  [](const VtuField& f) { return f.name == "displacement"; });
  REQUIRE(field != r.loaded_fields->point_data.end());
  REQUIRE(static_cast<Index>(field->values.size()) == 3 * at_node.size() / 2);
  Real largest_difference = 0.0;
  for (Index a = 0; a < at_node.size() / 2; ++a)
    for (int c = 0; c < 2; ++c)
      largest_difference = std::max(largest_difference, std::abs(field->values[3 * a + c] - at_node(2 * a + c)));
  CHECK(largest_difference <= 1e-6 * at_node.cwiseAbs().maxCoeff());
}
