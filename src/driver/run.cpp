// Simulation::run: the step loop with its outputs (docs/scenes.md, Output) and the run-time
// monotonicity monitor. Each step's rows are flushed before the next step starts; state files
// make a killed run resumable (RunOptions::resume).
#include <algorithm>
#include <chrono>
#include <fstream>
#include <optional>
#include <ostream>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <sys/resource.h>

#include "file_outputs.hpp"
#include "output_folder.hpp"
#include "pass_fatigue.hpp"
#include "roller/core/error.hpp"
#include "roller/driver/simulation.hpp"
#include "roller/driver/step_monitor.hpp"
#include "roller/io/atomic_file.hpp"
#include "roller/io/background_writer.hpp"
#include "roller/io/scene_loader.hpp"
#include "roller/io/scene_warnings.hpp"
#include "roller/io/track_ends.hpp"
#include "roller/solver/solver_abort.hpp"
#include "run_model.hpp"
#include "run_outputs.hpp"
#include "step_method.hpp"

namespace roller {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Peak resident memory of this process [MiB] (Linux reports ru_maxrss in KiB): what
// /usr/bin/time -v prints, so users see whether a mesh needs [linear_solver] out_of_core.
double peak_memory_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

void print_progress(std::ostream& out, const Scene& scene, const Simulation::StepRecord& res, double wall_s) {
  std::string contact_text;
  if (res.roller)
    contact_text = fmt::format("  contact {:>3}  pen {:8.2e}  Fy {:10.4g}", res.n_contact(), res.max_penetration,
                               res.roller->force.y());
  if (res.roller && scene.roller->suspension) contact_text += fmt::format("  w {:9.3e}", res.roller->deflection);
  const std::string pass_text =
      scene.passes.count > 1 ? fmt::format("pass {:>2}/{:<2} ", res.pass, scene.passes.count) : "";
  out << fmt::format("{}step {:>4}/{:<4} t={:<9.4g} its {:>3}  |r|/F {:8.2e}  cuts {}  yielded {:>5}{}  {:7.3f} s\n",
                     pass_text, res.step, scene.total_steps(), res.time, res.counters.iterations, res.last.residual,
                     res.cuts, res.n_yielded, contact_text, wall_s)
      << std::flush;
}

// A line at each pass's end: what it left (the mean increment of plastic strain in the track, and
// its ratio to pass 1's, which the verdict reads), the time so far and the time the passes left
// would take at this run's pace.
void print_pass_line(std::ostream& out, const std::vector<PassRecord>& passes, int count, std::size_t done_here,
                     double elapsed) {
  const PassRecord& last = passes.back();
  const Real first = passes.front().mean_plastic_increment;
  const std::string ratio = first > 0.0 && passes.size() > 1
                                ? fmt::format(" ({:.3g} of pass 1's)", last.mean_plastic_increment / first)
                                : std::string();
  const int left = count - static_cast<int>(passes.size());
  const std::string eta =
      left > 0 && done_here > 0 ? fmt::format(", about {:.0f} s to go", elapsed / done_here * left) : std::string();
  out << fmt::format("roller: pass {}/{} done: mean plastic strain increment {:.3g}{}, largest {:.3g}; {:.1f} s{}\n",
                     last.pass, count, last.mean_plastic_increment, ratio, last.max_plastic_increment, elapsed, eta)
      << std::flush;
}

// The Hertz peak pressure of the largest prescribed force over the shear yield stress
// k = sigma_y / sqrt(3): Johnson's load measure for shakedown (docs/validation.md, Shakedown);
// none without a yield stress or a prescribed force.
std::optional<Real> p0_over_k(const Scene& scene) {
  if (!scene.roller || !scene.material.plastic) return std::nullopt;
  Real load = 0.0;
  for (const PathSegment& seg : scene.roller->path)
    if (seg.fy) load = std::max(load, *seg.fy);
  if (!(load > 0.0)) return std::nullopt;
  // As roller.path[].p0_over_k: Hertz on the surface's E*, k of [material].
  const Real e_star = scene.contact_modulus();
  const Real p0 = hertz_line_contact(load, scene.roller->radius, e_star).peak;
  return p0 / (scene.material.yield_stress / std::sqrt(3.0));
}

// summary.json's reserve: the document is about 1 kB; a run's end writes it into this space
// when the disk has filled up (io/atomic_file.hpp).
constexpr std::size_t kSummaryReserve = 16384;

// The track of the run's last pass (io/track_ends.hpp), if it saw one.
std::optional<TrackEnds> last_track(const Simulation& sim) {
  const std::vector<PassRecord>& passes = sim.state().pass_records;
  return passes.empty() ? std::nullopt : track_ends(sim.scene(), passes.back());
}

// The keys every summary.json has, a run stopped before its first step's included.
nlohmann::json summary_head(const Scene& scene, const RunSummary& summary, bool resumed) {
  nlohmann::json j;
  j["scene"] = scene.name;
  j["status"] = enum_name(summary.status);
  j["exit_code"] = exit_code(summary.status, summary.signal);
  j["steps"] = scene.total_steps();
  j["steps_done"] = summary.steps_done;
  j["resumed"] = resumed;
  j["converged"] = summary.converged;
  j["message"] = summary.message;
  return j;
}

std::string summary_json(const Simulation& sim, const RunSummary& summary, int first_step, bool resumed) {
  const Scene& scene = sim.scene();
  nlohmann::json j = summary_head(scene, summary, resumed);
  j["backend"] = scene.roller ? enum_name(scene.contact.backend) : "none";
  j["ndof"] = sim.model().n_dofs();
  j["n_free_dofs"] = sim.model().dof_map().n_free();
  j["n_elements"] = sim.model().mesh().n_elements();
  j["first_step"] = first_step;
  j["strip_inertia"] = scene.dynamics.strip_inertia;
  j["suspension"] = sim.dynamics().suspension() != nullptr;
  j["wall_s"] = summary.wall_s;
  j["peak_memory_mb"] = summary.peak_memory_mb;
  j["iterations_total"] = summary.totals.iterations;
  j["cuts_total"] = summary.totals.cuts;
  j["max_penetration"] = summary.totals.max_penetration;
  j["warnings"] = scene_warnings(scene, sim.model().mesh());
  for (const std::string& w : summary.warnings) j["warnings"].push_back(w);
  if (const std::optional<ShakedownClassification>& c = summary.verdict) {
    j["passes"] = {
        {"count", sim.state().pass_records.size()}, {"verdict", enum_name(c->verdict)}, {"criterion", c->criterion}};
    if (const std::optional<Real> ratio = p0_over_k(scene)) j["passes"]["p0_over_k"] = *ratio;
    if (const std::optional<TrackEnds> track = last_track(sim)) j["passes"]["track"] = track->to_json();
  }
  if (const std::optional<FatigueAnswer>& f = sim.state().fatigue) j["fatigue"] = *f;
  return j.dump(2) + "\n";
}

void write_summary(const std::filesystem::path& file, const Simulation& sim, const RunSummary& summary, int first_step,
                   bool resumed) {
  write_reserved(file, summary_json(sim, summary, first_step, resumed));
}

}  // namespace

