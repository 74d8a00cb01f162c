#include "roller/driver/simulation.hpp"

#include <chrono>
#include <fstream>
#include <ostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "roller/assembly/increment_energy.hpp"
#include "roller/core/error.hpp"
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

Mesh build_mesh(const Scene& scene) { return make_strip_mesh(scene.mesh); }

}  // namespace

struct Simulation::Increment {
  NewtonReport report;
  VecX u;
};

Simulation::Simulation(Scene scene)
    : scene_(std::move(scene)),
      model_(std::make_unique<StripModel>(build_mesh(scene_), scene_.material, scene_.element)),
      loads_(scene_, model_->mesh()) {
  model_->set_dof_map(loads_.dof_map());
}

Simulation::Increment Simulation::solve_increment(Real s_from, Real s_to) {
  // Prescribed increments: target total minus what the dof already has, so sub-increments
  // never accumulate drift.
  VecX prescribed = loads_.prescribed_displacement(s_to) - model_->total_displacement();
  IncrementEnergy energy(*model_, prescribed, loads_.external_force(s_to));
  Increment inc;
  // Predictor: the previous converged increment scaled to this one's length (a linear
  // extrapolation of the path), which starts Newton near the solution on smooth paths.
  VecX x = VecX::Zero(model_->dof_map().n_free());
  if (last_increment_.size() == model_->n_dofs() && last_length_ > 0.0)
    x = model_->dof_map().restrict_to_free(last_increment_) * ((s_to - s_from) / last_length_);
  inc.report = minimise_newton(energy, x, scene_.newton);
  inc.u = energy.full_increment(x);
  return inc;
}

RunSummary Simulation::run(const RunOptions& options) {
  const auto t_start = Clock::now();
  std::filesystem::create_directories(options.out_dir);
  {
    std::ofstream resolved(options.out_dir / "scene.resolved.toml");
    resolved << scene_to_toml(scene_);
  }
  CsvTable solver_csv(options.out_dir / "solver.csv",
                      {"step", "time", "iterations", "residual", "cuts", "yielded_points",
                       "factorizations", "wall_s", "status"});
  PvdSeries series(options.out_dir / "fields.pvd");
  auto write_fields = [&](int step) {
    if (!scene_.output.vtu) return;
    const std::string name = fmt::format("step_{:04d}.vtu", step);
    const StripFields f = strip_fields(*model_);
    write_vtu(options.out_dir / name, model_->mesh(), model_->current_coordinates(), f.point_data,
              f.cell_data);
    series.add(step * scene_.steps.dt, options.out_dir / name);
  };
  write_fields(0);

  RunSummary summary;
  summary.converged = true;
  for (int step = 1; step <= scene_.steps.n_steps; ++step) {
    const auto t_step = Clock::now();
    int cuts = 0, iterations = 0, factorizations = 0;
    Real residual = 0.0;
    bool ok = true;
    std::string failure;
    // Sub-increments of 1/2^cuts of the step; a failed sub-increment is halved again.
    Real s = step - 1;
    Real ds = 1.0;
    while (s < step - 1e-12) {
      Increment inc = solve_increment(s, s + ds);
      iterations += inc.report.iterations;
      factorizations += inc.report.factorizations;
      if (inc.report.converged()) {
        model_->commit(inc.u);
        last_increment_ = inc.u;
        last_length_ = ds;
        s += ds;
        residual = inc.report.residual;
        continue;
      }
      if (cuts >= scene_.steps.max_cuts) {
        ok = false;
        failure = fmt::format("step {} failed after {} cuts (sub-increment {:.4g} of the step): {}",
                              step, cuts, ds, inc.report.message);
        break;
      }
      ++cuts;
      ds *= 0.5;
    }
    const double wall = seconds_since(t_step);
    summary.iterations_total += iterations;
    summary.cuts_total += cuts;
    solver_csv.add_row({static_cast<Index>(step), step * scene_.steps.dt, static_cast<Index>(iterations),
                        residual, static_cast<Index>(cuts), model_->n_yielded_last(),
                        static_cast<Index>(factorizations), wall, std::string(ok ? "converged" : "failed")});
    if (!ok) {
      summary.converged = false;
      summary.message = failure;
      if (options.progress) *options.progress << "error: " << failure << "\n";
      break;
    }
    summary.steps_done = step;
    if (step % scene_.output.every == 0 || step == scene_.steps.n_steps) write_fields(step);
    if (options.progress)
      *options.progress << fmt::format(
          "step {:>4}/{:<4} t={:<10.4g} newton {:>2}  |r|/F {:8.2e}  cuts {}  yielded {:>5}  {:7.3f} s\n",
          step, scene_.steps.n_steps, step * scene_.steps.dt, iterations, residual, cuts,
          model_->n_yielded_last(), wall)
                        << std::flush;
  }
  summary.wall_s = seconds_since(t_start);
  if (summary.converged) summary.message = fmt::format("{} steps converged", summary.steps_done);

  nlohmann::json j;
  j["scene"] = scene_.name;
  j["backend"] = "none";
  j["ndof"] = model_->n_dofs();
  j["n_free_dofs"] = model_->dof_map().n_free();
  j["n_elements"] = model_->mesh().n_elements();
  j["steps"] = scene_.steps.n_steps;
  j["steps_done"] = summary.steps_done;
  j["converged"] = summary.converged;
  j["wall_s"] = summary.wall_s;
  j["iterations_total"] = summary.iterations_total;
  j["cuts_total"] = summary.cuts_total;
  j["message"] = summary.message;
  std::ofstream(options.out_dir / "summary.json") << j.dump(2) << "\n";
  return summary;
}

}  // namespace roller
