// Simulation::run: the step loop with its outputs (SPEC §6) and the run-time monotonicity
// monitor. Each step's rows are flushed before the next step starts; state files make a killed
// run resumable (RunOptions::resume).
#include <chrono>
#include <cmath>
#include <fstream>
#include <ostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <sys/resource.h>

#include "roller/analysis/monotonicity.hpp"
#include "roller/core/error.hpp"
#include "roller/driver/simulation.hpp"
#include "roller/io/csv_table.hpp"
#include "roller/io/field_output.hpp"
#include "roller/io/scene_loader.hpp"
#include "roller/io/vtu_writer.hpp"

namespace roller {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Peak resident memory of this process [MiB] (Linux reports ru_maxrss in KiB): what
// /usr/bin/time -v prints, so users see whether a mesh needs [linear_solver] out_of_core.
double peak_memory_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

// A table created afresh, or continued after the resumed step.
std::unique_ptr<CsvTable> open_table(const std::filesystem::path& path, std::vector<std::string> columns,
                                     bool resume, int resumed_step) {
  if (resume) return std::make_unique<CsvTable>(path, std::move(columns), resumed_step);
  return std::make_unique<CsvTable>(path, std::move(columns));
}

VtuField nodal_vector(const std::string& name, const VecX& v) {
  VtuField f;
  f.name = name;
  f.n_components = 3;
  f.values.assign(3 * (v.size() / 2), 0.0);
  for (Index a = 0; a < v.size() / 2; ++a) {
    f.values[3 * a] = v(2 * a);
    f.values[3 * a + 1] = v(2 * a + 1);
  }
  return f;
}

}  // namespace

