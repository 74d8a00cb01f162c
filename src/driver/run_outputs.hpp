#pragma once
// What a run gives its sinks (driver/output_sink.hpp) step by step: the solver's row of every
// step; for a converged step its contact and roller rows, at the end of a pass its row of passes
// and its residual profile, and the strip's fields every output.every steps and at the last one.
// A fresh run gives the start state first: the roller's row 0 and the fields of step 0.
#include <memory>
#include <optional>
#include <vector>

#include "roller/driver/output_sink.hpp"
#include "roller/driver/simulation.hpp"
#include "roller/driver/step_monitor.hpp"
#include "roller_disc_fields.hpp"

namespace roller {

// Whether the fields of `step` are written: every output.every steps and the last one.
bool fields_written(const Scene& scene, int step);

class RunOutputs {
 public:
  // The fields are read from `model` and `dynamics` (the run's, which outlive this object) when
  // a step is given; everything else comes in the step's record.
  RunOutputs(const Scene& scene, const StripModel& model, const DynamicsState& dynamics, const RollerPose& start_pose,
             bool fresh, std::vector<OutputSink*> sinks);

  // The solver's row of a step, converged or not.
  void write_solver_row(const Simulation::StepRecord& step, const MonitorReport& monitor, double wall_s);
  // The results of a converged step.
  void write_step(const Simulation::StepRecord& step);

 private:
  void add_row(OutputTable table, const Row& row);
  // The strip's fields of a step, and the roller (its pose; none without a roller) beside them,
  // with `cells` (a pass's fatigue indices) added to the strip's cell data.
  void write_fields(int step, int pass, const std::vector<NodeContactRecord>& contact,
                    const std::optional<RollerPose>& roller, std::vector<VtuField> cells = {});
  // A stationary pass's loaded state beside the step's fields.
  void write_loaded_fields(const Simulation::StepRecord& step);
  // Fields to every sink (copies to all but the last).
  void add_fields(StepFields f);

  const Scene& scene_;
  const StripModel& model_;
  const DynamicsState& dynamics_;
  std::vector<OutputSink*> sinks_;
  VecX step_start_displacement_;            // total displacement at the start of the step being given
  int mid_pass_step_ = 0;                   // the step within a pass whose fields output.mid_pass adds (0: none)
  std::unique_ptr<RollerDiscFields> disc_;  // an elastic roller's disc, with the VTU output
};

}  // namespace roller
