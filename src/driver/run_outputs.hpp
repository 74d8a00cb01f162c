#pragma once
// The files of a run's output folder (docs/scenes.md, Output): solver.csv, contact.csv and
// roller.csv (one row per step, flushed before the next step starts), fields.pvd with its VTU
// files (points in the reference configuration with the displacement: ParaView's Warp By Vector
// gives the deformed strip) and, with a roller, roller.pvd with its circle at the same steps. A resumed run continues
// the tables after the resumed step and keeps the earlier VTU files in the series. Each table's columns are one list of
// (name, value) pairs, its header the names of that list (run_outputs.cpp).
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>

#include "roller/driver/simulation.hpp"
#include "roller/driver/step_monitor.hpp"
#include "roller/io/background_writer.hpp"
#include "roller/io/csv_table.hpp"
#include "roller/io/vtu_writer.hpp"

namespace roller {

class RunOutputs {
 public:
  // Opens the tables (continued after `steps_done` when resuming) and, for a fresh run, writes
  // the start state: fields of step 0 and the roller's row 0 at `start_pose`. The fields are
  // read from `model` and `dynamics` (the run's, which outlive this object) when a step is
  // written; everything else comes in the step's record. Field files go to `writer` (written
  // while the next step is solved).
  RunOutputs(const Scene& scene, const StripModel& model, const DynamicsState& dynamics, const RollerPose& start_pose,
             int steps_done, const std::filesystem::path& out_dir, bool resume, BackgroundWriter& writer);
  // The writer's jobs add to this object's series: none may outlive it.
  ~RunOutputs() { writer_.drain(); }
  RunOutputs(const RunOutputs&) = delete;
  RunOutputs& operator=(const RunOutputs&) = delete;

  // The solver's row of a step, converged or not.
  void write_solver_row(const Simulation::StepRecord& step, const MonitorReport& monitor, double wall_s);
  // The results of a converged step: contact and roller rows, fields every output.every steps
  // and at the last one; at the end of a pass its row of passes.csv and its residual profile.
  void write_step(const Simulation::StepRecord& step);

 private:
  // The strip's fields of a step, and the roller (its pose; none without a roller) beside them.
  void write_fields(int step, int pass, const std::vector<NodeContactRecord>& contact,
                    const std::optional<RollerPose>& roller);
  std::filesystem::path vtu_path(int step) const;
  std::filesystem::path vtp_path(int step) const;

  const Scene& scene_;
  const StripModel& model_;
  const DynamicsState& dynamics_;
  BackgroundWriter& writer_;
  std::filesystem::path out_dir_;
  std::unique_ptr<CsvTable> solver_csv_, contact_csv_, roller_csv_, passes_csv_, depth_csv_;
  VecX step_start_displacement_;            // total displacement at the start of the step being written
  PvdSeries series_;                        // added to by the writer's jobs, one at a time (series_mutex_)
  std::optional<PvdSeries> roller_series_;  // roller.pvd, with a roller: its circle at the same steps
  std::mutex series_mutex_;
};

}  // namespace roller