void write_stopped_summary(const Scene& scene, const RunOptions& options, RunStatus status,
                           const std::string& message) {
  try {
    if (!options.resume) prepare_output_folder(options.out_dir, scene.name, options.overwrite);
    RunSummary summary;
    summary.status = status;
    summary.message = message;
    write_file_atomically(options.out_dir / "summary.json",
                          summary_head(scene, summary, options.resume).dump(2) + "\n");
  } catch (const std::exception&) {
  }
}

int exit_code(RunStatus status, int signal) {
  switch (status) {
    case RunStatus::Interrupted: return 128 + signal;
    case RunStatus::Running:
    case RunStatus::Completed: return 0;
    case RunStatus::StepFailed: return 1;
    case RunStatus::InputError: return 2;
    case RunStatus::SystemError: return 3;
    case RunStatus::InternalError: return 4;
  }
  return 4;
}

std::string message_of(const std::exception& e) {
  if (dynamic_cast<const std::bad_alloc*>(&e))
    return "out of memory; use a coarser mesh (smaller refine) or [linear_solver] out_of_core = true, or raise the "
           "memory limit (ulimit -v)";
  return e.what();
}

RunStatus status_of(const std::exception& e) {
  if (dynamic_cast<const InputError*>(&e)) return RunStatus::InputError;
  if (dynamic_cast<const SystemError*>(&e) || dynamic_cast<const std::bad_alloc*>(&e)) return RunStatus::SystemError;
  return RunStatus::InternalError;
}

