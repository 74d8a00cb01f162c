#pragma once
// The step loop (set-up; for each step: predict, solve, cut back if needed, commit,
// write). Results of completed steps are on disk before the next step starts, so a failure or
// a kill loses nothing already done.
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>

#include "roller/analysis/hertz.hpp"
#include "roller/analysis/pass_metrics.hpp"
#include "roller/assembly/strip_model.hpp"
#include "roller/contact/backend.hpp"
#include "roller/contact/friction_history.hpp"
#include "roller/core/enum_names.hpp"
#include "roller/driver/load_program.hpp"
#include "roller/driver/run_state.hpp"
#include "roller/dynamics/dynamics_state.hpp"
#include "roller/io/scene.hpp"
#include "roller/solver/newton.hpp"

namespace roller {

class RunOutputs;        // driver/run_outputs.hpp
class StepMonitor;       // driver/step_monitor.hpp
class BackgroundWriter;  // io/background_writer.hpp

struct RunOptions {
  std::filesystem::path out_dir = "out";
  std::ostream* progress = nullptr;  // one line per step; nullptr = silent
  // Continue a run in out_dir from its checkpoint.cbor: the output of the steps after the
  // checkpoint is dropped and recomputed, the rest is kept.
  bool resume = false;
  // A fresh run into a folder that is not empty and holds another scene's output (or other
  // files): refused unless overwrite (driver/output_folder.hpp).
  bool overwrite = false;
};

// How a run ended, and the exit code of `roller run` for it (docs/scenes.md, Exit codes).
enum class RunStatus { Running, Completed, StepFailed, InputError, SystemError, InternalError };
template <>
struct EnumNames<RunStatus> {
  static constexpr std::array<std::pair<RunStatus, const char*>, 6> names{
      {{RunStatus::Running, "running"},
       {RunStatus::Completed, "completed"},
       {RunStatus::StepFailed, "step_failed"},
       {RunStatus::InputError, "input_error"},
       {RunStatus::SystemError, "system_error"},
       {RunStatus::InternalError, "internal_error"}}};
};
int exit_code(RunStatus status);
// The status of a run stopped by `e` (InputError, SystemError or out of memory, or a bug).
RunStatus status_of(const std::exception& e);

struct RunSummary {
  RunStatus status = RunStatus::Running;
  bool converged = false;
  int steps_done = 0;
  RunTotals totals;  // over every step of the run, a resumed run's earlier ones included
  double wall_s = 0.0;
  double peak_memory_mb = 0.0;  // the process's peak resident memory so far [MiB]
  std::string message;
};

// A run stopped before its first step (the memory check while the Simulation is built): its
// output folder prepared as run() would, with a summary.json saying why. Nothing when the folder
// cannot be used (the caller reports the first error).
void write_stopped_summary(const Scene& scene, const RunOptions& options, RunStatus status, const std::string& message);

class Simulation {
 public:
  // Builds the mesh and the load program, validating the scene against the mesh (InputError).
  explicit Simulation(Scene scene);

  RunSummary run(const RunOptions& options);

