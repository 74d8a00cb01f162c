// Thesis scenes Z3 (suspended roller, two passes) and Z4 (impact with strip inertia) run end to
// end at refine 1 with both backends; the suspension obeys its equation of motion at every
// step, and DATA02 starts from DATA01's final state.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <unistd.h>

#include "../support/run_scene.hpp"

using namespace roller;

namespace {

// m a + c v + k w = F_y at the end of the step (Houbolt's v and a of the deflection). The
// coupling stops when the deflection changes by less than 1e-10 R, i.e. the balance holds to
// (k_eff + contact stiffness) x 1e-10 R, about 1e-6 of the scene's force scale.
Real suspension_imbalance(const Simulation& sim) {
  const SuspensionSpec& s = *sim.scene().roller->suspension;
  const Real w = sim.dynamics().suspension()->deflection();
  return s.mass * sim.dynamics().suspension_acceleration() + s.damping * sim.dynamics().suspension_velocity() +
         s.stiffness * w - force_on_roller(sim.state().contact).y();
}

}  // namespace

TEST_CASE("Z4 impact scenes run end to end, the suspension in balance at every step", "[dynamics][thesis][slow]") {
  for (const char* name : {"z4_v6_25", "z4_v25", "z4_v50"}) {
    INFO(name);
    Simulation sim(load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/" + name + ".toml"));
    Simulation penalty(load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/" + name + ".toml",
                                  {{"contact.backend", "\"penalty\""}}));
    // Node 101 (thesis numbering), the corner the roller strikes: its per-step increment D_y.
    const Index corner = 2 * 100 + 1;
    Real previous_uy = 0.0, largest = 0.0;
    int largest_step = 0;
    for (int step = 1; step <= sim.scene().steps.n_steps; ++step) {
      INFO("step " << step);
      REQUIRE(sim.advance_step(step).converged());
      REQUIRE(penalty.advance_step(step).converged());
      const Real fy = force_on_roller(sim.state().contact).y();
      // Before contact the coupling's own tolerance (k x 1e-10 R) is the scale, not the force.
      const Real coupling_tol = 2.0 * sim.scene().roller->suspension->stiffness * 1e-10 * sim.scene().roller->radius;
      CHECK(std::abs(suspension_imbalance(sim)) <= std::max(1e-5 * std::abs(fy), coupling_tol));
      if (step >= 4) {
        // Contact begins in step 4 (the scene starts the roller 3.5 steps before the corner).
        CHECK(fy > 0.0);
        CHECK(sim.dynamics().suspension()->deflection() > 0.0);
        CHECK(force_on_roller(penalty.state().contact).y() == Approx(fy).epsilon(0.01));
      } else {
        CHECK(std::abs(fy) <= 1e-4);  // the interior point's barrier force on a node not yet touched
      }
      const Real uy = sim.model().total_displacement()(corner);
      if (std::abs(uy - previous_uy) > largest) {
        largest = std::abs(uy - previous_uy);
        largest_step = step;
      }
      previous_uy = uy;
    }
    // The thesis (its figure 5.21): D_y of node 101 is largest at step 5 for all speeds.
    CHECK(largest_step == 5);
    // Strip inertia is on: the strip moves.
    CHECK(sim.dynamics().kinetic_energy() > 0.0);
  }
}

TEST_CASE("Z3 DATA01 then DATA02 from its final state, suspension in balance", "[dynamics][thesis][slow]") {
  Simulation first(load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/z3_data01.toml"));
  const Real force_scale = 1e5;  // N/mm: the largest roller force of the pass (measured 9.6e4)
  bool touched_at_step_1 = false;
  Real first_force_47 = 0.0;
  for (int step = 1; step <= first.scene().steps.n_steps; ++step) {
    INFO("DATA01 step " << step);
    REQUIRE(first.advance_step(step).converged());
    CHECK(std::abs(suspension_imbalance(first)) <= 1e-5 * force_scale);
    if (step == 1) touched_at_step_1 = force_on_roller(first.state().contact).y() > 0.0;
    if (step == 47) first_force_47 = force_on_roller(first.state().contact).y();
  }
  CHECK(touched_at_step_1);
  const std::filesystem::path state =
      std::filesystem::temp_directory_path() / ("roller_z3_state_" + std::to_string(::getpid()) + ".cbor");
  first.save_state(state);

  Simulation second(load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/z3_data02.toml",
                               {{"restart.from", "\"" + state.string() + "\""}}));
  // The second pass starts on the deformed strip with its residual stresses.
  CHECK((second.model().total_displacement() - first.model().total_displacement()).norm() == 0.0);
  CHECK(second.model().state(0, 0).stress == first.model().state(0, 0).stress);
  // Its depths are measured from the surface pass 1 left (roller.touch_strip): the roller starts
  // touching the groove, 0.95 mm below the original top at its x.
  CHECK(second.state().pose.centre.y() < first.scene().roller->start_centre->y() - 0.5);
  for (int step = 1; step <= second.scene().steps.n_steps; ++step) {
    INFO("DATA02 step " << step);
    REQUIRE(second.advance_step(step).converged());
    if (step == 1) CHECK(force_on_roller(second.state().contact).y() > 0.0);  // pressing into the groove at once
    CHECK(std::abs(suspension_imbalance(second)) <= 1e-5 * 2.0 * force_scale);
    // The thesis (its figures 5.18, 5.19): the second pass leaves larger stresses; it needs a
    // larger force at the same step.
    if (step == 47) CHECK(force_on_roller(second.state().contact).y() > 1.2 * first_force_47);
  }
  std::filesystem::remove(state);
}