RunSummary Simulation::run(const RunOptions& options) {
  const auto t_start = Clock::now();
  const bool resumed = start_or_resume(options);
  const int first_step = run_->state.steps_done + 1;
  const bool files = options.write_files;
  const std::filesystem::path summary_file = options.out_dir / "summary.json";
  RunSummary summary;
  summary.steps_done = run_->state.steps_done;
  // Written now with room to spare, so that the run's end can still say why it stopped when the
  // disk fills up meanwhile.
  if (files) write_with_reserve(summary_file, summary_json(*this, summary, first_step, resumed), kSummaryReserve);
  // VTU and state files are written while the next step is solved (io/background_writer.hpp),
  // except when the factors go to disk to save memory: the jobs' copies would undo that.
  BackgroundWriter writer(!run_->scene.newton.linear.out_of_core);
  summary.converged = true;
  auto finish_summary = [&] {
    if (run_->scene.passes.count > 1) summary.verdict = classify_passes(run_->state.pass_records);
    summary.totals = run_->state.totals;
    summary.warnings = run_->state.warnings;
    summary.wall_s = seconds_since(t_start);
    summary.peak_memory_mb = peak_memory_mb();
  };
  // A run stopped by an error: summary.json says how far it came and why (a failure to write it
  // adds nothing to the first error).
  auto record_stop = [&](RunStatus status, const std::string& message) {
    summary.converged = false;
    summary.status = status;
    summary.message = message;
    finish_summary();
    try {
      if (files) write_summary(summary_file, *this, summary, first_step, resumed);
    } catch (const std::exception&) {
    }
  };
  // MUMPS's abort (an allocation failed inside a factorisation) ends the process: what the
  // steps before wrote stays, and summary.json says why.
  const SolverAbortGuard on_solver_abort([&](const std::string& message) {
    writer.drain();
    record_stop(RunStatus::SystemError, message);
  });
  try {
    std::optional<FileOutputs> file_outputs;
    std::vector<OutputSink*> sinks;
    if (files) {
      file_outputs.emplace(run_->scene, run_->strip->mesh(), options.out_dir, resumed, run_->state.steps_done, writer);
      sinks.push_back(&*file_outputs);
    }
    if (options.sink) sinks.push_back(options.sink);
    RunOutputs outputs(run_->scene, *run_->strip, run_->dynamics, run_->state.pose, !resumed, std::move(sinks));
    StepMonitor monitor(run_->scene.output.monitor, run_->scene.steps.dt,
                        run_->scene.dynamics.strip_inertia ? &run_->dynamics.mass_free() : nullptr, run_->backend.get(),
                        options.progress, run_->scene.passes.method == PassMethod::Stationary);
    run_steps(options, first_step, outputs, monitor, writer, summary);
    writer.finish();
    if (files && summary.status == RunStatus::Interrupted) {
      // The checkpoint of the last step done, so that --resume goes on from there.
      if (run_->scene.output.checkpoint_every > 0) save_state(options.out_dir / "checkpoint.cbor");
    } else if (files && summary.converged) {
      // The checkpoint of the last step holds the same state: a copy instead of a second
      // serialisation (at 2.9e5 dofs 37 MB, 0.4 s).
      const std::filesystem::path checkpoint = options.out_dir / "checkpoint.cbor";
      const int every = run_->scene.output.checkpoint_every;
      if (every > 0 && run_->state.steps_done % every == 0 && std::filesystem::exists(checkpoint))
        copy_file_atomically(checkpoint, options.out_dir / "state_final.cbor", "the state file");
      else
        save_state(options.out_dir / "state_final.cbor");
    }
  } catch (const std::exception& e) {
    // Whatever stops the run (a full disk, out of memory, a bug), the steps done so far are on
    // disk and summary.json says how far the run came and why it stopped.
    try {
      writer.finish();  // the files of the steps done; a second error adds nothing to the first
    } catch (const std::exception&) {
    }
    record_stop(status_of(e), message_of(e));
    throw;
  }
  finish_summary();
  if (summary.status != RunStatus::Interrupted)
    summary.status = summary.converged ? RunStatus::Completed : RunStatus::StepFailed;
  if (summary.status == RunStatus::Completed)
    summary.message =
        summary.decided
            ? fmt::format("{} steps converged; the verdict was decided after pass {} of {} (passes.until_verdict)",
                          summary.steps_done, run_->state.pass_records.size(), run_->scene.passes.count)
            : fmt::format("{} steps converged", summary.steps_done);
  // The answer of a multi-pass run on its last line: the verdict and the rule that gave it.
  if (summary.status == RunStatus::Completed && summary.verdict) {
    summary.message += fmt::format("; verdict after {} passes: {} ({})", run_->state.pass_records.size(),
                                   enum_name(summary.verdict->verdict), summary.verdict->criterion);
    if (const std::optional<TrackEnds> track = last_track(*this); track && track->kind == TrackKind::Finite)
      summary.message += "; " + track->note();
    if (const std::optional<FatigueAnswer>& f = run_->state.fatigue) summary.message += "; " + describe(*f);
  }
  if (files) write_summary(summary_file, *this, summary, first_step, resumed);
  return summary;
}

