#include "roller/driver/simulation.hpp"

#include <memory>
#include <utility>

#include "pass_fatigue.hpp"
#include "roller/contact/backend_factory.hpp"
#include "roller/io/roller_start.hpp"
#include "roller/io/scene_strip.hpp"
#include "run_model.hpp"
#include "step_method.hpp"
#include "transient_increments.hpp"

namespace roller {

Simulation::Simulation(Scene scene) : run_(std::make_unique<RunModel>()) {
  RunModel& run = *run_;
  run.scene = std::move(scene);
  const Scene& sc = run.scene;
  run.strip = make_scene_strip(sc);
  run.backend = make_increment_backend(sc.roller.has_value(), sc.contact, sc.newton);
  increments_ = std::make_unique<TransientIncrements>(run);  // sets the strip's dof map
  if (!sc.initial_state.empty()) load_state(sc.initial_state, /*strip_only=*/true);
  Vec2 start_centre = Vec2::Zero();
  if (sc.roller) {
    start_centre = start_centre_on(sc, *run.strip, increments_->candidate_nodes());
    run.state.pose = roller_pose(*sc.roller, start_centre, 0.0);
  }
  run.program = RollerProgram(sc.roller, sc.passes, sc.steps.n_steps, start_centre);
  // After the initial state: a restarted strip starts at rest in its new configuration.
  run.dynamics = DynamicsState(*run.strip, sc.dynamics.strip_inertia, sc.dynamics.lumped_mass,
                               sc.roller ? sc.roller->suspension : std::nullopt, sc.steps.dt);
  if (sc.passes.count > 1) run.state.pass_baseline = PassBaseline::of(*run.strip);
  if (sc.fatigue && sc.passes.method == PassMethod::Transient)  // the first pass's cycle from the strip as found
    run.state.pass_cycles = start_cycles(sc, run.program, 1, *run.strip);
  method_ =
      sc.passes.method == PassMethod::Stationary ? make_stationary_steps(run) : make_transient_steps(run, *increments_);
}

Simulation::~Simulation() = default;
Simulation::Simulation(Simulation&&) noexcept = default;

const Scene& Simulation::scene() const { return run_->scene; }
StripModel& Simulation::model() { return *run_->strip; }
const StripModel& Simulation::model() const { return *run_->strip; }
const RunState& Simulation::state() const { return run_->state; }
const DynamicsState& Simulation::dynamics() const { return run_->dynamics; }
const RollerProgram& Simulation::program() const { return run_->program; }
ContactBackend* Simulation::contact_backend() { return run_->backend.get(); }

IncrementReport Simulation::advance(Real s_from, Real s_to) { return increments_->advance(s_from, s_to); }

Simulation::StepRecord Simulation::advance_step(int step) { return method_->advance(step, StepOptions{}); }

}  // namespace roller
