#pragma once
// The pieces of a run that its step method works on (step_method.hpp), owned by the Simulation
// in one place so that a method holds them by reference: the scene, the strip, the contact
// backend, what the scene prescribes to the roller, the run state and the dynamics.
#include <memory>

#include "roller/assembly/strip_model.hpp"
#include "roller/contact/backend.hpp"
#include "roller/driver/run_state.hpp"
#include "roller/driver/step_record.hpp"
#include "roller/dynamics/dynamics_state.hpp"
#include "roller/io/roller_program.hpp"
#include "roller/io/scene.hpp"

namespace roller {

struct RunModel {
  Scene scene;
  std::unique_ptr<StripModel> strip;
  std::unique_ptr<ContactBackend> backend;
  RollerProgram program;
  RunState state;  // everything a later step reads but the strip and the dynamics (run_state.hpp)
  DynamicsState dynamics;

  Vec2 roller_force() const { return force_on_roller(state.contact); }  // of the strip [N per mm width]
  // The state at the end of a step (converged or not) into its record; the roller's prescribed
  // pose and forces are those of scene step `program_step`.
  void record_state(StepRecord& res, int program_step) const;
};

}  // namespace roller