void Simulation::run_steps(const RunOptions& options, int first_step, RunOutputs& outputs, StepMonitor& monitor,
                           BackgroundWriter& writer, RunSummary& summary) {
  auto interrupt = [&](int step) {
    summary.status = RunStatus::Interrupted;
    summary.signal = *options.stop_signal;
    summary.converged = false;
    summary.message =
        fmt::format("interrupted by signal {} after step {}; continue with --resume", summary.signal, step - 1);
    if (options.progress) *options.progress << "roller: " << summary.message << "\n";
  };
  const std::size_t passes_at_start = run_->state.pass_records.size();
  double elapsed = 0.0;  // the steps' wall time in this run
  for (int step = first_step; step <= run_->scene.total_steps(); ++step) {
    if (options.stop_signal && *options.stop_signal != 0) {
      interrupt(step);
      break;
    }
    const auto t_step = Clock::now();
    const std::size_t passes_before = run_->state.pass_records.size();
    const StepRecord res = method_->advance(step, StepOptions{options.progress, options.stop_signal});
    const double wall = seconds_since(t_step);
    // A stationary pass left for a stop request: nothing of it is kept, the run resumes before it.
    if (res.status == Termination::Interrupted && options.stop_signal && *options.stop_signal != 0) {
      interrupt(step);
      break;
    }
    run_->state.totals.iterations += res.counters.iterations;
    run_->state.totals.cuts += res.cuts;
    run_->state.totals.max_penetration = std::max(run_->state.totals.max_penetration, res.max_penetration);
    const MonitorReport checked = monitor.check(step, *run_->strip, run_->state.pointwise_loss_reported);
    run_->state.pointwise_loss_reported = run_->state.pointwise_loss_reported || checked.pointwise_loss_first;
    for (const std::string& w : checked.warnings) {
      // Each kind once: the text after "step N: " up to its numbers.
      const std::string kind = w.substr(w.find(": ") + 2, 40);
      if (std::none_of(run_->state.warnings.begin(), run_->state.warnings.end(),
                       [&](const std::string& seen) { return seen.substr(seen.find(": ") + 2, 40) == kind; }))
        run_->state.warnings.push_back(w);
    }
    outputs.write_solver_row(res, checked, wall);
    if (!res.converged()) {
      summary.converged = false;
      summary.message = res.message;
      if (options.progress) *options.progress << "error: " << res.message << "\n";
      break;
    }
    summary.steps_done = step;
    outputs.write_step(res);
    if (options.write_files)
      save_states(step, options.out_dir, writer);  // after the step's output, so a resumed run never misses rows
    elapsed += wall;
    if (options.progress) print_progress(*options.progress, run_->scene, res, wall);
    if (options.progress && res.pass_end && run_->scene.passes.count > 1)
      print_pass_line(*options.progress, run_->state.pass_records, run_->scene.passes.count,
                      run_->state.pass_records.size() - passes_at_start, elapsed);
    if (run_->scene.passes.until_verdict && run_->state.pass_records.size() > passes_before &&
        classify_passes(run_->state.pass_records).verdict != ShakedownVerdict::Undetermined) {
      summary.decided = true;
      break;
    }
  }
}

bool Simulation::start_or_resume(const RunOptions& options) {
  const std::filesystem::path checkpoint = options.out_dir / "checkpoint.cbor";
  if (!options.write_files) {
    if (options.resume) throw InputError("a run that writes no files cannot resume: it has no checkpoint");
    return false;
  }
  bool resume = options.resume;
  std::error_code ec;
  if (resume && !std::filesystem::exists(checkpoint, ec)) {
    if (run_->scene.output.checkpoint_every < 1)
      throw InputError(
          fmt::format("--resume: {} does not exist: this scene keeps no checkpoint (output.checkpoint_every = {}); "
                      "run it without --resume, with output.checkpoint_every >= 1 to make later runs resumable",
                      checkpoint.string(), run_->scene.output.checkpoint_every));
    // Stopped before its first checkpoint: nothing done is lost by starting over.
    if (options.progress)
      *options.progress << fmt::format(
          "roller: --resume: {} holds no checkpoint yet (the run stopped before its first one): starting over\n",
          options.out_dir.string());
    resume = false;
  }
  if (!resume) {
    prepare_output_folder(options.out_dir, run_->scene.name, options.overwrite);
    write_file_atomically(options.out_dir / "scene.resolved.toml", scene_to_toml(run_->scene));
    return false;
  }
  load_state(checkpoint, /*strip_only=*/false);
  if (options.progress)
    *options.progress << fmt::format("resuming after step {} from {}\n", run_->state.steps_done, checkpoint.string());
  return true;
}

void Simulation::save_states(int step, const std::filesystem::path& out_dir, BackgroundWriter& writer) const {
  const auto& keep = run_->scene.output.save_states;
  if (std::find(keep.begin(), keep.end(), step) != keep.end())
    writer.submit(state_writer(out_dir / fmt::format("state_{:04d}.cbor", step)));
  if (run_->scene.output.checkpoint_every > 0 && step % run_->scene.output.checkpoint_every == 0)
    writer.submit(state_writer(out_dir / "checkpoint.cbor"));
}

}  // namespace roller