RunSummary Simulation::run(const RunOptions& options) {
  const auto t_start = Clock::now();
  std::filesystem::create_directories(options.out_dir);
  const std::filesystem::path checkpoint = options.out_dir / "checkpoint.cbor";
  if (options.resume) {
    if (!std::filesystem::exists(checkpoint))
      throw InputError(fmt::format("--resume: {} does not exist (the run wrote no checkpoint; set "
                                   "output.checkpoint_every >= 1)",
                                   checkpoint.string()));
    load_state(checkpoint, /*strip_only=*/false);
    if (options.progress)
      *options.progress << fmt::format("resuming after step {} from {}\n", steps_done_, checkpoint.string());
  } else {
    std::ofstream resolved(options.out_dir / "scene.resolved.toml");
    resolved << scene_to_toml(scene_);
  }
  const int first_step = steps_done_ + 1;
  const Real dt = scene_.steps.dt;
  auto solver_csv = open_table(
      options.out_dir / "solver.csv",
      {"step", "time", "iterations", "residual", "max_penetration", "wall_s", "cuts", "yielded_points",
       "factorizations", "complementarity", "constraint_violation", "fixed_point_iterations", "contact_nodes",
       "a_not_pd_points", "a_lambda_min", "k_eff_positive_definite", "k_eff_negative_pivots", "dt_restore",
       "kinetic_energy", "suspension_passes", "linearisations", "nlp_solves", "condensed_dofs", "ipopt_time_s",
       "status"},
      options.resume, steps_done_);
  std::unique_ptr<CsvTable> contact_csv, roller_csv;
  if (scene_.roller) {
    contact_csv = open_table(options.out_dir / "contact.csv",
                             {"step", "node", "x", "y", "gap", "p_n", "p_t", "status", "slip"}, options.resume,
                             steps_done_);
    roller_csv = open_table(options.out_dir / "roller.csv",
                            {"step", "time", "xc", "yc", "phi", "fx", "fy", "vx", "vy", "anchor_y", "deflection",
                             "deflection_velocity", "deflection_acceleration"},
                            options.resume, steps_done_);
    if (!options.resume)
      roller_csv->add_row({Index{0}, 0.0, pose_.centre.x(), pose_.centre.y(), pose_.angle, 0.0, 0.0, 0.0, 0.0,
                           pose_.centre.y(), 0.0, 0.0, 0.0});
  }
  PvdSeries series(options.out_dir / "fields.pvd");
  auto vtu_name = [](int step) { return fmt::format("step_{:04d}.vtu", step); };
  auto write_fields = [&](int step) {
    if (!scene_.output.vtu) return;
    StripFields f = strip_fields(*model_);
    if (scene_.dynamics.strip_inertia) {
      f.point_data.push_back(nodal_vector("velocity", velocity_));
      f.point_data.push_back(nodal_vector("acceleration", acceleration_));
    }
    write_vtu(options.out_dir / vtu_name(step), model_->mesh(), model_->current_coordinates(), f.point_data,
              f.cell_data);
    series.add(step * dt, options.out_dir / vtu_name(step));
  };
  if (options.resume) {
    for (int step = 0; step <= steps_done_; ++step)
      if (std::filesystem::exists(options.out_dir / vtu_name(step)))
        series.add(step * dt, options.out_dir / vtu_name(step));
  } else {
    write_fields(0);
  }

  RunSummary summary;
  summary.converged = true;
  summary.steps_done = steps_done_;
  bool pointwise_loss_reported = false;
  for (int step = first_step; step <= scene_.steps.n_steps; ++step) {
    const auto t_step = Clock::now();
    const StepResult res = advance_step(step);
    const double wall = seconds_since(t_step);
    summary.iterations_total += res.iterations;
    summary.cuts_total += res.cuts;
    summary.max_penetration = std::max(summary.max_penetration, res.max_penetration);
    const BackendStats& stats = res.last.stats;
    Index n_contact = 0;
    for (const auto& c : contact_) n_contact += c.contact.status != ContactStatus::Open ? 1 : 0;
    const Index n_yielded = model_->n_yielded_last();  // before the monitor re-evaluates the strip
    // Run-time monotonicity monitor (SPEC §3): operator A at the integration points and the
    // definiteness of the assembled effective tangent (contact terms excluded) at the new state.
    // Switched off (output.monitor = false) its columns read -1 (not checked).
    const Real dt_dynamic = scene_.dynamics.strip_inertia ? dt : 0.0;
    StripMonotonicity mono;
    SparseDefiniteness kdef;
    if (scene_.output.monitor) {
      mono = check_strip(*model_, dt_dynamic);
      SparseMatrix k_eff;
      model_->evaluate(VecX::Zero(model_->n_dofs()), nullptr, &k_eff);
      if (scene_.dynamics.strip_inertia) k_eff += (2.0 / (dt * dt)) * mass_free_;
      kdef = sparse_definiteness(k_eff);
    }
    // Where: the centroid of the worst element.
    Vec2 where = Vec2::Zero();
    if (mono.worst.element >= 0) {
      const auto x = model_->current_coordinates();
      const auto& element = model_->mesh().elements[mono.worst.element];
      for (Index a : element) where += x[a] / static_cast<Real>(element.size());
    }
    if (mono.n_not_pd > 0 && !pointwise_loss_reported && options.progress) {
      // Reported once: in rolling, shear-dominated plastic points lose pointwise monotonicity
      // routinely while the assembled operator stays positive definite.
      *options.progress << fmt::format(
          "warning: step {}: operator A is not positive definite at {} integration points (worst near "
          "x = {:.4g}, y = {:.4g} mm); further steps report the count in solver.csv\n",
          step, mono.n_not_pd, where.x(), where.y());
      pointwise_loss_reported = true;
    }
    if (scene_.output.monitor && !kdef.positive_definite() && options.progress)
      *options.progress << fmt::format(
          "warning: step {}: the assembled tangent stiffness is not positive definite ({} negative, {} zero "
          "pivots) near x = {:.4g}, y = {:.4g} mm: operator A lost monotonicity ({}); {}\n",
          step, kdef.n_negative, kdef.n_zero, where.x(), where.y(), mono.brief_report(),
          mono.dt_restore_all > 0.0 && std::isfinite(mono.dt_restore_all)
              ? fmt::format("a time step below {:.3g} s would restore it (3.18)", mono.dt_restore_all)
              : "in a quasistatic strip no time step restores it: use smaller steps or check the supports");
    const Index not_checked = -1;
    solver_csv->add_row({static_cast<Index>(step), step * dt, static_cast<Index>(res.iterations), res.last.residual,
                         res.max_penetration, wall, static_cast<Index>(res.cuts), n_yielded,
                         static_cast<Index>(res.factorizations), stats.complementarity,
                         stats.constraint_violation, static_cast<Real>(stats.fixed_point_iterations), n_contact,
                         scene_.output.monitor ? mono.n_not_pd : not_checked,
                         std::isfinite(mono.lambda_min) ? mono.lambda_min : 0.0,
                         scene_.output.monitor ? static_cast<Index>(kdef.positive_definite() ? 1 : 0) : not_checked,
                         scene_.output.monitor ? kdef.n_negative : not_checked,
                         std::isfinite(mono.dt_restore_all) ? mono.dt_restore_all : 0.0, kinetic_energy(),
                         static_cast<Real>(res.last.suspension_passes), static_cast<Real>(stats.linearisations), static_cast<Real>(stats.nlp_solves),
                         static_cast<Real>(stats.condensed_dofs), stats.ipopt_time_s, std::string(res.converged ? "converged" : "failed")});
    if (!res.converged) {
      summary.converged = false;
      summary.message = res.message;
      if (options.progress) *options.progress << "error: " << res.message << "\n";
      break;
    }
    summary.steps_done = step;
    if (scene_.roller) {
      for (const auto& c : contact_)
        contact_csv->add_row({static_cast<Index>(step), c.node + 1, c.position.x(), c.position.y(), c.contact.gap,
                              c.contact.normal_force / c.tributary_length,
                              c.contact.tangential_force / c.tributary_length,
                              std::string(to_string(c.contact.status)), c.contact.slip});
      const Vec2 f = roller_force();
      const Real anchor_y = roller_pose(*scene_.roller, start_centre(), step).centre.y();
      const Real w = suspension_ ? suspension_->deflection() : 0.0;
      roller_csv->add_row({static_cast<Index>(step), step * dt, pose_.centre.x(), pose_.centre.y(), pose_.angle,
                           f.x(), f.y(), roller_velocity_.x(), roller_velocity_.y(), anchor_y, w,
                           suspension_velocity_, suspension_acceleration_});
    }
    if (step % scene_.output.every == 0 || step == scene_.steps.n_steps) write_fields(step);
    // State files after the step's output, so a resumed run never misses rows.
    const auto& keep = scene_.output.save_states;
    if (std::find(keep.begin(), keep.end(), step) != keep.end())
      save_state(options.out_dir / fmt::format("state_{:04d}.cbor", step));
    if (scene_.output.checkpoint_every > 0 && step % scene_.output.checkpoint_every == 0) save_state(checkpoint);
    if (options.progress) {
      std::string contact_text;
      if (scene_.roller)
        contact_text = fmt::format("  contact {:>3}  pen {:8.2e}  Fy {:10.4g}", n_contact, res.max_penetration,
                                   roller_force().y());
      if (suspension_) contact_text += fmt::format("  w {:9.3e}", suspension_->deflection());
      *options.progress << fmt::format(
                               "step {:>4}/{:<4} t={:<9.4g} its {:>3}  |r|/F {:8.2e}  cuts {}  yielded {:>5}{}  {:7.3f} s\n",
                               step, scene_.steps.n_steps, step * dt, res.iterations, res.last.residual,
                               res.cuts, n_yielded, contact_text, wall)
                        << std::flush;
    }
  }
  if (summary.converged) save_state(options.out_dir / "state_final.cbor");
  summary.wall_s = seconds_since(t_start);
  summary.peak_memory_mb = peak_memory_mb();
  if (summary.converged) summary.message = fmt::format("{} steps converged", summary.steps_done);

  nlohmann::json j;
  j["scene"] = scene_.name;
  j["backend"] = scene_.roller ? enum_name(scene_.contact.backend) : "none";
  j["ndof"] = model_->n_dofs();
  j["n_free_dofs"] = model_->dof_map().n_free();
  j["n_elements"] = model_->mesh().n_elements();
  j["steps"] = scene_.steps.n_steps;
  j["steps_done"] = summary.steps_done;
  j["first_step"] = first_step;
  j["resumed"] = options.resume;
  j["strip_inertia"] = scene_.dynamics.strip_inertia;
  j["suspension"] = suspension_.has_value();
  j["converged"] = summary.converged;
  j["wall_s"] = summary.wall_s;
  j["peak_memory_mb"] = summary.peak_memory_mb;
  j["iterations_total"] = summary.iterations_total;
  j["cuts_total"] = summary.cuts_total;
  j["max_penetration"] = summary.max_penetration;
  j["message"] = summary.message;
  std::ofstream(options.out_dir / "summary.json") << j.dump(2) << "\n";
  return summary;
}

}  // namespace roller
