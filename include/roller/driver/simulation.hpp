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
#include "roller/driver/increment_solver.hpp"
#include "roller/driver/load_program.hpp"
#include "roller/driver/roller_program.hpp"
#include "roller/driver/run_state.hpp"
#include "roller/dynamics/dynamics_state.hpp"
#include "roller/io/field_output.hpp"
#include "roller/io/scene.hpp"

namespace roller {

class RunOutputs;        // driver/run_outputs.hpp
class OutputSink;        // driver/output_sink.hpp
class StepMonitor;       // driver/step_monitor.hpp
class BackgroundWriter;  // io/background_writer.hpp
class StationaryPasses;  // driver/stationary_passes.hpp

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
  // Builds the mesh and the load program, validating the scene against the mesh (InputError).
  explicit Simulation(Scene scene);
  ~Simulation();
  Simulation(Simulation&&) noexcept;

  RunSummary run(const RunOptions& options);

  const Scene& scene() const { return scene_; }
  StripModel& model() { return *model_; }
  const StripModel& model() const { return *model_; }
  // The contact backend of the run (nullptr without a roller); the run-time monitor asks it for
  // the inertia of factors it holds.
  ContactBackend* contact_backend() { return backend_.get(); }
  // Everything a later step reads besides the strip and the dynamics (run_state.hpp): the roller's
  // pose, the contact of the last increment, the pass records, ...
  const RunState& state() const { return state_; }
  // Strip inertia and suspension at the end of the last step (dynamics_state.hpp).
  const DynamicsState& dynamics() const { return dynamics_; }
  // What the scene prescribes at each step: the roller's pose and forces, the passes.
  const RollerProgram& program() const { return program_; }
  Vec2 roller_force() const { return force_on_roller(state_.contact); }  // of the strip [N per mm width]

  // State files (CBOR): everything the next step needs, so that a run continued from a saved
  // state gives the same results as an uninterrupted one. load_state() restores the strip and,
  // unless strip_only, the run state and the dynamics.
  void save_state(const std::filesystem::path& file) const;
  // The same in two halves: the state is read now, the returned job writes it (to run on a
  // background thread while the next step changes the model).
  std::function<void()> state_writer(const std::filesystem::path& file) const;
  void load_state(const std::filesystem::path& file, bool strip_only);

  // Advances the state from s_from to s_to (scene steps, fractional) with one increment;
  // commits on success (converged = true) and leaves the state untouched on failure.
  IncrementReport advance(Real s_from, Real s_to);

  // The roller at the end of a converged step, as the outputs write it (roller.csv).
  struct RollerRecord {
    RollerPose pose;
    Vec2 force = Vec2::Zero();     // of the strip on the roller [N per mm width]
    Vec2 velocity = Vec2::Zero();  // of the centre over the step (backward difference) [mm/s]
    Real anchor_y = 0.0;           // the prescribed pose's height: a suspension's anchor
    Real deflection = 0.0, deflection_velocity = 0.0, deflection_acceleration = 0.0;  // suspension
    PrescribedForce prescribed;  // the forces the step prescribed (none: its motion)
    Vec2 load_offset = Vec2::Zero();
  };

  // Advances through scene step `step` (1-based), cutting it into 2, 4, ... sub-increments when
  // an increment fails, up to steps.max_cuts times. The record holds every value the outputs
  // write about the step (driver/run_outputs.hpp), the prescribed pose and forces included.
  struct StepRecord {
    int step = 0;
    int pass = 1;
    Real time = 0.0;
    Termination status = Termination::Failed;
    int cuts = 0;
    SolveCounters counters;  // of the step's sub-increments
    BackendDetails details;  // of the step's sub-increments: their work summed, the rest of the last one
    Real max_penetration = 0.0;
    Index n_yielded = 0;   // integration points that yielded in the step's last converged increment
    IncrementReport last;  // the last increment tried
    std::string message;   // why the step failed
    bool converged() const { return status == Termination::Converged; }
    // The step ended a pass of a multi-pass run: what the pass left (analysis/pass_metrics.hpp),
    // with the residual state by depth under the middle of its track (at x = profile_x).
    struct PassEnd {
      PassRecord record;
      Real profile_x = 0.0;
      std::vector<DepthSample> profile;
    };
    std::optional<PassEnd> pass_end;
    // The state at the end of the step (as it stands after a failed one): the contact of its
    // last increment, the roller, the strip's kinetic energy.
    std::vector<NodeContactRecord> contact;
    Index n_contact() const { return count_in_contact(contact); }
    std::optional<RollerRecord> roller;
    Real kinetic_energy = 0.0;
    // A stationary pass's loaded state, when its fields are written (output.mid_pass).
    std::optional<StripFields> loaded_fields;
  };
  StepRecord advance_step(int step);

 private:
  // advance_step of the stationary method: step = pass (stationary_step.cpp).
  StepRecord advance_stationary(int step);
  // Before the first step of pass `pass` > 1: the roller, clear of the strip, returns to the
  // pass's start; a message (and nothing changed) when it is not clear.
  std::string return_for_pass(int pass);
  // Where an increment starts: the previous converged increment scaled to this one's length
  // (and, as an option, the thesis's arc predictor for nodes that would enter the roller).
  VecX predictor(Real s_from, Real s_to, const RollerMotion* motion) const;
  // What the increment to s_to starts from besides the strip (the roller's motion, forces, ...).
  IncrementStart increment_start(Real s_to) const;
  // Accepts a converged increment (transactional: a throw of the strip's commit changes nothing).
  void commit(const IncrementSolution& solution, const RollerMotion& motion, Real s_from, Real s_to,
              IncrementReport& inc);
  // After a converged step: observes the contact; at a pass's last step, measures the pass.
  std::optional<StepRecord::PassEnd> observe_pass(int step);
  // The state at the end of the step (converged or not) into its record.
  void record_state(StepRecord& res) const;
  // The step loop's pieces (run.cpp).
  // Whether the run resumes: false when it starts (over), a --resume before the first checkpoint
  // included.
  bool start_or_resume(const RunOptions& options);
  void run_steps(const RunOptions& options, int first_step, RunOutputs& outputs, StepMonitor& monitor,
                 BackgroundWriter& writer, RunSummary& summary);
  void save_states(int step, const std::filesystem::path& out_dir, BackgroundWriter& writer) const;

  Scene scene_;
  std::unique_ptr<StripModel> model_;
  LoadProgram loads_;
  std::unique_ptr<ContactBackend> backend_;
  std::vector<Index> candidate_nodes_;
  RollerProgram program_;
  IncrementSolver solver_;
  RunState state_;  // everything a later step reads but the strip and the dynamics (run_state.hpp)
  DynamicsState dynamics_;
  std::unique_ptr<StationaryPasses> stationary_;  // the stationary method's set-up, built at its first pass
  std::ostream* progress_ = nullptr;              // run()'s progress stream, for the stationary iterations
  const std::atomic<int>* stop_ = nullptr;        // run()'s stop request, which the stationary iterations hear
};

}  // namespace roller
