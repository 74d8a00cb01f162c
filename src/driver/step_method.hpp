#pragma once
// How a run advances one scene step (docs/architecture.md): the transient method (the step's
// increments, cut back when one fails) or the stationary method (one step is one pass, solved in
// the roller's frame). The run's method is chosen once, when the Simulation is built; what one
// step hands the next lives in the run state (run_state.hpp), typed by the method.
#include <atomic>
#include <iosfwd>
#include <memory>

#include "roller/driver/step_record.hpp"
#include "run_model.hpp"

namespace roller {

class TransientIncrements;  // transient_increments.hpp

// Where a step's progress lines go, and the stop request it heeds.
struct StepOptions {
  std::ostream* progress = nullptr;        // the stationary iterations' lines; nullptr = silent
  const std::atomic<int>* stop = nullptr;  // a signal's number: stop as interrupted
};

class StepMethod {
 public:
  virtual ~StepMethod() = default;
  // Advances the run's pieces through scene step `step` (1-based); on failure they are as they
  // were before the step, or at its last converged sub-increment.
  virtual StepRecord advance(int step, const StepOptions& control) = 0;
};

std::unique_ptr<StepMethod> make_transient_steps(RunModel& run, TransientIncrements& increments);
std::unique_ptr<StepMethod> make_stationary_steps(RunModel& run);

}  // namespace roller
