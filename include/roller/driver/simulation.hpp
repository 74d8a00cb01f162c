#pragma once
// The step loop (set-up; for each step: predict, solve, cut back if needed, commit,
// write). Results of completed steps are on disk before the next step starts, so a failure or
// a kill loses nothing already done.
#include <atomic>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>

#include "roller/analysis/hertz.hpp"
#include "roller/analysis/pass_metrics.hpp"
#include "roller/analysis/shakedown.hpp"
#include "roller/assembly/strip_model.hpp"
#include "roller/contact/backend.hpp"
#include "roller/contact/friction_history.hpp"
#include "roller/core/enum_names.hpp"
#include "roller/driver/run_state.hpp"
#include "roller/driver/step_record.hpp"
#include "roller/dynamics/dynamics_state.hpp"
#include "roller/io/field_output.hpp"
#include "roller/io/roller_program.hpp"
#include "roller/io/scene.hpp"

namespace roller {

class RunOutputs;           // driver/run_outputs.hpp
class OutputSink;           // driver/output_sink.hpp
class StepMonitor;          // driver/step_monitor.hpp
class BackgroundWriter;     // io/background_writer.hpp
struct RunModel;            // driver/run_model.hpp
class TransientIncrements;  // driver/transient_increments.hpp
class StepMethod;           // driver/step_method.hpp

struct RunOptions {
  std::filesystem::path out_dir = "out";
  std::ostream* progress = nullptr;  // one line per step; nullptr = silent
  // Continue a run in out_dir from its checkpoint.cbor: the output of the steps after the
  // checkpoint is dropped and recomputed, the rest is kept.
  bool resume = false;
  // A fresh run into a folder that is not empty and holds another scene's output (or other
  // files): refused unless overwrite (driver/output_folder.hpp).
  bool overwrite = false;
  // Set (to the signal's number) by the caller's handler of SIGINT or SIGTERM: the run stops
  // after the step under way, keeps its files and checkpoint, and says "interrupted".
  const std::atomic<int>* stop_signal = nullptr;
  // Without files (write_files = false) nothing is written to out_dir: no tables, fields,
  // summary.json or state files; the results go to `sink` alone (roller run from Python).
  bool write_files = true;
  // Also given every row and field the run writes (driver/output_sink.hpp); may be nullptr.
  OutputSink* sink = nullptr;
};

// How a run ended, and the exit code of `roller run` for it (docs/scenes.md, Exit codes).
enum class RunStatus { Running, Completed, StepFailed, InputError, SystemError, InternalError, Interrupted };
template <>
struct EnumNames<RunStatus> {
  static constexpr std::array<std::pair<RunStatus, const char*>, 7> names{{{RunStatus::Running, "running"},
                                                                           {RunStatus::Completed, "completed"},
                                                                           {RunStatus::StepFailed, "step_failed"},
                                                                           {RunStatus::InputError, "input_error"},
                                                                           {RunStatus::SystemError, "system_error"},
                                                                           {RunStatus::InternalError, "internal_error"},
                                                                           {RunStatus::Interrupted, "interrupted"}}};
};
// `signal`: the signal that interrupted the run (Interrupted: 128 + signal, as a shell reports it).
int exit_code(RunStatus status, int signal = 0);
// The status of a run stopped by `e` (InputError, SystemError or out of memory, or a bug).
RunStatus status_of(const std::exception& e);
// What summary.json and the console say of `e`: its text, or for an allocation that failed what
// to do about it (std::bad_alloc's own text is "std::bad_alloc").
std::string message_of(const std::exception& e);

struct RunSummary {
  RunStatus status = RunStatus::Running;
  int signal = 0;  // Interrupted: the signal's number
  bool converged = false;
  int steps_done = 0;
  RunTotals totals;  // over every step of the run, a resumed run's earlier ones included
  double wall_s = 0.0;
  double peak_memory_mb = 0.0;  // the process's peak resident memory so far [MiB]
  std::string message;
  bool decided = false;               // passes.until_verdict stopped the run after the pass that decided
  std::vector<std::string> warnings;  // the run-time monitor's, each kind once (summary.json's beside the scene's)
  // A multi-pass run that has ended (however): the shakedown verdict of its passes.
  std::optional<ShakedownClassification> verdict;
};

// A run stopped before its first step (the memory check while the Simulation is built): its
// output folder prepared as run() would, with a summary.json saying why. Nothing when the folder
// cannot be used (the caller reports the first error).
void write_stopped_summary(const Scene& scene, const RunOptions& options, RunStatus status, const std::string& message);

class Simulation {
 public:
  // Builds the strip, the scene's conditions on it, the roller's program and the run's step
  // method (driver/step_method.hpp), validating the scene against the mesh (InputError).
  explicit Simulation(Scene scene);
  ~Simulation();
  Simulation(Simulation&&) noexcept;

  RunSummary run(const RunOptions& options);

  const Scene& scene() const;
  StripModel& model();
  const StripModel& model() const;
  // Everything a later step reads besides the strip and the dynamics (run_state.hpp): the roller's
  // pose, the contact of the last increment, the pass records, ...
  const RunState& state() const;
  // Strip inertia and suspension at the end of the last step (dynamics_state.hpp).
  const DynamicsState& dynamics() const;
  // What the scene prescribes at each step: the roller's pose and forces, the passes.
  const RollerProgram& program() const;
  // The contact backend of the run (nullptr without a roller); the run-time monitor asks it for
  // the inertia of factors it holds.
  ContactBackend* contact_backend();

  // State files (CBOR): everything the next step needs, so that a run continued from a saved
  // state gives the same results as an uninterrupted one. load_state() restores the strip and,
  // unless strip_only, the run state and the dynamics.
  void save_state(const std::filesystem::path& file) const;
  void load_state(const std::filesystem::path& file, bool strip_only);

  // Advances the state from s_from to s_to (scene steps, fractional) with one increment of the
  // transient method; commits on success (converged = true) and leaves the state untouched on failure.
  IncrementReport advance(Real s_from, Real s_to);

  // Advances through scene step `step` (1-based) by the run's step method: the transient's
  // increments, cut into 2, 4, ... sub-increments when one fails, up to steps.max_cuts times, or
  // the stationary pass. The record holds every value the outputs write about the step.
  using RollerRecord = roller::RollerRecord;
  using StepRecord = roller::StepRecord;
  StepRecord advance_step(int step);

 private:
  // The step loop's pieces (run.cpp).
  // Whether the run resumes: false when it starts (over), a --resume before the first checkpoint
  // included.
  bool start_or_resume(const RunOptions& options);
  void run_steps(const RunOptions& options, int first_step, RunOutputs& outputs, StepMonitor& monitor,
                 BackgroundWriter& writer, RunSummary& summary);
  void save_states(int step, const std::filesystem::path& out_dir, BackgroundWriter& writer) const;
  // save_state in two halves: the state is read now, the returned job writes it (to run on a
  // background thread while the next step changes the model).
  std::function<void()> state_writer(const std::filesystem::path& file) const;

  // On the heap, so that the methods' references to them outlive a move of the Simulation.
  std::unique_ptr<RunModel> run_;                    // the scene, the strip, the run state, ...
  std::unique_ptr<TransientIncrements> increments_;  // one increment of the transient method
  std::unique_ptr<StepMethod> method_;               // chosen once, by passes.method
};

}  // namespace roller