  const Scene& scene() const { return scene_; }
  StripModel& model() { return *model_; }
  const StripModel& model() const { return *model_; }
  // The contact backend of the run (nullptr without a roller); the run-time monitor asks it for
  // the inertia of factors it holds.
  ContactBackend* contact_backend() { return backend_.get(); }
  // Roller pose at the end of the last committed increment, and the contact of that increment.
  const RollerPose& pose() const { return state_.pose; }
  int pass_of_step(int step) const;  // 1-based ([passes]; 1 without)
  // The records of the passes completed so far (multi-pass runs) and what they show.
  const std::vector<PassRecord>& pass_records() const { return state_.pass_records; }
  const std::vector<NodeContactRecord>& contact() const { return state_.contact; }
  Vec2 roller_force() const;  // force of the strip on the roller [N per mm width]
  int steps_done() const { return state_.steps_done; }
  // Strip inertia and suspension at the end of the last step (dynamics_state.hpp).
  const DynamicsState& dynamics() const { return dynamics_; }
  const VecX& velocity() const { return dynamics_.velocity(); }
  const VecX& acceleration() const { return dynamics_.acceleration(); }
  Real kinetic_energy() const { return dynamics_.kinetic_energy(); }
  // Suspended roller (nullptr without suspension): the deflection from the anchor, its rates.
  const Suspension* suspension() const { return dynamics_.suspension(); }
  Real suspension_velocity() const { return dynamics_.suspension_velocity(); }
  Real suspension_acceleration() const { return dynamics_.suspension_acceleration(); }
  // The roller's prescribed pose at (fractional) scene step s: for a suspended roller, its anchor;
  // under force control (roller.path fy) the path without the load offset.
  RollerPose prescribed_pose(Real s) const;
  // Force control: the centre's offset from the path that carries the prescribed forces (kept
  // after the force-controlled segments), and those forces at step s (none: motion).
  Vec2 load_offset() const { return state_.load_offset; }
  PrescribedForce prescribed_force(Real s) const;
  // Roller centre velocity over the last step (backward difference) [mm/s].
  Vec2 roller_velocity() const { return state_.roller_velocity; }

  // State files (CBOR): everything the next step needs, so that a run continued from a saved
  // state gives the same results as an uninterrupted one. load_state() restores the strip and,
  // unless strip_only, the roller, the friction history, the predictor and the step counter.
  void save_state(const std::filesystem::path& file) const;
  // The same in two halves: the state is read now, the returned job writes it (to run on a
  // background thread while the next step changes the model).
  std::function<void()> state_writer(const std::filesystem::path& file) const;
  void load_state(const std::filesystem::path& file, bool strip_only);
  // Nodal contact pressures of the last increment against x measured from the roller centre;
  // open nodes count as unloaded (an interior-point solution leaves barrier-size forces there).
  std::vector<PressureSample> pressure_profile() const;

  // Advances the state from s_from to s_to (scene steps, fractional) with one increment;
  // commits on success (converged = true) and leaves the state untouched on failure.
  struct Increment {
    bool converged = false;
    int iterations = 0;
    int factorizations = 0;
    Real residual = 0.0;
    Real max_penetration = 0.0;
    Index n_yielded = 0;        // integration points that yielded in the committed increment
    BackendStats stats;         // the contact solves' work summed, the rest of the last one
    int suspension_passes = 0;  // passes coupling the suspension with the contact
    int load_passes = 0;        // contact solves finding the height that carries the prescribed force
    std::string message;
  };
  Increment advance(Real s_from, Real s_to);

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
    bool converged = false;
    int cuts = 0;
    int iterations = 0;
    int factorizations = 0;
    BackendStats stats;  // of the step's sub-increments: their work summed, the rest of the last one
    Real max_penetration = 0.0;
    Index n_yielded = 0;  // integration points that yielded in the step's last converged increment
    Increment last;       // the last increment tried
    std::string message;  // why the step failed
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
  };
  StepRecord advance_step(int step);

 private:
  // The scene's start centre (roller.centre or its default), and that moved by roller.touch_strip.
  Vec2 given_start_centre() const;
  Vec2 start_centre() const;
  // roller.touch_strip: how far the start centre moves up (> 0) or down to touch the strip as it
  // is after the initial state; InputError when no contact candidate lies under the roller.
  Real touching_lift() const;
  // Before the first step of pass `pass` > 1: the roller, clear of the strip, returns to the
  // pass's start; a message (and nothing changed) when it is not clear.
  std::string return_for_pass(int pass);
  // The prescribed pose at step `local` (fractional) of pass `pass` (1-based).
  RollerPose pose_in_pass(int pass, Real local) const;
  void check_roller_starts_outside() const;  // InputError naming roller.centre
  // Where an increment starts: the previous converged increment scaled to this one's length
  // (and, as an option, the thesis's arc predictor for nodes that would enter the roller).
  VecX predictor(Real s_from, Real s_to, const RollerMotion* motion) const;
  // The increment's solve: Newton without a roller, the contact backend with one, coupled with
  // the suspension when the roller hangs on one. Fills the increment's counters.
  struct Solution {
    VecX u;  // increment of all dofs (when inc.converged)
    std::vector<ContactCandidate> candidates;
    BackendResult contact;
    Real deflection = 0.0;
    Vec2 load_offset = Vec2::Zero();     // force control: the centre's offset that carries the forces
    Vec2 load_stiffness = Vec2::Zero();  // and the slopes -dF/dw there per axis (0: not force-controlled)
  };
  // `force`: the forces prescribed on the roller (none: its motion is prescribed).
  Solution solve_increment(IncrementEnergy& energy, const VecX& prescribed, VecX predictor, RollerMotion& motion,
                           const PrescribedForce& force, Increment& inc);
  // One contact solve of the increment with the roller at `motion`: the candidates and the
  // backend's result replace `solution`'s (which, when converged, is the last pass's and seeds
  // this one). With `potential` the roller's vertical offset from there is an unknown of the solve
  // (IncrementProblem::free_roller), and `motion` ends where the solve put the roller.
  void solve_contact(IncrementEnergy& energy, const VecX& prescribed, const VecX& predictor, RollerMotion& motion,
                     VecX& x, Solution& solution, const std::optional<RollerPotential>& potential = std::nullopt);
  // Whether a roller whose height is not prescribed is solved with the strip (contact.roller_coupling
  // and a backend that can) rather than by passes.
  bool joint_height() const;
  // solve_contact with the roller's height an unknown carrying `potential`: the offset the solve
  // moved the roller by, or nullopt, with x, `solution` and the centre as they were, when it did not
  // converge or moved it by more than `max_offset` (the caller then couples by passes).
  std::optional<Real> solve_height_jointly(IncrementEnergy& energy, const VecX& prescribed, const VecX& predictor,
                                           RollerMotion& motion, VecX& x, Solution& solution, Increment& inc,
                                           const RollerPotential& potential, Real max_offset);
  // The suspension's vertical force balance with the contact, iterated on the deflection.
  Solution solve_suspended(IncrementEnergy& energy, const VecX& prescribed, const VecX& predictor, RollerMotion& motion,
                           VecX& x, Increment& inc);
  // The prescribed forces, iterated on the centre's height and x (driver/force_control.hpp): a
  // horizontal force by an outer iteration on x whose every solve carries the vertical one.
  Solution solve_loaded(const PrescribedForce& force, IncrementEnergy& energy, const VecX& prescribed,
                        const VecX& predictor, RollerMotion& motion, VecX& x, Increment& inc);
  // The force of the strip on the roller in a contact solution.
  Vec2 strip_force(const Solution& solution, const RollerMotion& motion, IncrementEnergy& energy) const;
  // Accepts a converged increment (transactional: a throw of the strip's commit changes nothing).
  void commit(const Solution& solution, const RollerMotion& motion, Real s_from, Real s_to, Increment& inc);
  void record_contact(const std::vector<ContactCandidate>& candidates, const BackendResult& result, const VecX& u);
  // The step loop's pieces (run.cpp).
  void start_or_resume(const RunOptions& options);
  void run_steps(const RunOptions& options, int first_step, RunOutputs& outputs, StepMonitor& monitor,
                 BackgroundWriter& writer, RunSummary& summary);
  void save_states(int step, const std::filesystem::path& out_dir, BackgroundWriter& writer) const;

  Scene scene_;
  std::unique_ptr<StripModel> model_;
  LoadProgram loads_;
  std::unique_ptr<ContactBackend> backend_;
  std::vector<Index> candidate_nodes_;
  Real start_lift_ = 0.0;  // roller.touch_strip: vertical shift of the start centre [mm]
  RunState state_;         // everything a later step reads but the strip and the dynamics (run_state.hpp)
  DynamicsState dynamics_;
  NewtonMinimiser newton_;  // increments without contact
  // After a converged step: observes the contact; at a pass's last step, measures the pass.
  std::optional<StepRecord::PassEnd> observe_pass(int step);
  // The state at the end of the step (converged or not) into its record.
  void record_state(StepRecord& res) const;
};

}  // namespace roller
