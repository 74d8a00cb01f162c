#include "roller/driver/simulation.hpp"

#include <chrono>
#include <cmath>
#include <fstream>
#include <ostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "roller/analysis/monotonicity.hpp"
#include "roller/assembly/increment_energy.hpp"
#include "roller/contact/contact_set.hpp"
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

}  // namespace

Simulation::Simulation(Scene scene)
    : scene_(std::move(scene)),
      model_(std::make_unique<StripModel>(make_strip_mesh(scene_.mesh), scene_.material, scene_.element)),
      loads_(scene_, model_->mesh()) {
  model_->set_dof_map(loads_.dof_map());
  if (scene_.roller) {
    backend_ = make_contact_backend(scene_.contact, scene_.newton);
    NodeSelector sel;
    sel.set_name = scene_.contact.candidates;
    candidate_nodes_ = resolve_nodes(sel, model_->mesh(), "contact.candidates");
    pose_ = roller_pose(*scene_.roller, start_centre(), 0.0);
  }
}

Vec2 Simulation::start_centre() const {
  if (scene_.roller->start_centre) return *scene_.roller->start_centre;
  // Default: touching the top of the strip at mid-length.
  return Vec2(0.5 * scene_.mesh.length, scene_.mesh.height + scene_.roller->radius);
}

Vec2 Simulation::roller_force() const {
  Vec2 f = Vec2::Zero();
  for (const auto& c : contact_) f -= c.force;
  return f;
}

std::vector<PressureSample> Simulation::pressure_profile() const {
  std::vector<PressureSample> out;
  for (const auto& c : contact_) {
    const bool loaded = c.contact.status != ContactStatus::Open;
    out.push_back({c.position.x() - pose_.centre.x(), loaded ? c.contact.normal_force / c.tributary_length : 0.0});
  }
  return out;
}

Simulation::Increment Simulation::advance(Real s_from, Real s_to) {
  Increment inc;
  // Prescribed increments: target total minus what the dof already has, so sub-increments
  // never accumulate drift.
  const VecX prescribed = loads_.prescribed_displacement(s_to) - model_->total_displacement();
  IncrementEnergy energy(*model_, prescribed, loads_.external_force(s_to));
  // Predictor: the previous converged increment scaled to this one's length (a linear
  // extrapolation of the path), which starts Newton near the solution on smooth paths.
  VecX predictor = VecX::Zero(model_->n_dofs());
  if (last_increment_.size() == model_->n_dofs() && last_length_ > 0.0)
    predictor = last_increment_ * ((s_to - s_from) / last_length_);
  VecX x = model_->dof_map().restrict_to_free(predictor);

  VecX u;
  std::vector<ContactCandidate> candidates;
  BackendResult contact_result;
  if (!scene_.roller) {
    const NewtonReport r = minimise_newton(energy, x, scene_.newton);
    inc.converged = r.converged();
    inc.iterations = r.iterations;
    inc.factorizations = r.factorizations;
    inc.residual = r.residual;
    inc.message = r.message;
    u = energy.full_increment(x);
  } else {
    RollerMotion motion;
    motion.radius = scene_.roller->radius;
    motion.start = roller_pose(*scene_.roller, start_centre(), s_from);
    motion.end = roller_pose(*scene_.roller, start_centre(), s_to);
    motion.friction = scene_.contact.friction;
    // Nodes farther from the roller than it can travel within the increment cannot touch it.
    const Real reach = 0.05 * motion.radius + 4.0 * motion.dc().norm() + 4.0 * predictor.cwiseAbs().maxCoeff();
    candidates = make_contact_candidates(*model_, candidate_nodes_, prescribed, predictor,
                                         motion.end.centre, motion.radius, reach);
    for (auto& c : candidates) {
      const auto h = history_.find(c.node);
      if (h == history_.end()) continue;
      c.tangential_force = h->second.tangential_force;
      c.normal_force_guess = h->second.normal_force;
    }
    IncrementProblem problem(energy, candidates, motion, scene_.material.youngs_modulus,
                             scene_.material.poisson_ratio);
    contact_result = backend_->solve(problem, x);
    // The extrapolated predictor misleads when the roller path turns (press -> roll, the
    // harmonic's crests): retry once from the start-of-step configuration before giving up.
    if (!contact_result.converged() && x.squaredNorm() > 0.0) {
      const int spent = contact_result.iterations;
      contact_result = backend_->solve(problem, VecX::Zero(x.size()));
      contact_result.iterations += spent;
    }
    inc.converged = contact_result.converged();
    inc.iterations = contact_result.iterations;
    inc.factorizations = contact_result.factorizations;
    inc.residual = contact_result.residual;
    inc.max_penetration = contact_result.max_penetration;
    inc.stats = contact_result.stats;
    inc.message = contact_result.message;
    if (inc.converged) {
      u = energy.full_increment(contact_result.x);
      pose_ = motion.end;
    }
  }
  if (!inc.converged) return inc;

  try {
    model_->commit(u);
  } catch (const NumericalError& e) {
    // A solver reported success at a state the strip cannot take (e.g. an inverted element):
    // treat it as a failed increment so the step is cut; nothing was committed.
    inc.converged = false;
    inc.message = fmt::format("the increment's solution is not admissible: {}", e.what());
    return inc;
  }
  last_increment_ = u;
  last_length_ = s_to - s_from;
  if (scene_.roller) {
    contact_.clear();
    history_.clear();
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      const ContactCandidate& c = candidates[i];
      const NodeContact& nc = contact_result.contact[i];
      NodeContactRecord rec;
      rec.node = c.node;
      rec.position = c.position + Vec2(u(2 * c.node), u(2 * c.node + 1));
      rec.contact = nc;
      rec.tributary_length = c.tributary_length;
      rec.element_size = c.element_size;
      const Vec2 n = (rec.position - pose_.centre).normalized();
      rec.force = nc.normal_force * n + nc.tangential_force * c.tangent;
      contact_.push_back(rec);
      if (nc.status != ContactStatus::Open) history_[c.node] = nc;
    }
  }
  return inc;
}

Simulation::StepResult Simulation::advance_step(int step) {
  StepResult res;
  // Sub-increments of 1/2^cuts of the step; a failed sub-increment is halved again.
  Real s = step - 1;
  Real ds = 1.0;
  while (s < step - 1e-12) {
    Increment inc = advance(s, s + ds);
    res.iterations += inc.iterations;
    res.factorizations += inc.factorizations;
    res.last = inc;
    if (inc.converged) {
      s += ds;
      res.max_penetration = std::max(res.max_penetration, inc.max_penetration);
      continue;
    }
    if (res.cuts >= scene_.steps.max_cuts) {
      res.message = fmt::format("step {} failed after {} cuts (sub-increment {:.4g} of the step): {}", step,
                                res.cuts, ds, inc.message);
      return res;
    }
    ++res.cuts;
    ds *= 0.5;
  }
  res.converged = true;
  return res;
}

RunSummary Simulation::run(const RunOptions& options) {
  const auto t_start = Clock::now();
  std::filesystem::create_directories(options.out_dir);
  {
    std::ofstream resolved(options.out_dir / "scene.resolved.toml");
    resolved << scene_to_toml(scene_);
  }
  CsvTable solver_csv(options.out_dir / "solver.csv",
                      {"step", "time", "iterations", "residual", "max_penetration", "wall_s", "cuts",
                       "yielded_points", "factorizations", "complementarity", "constraint_violation",
                       "fixed_point_iterations", "contact_nodes", "a_not_pd_points", "a_lambda_min",
                       "k_eff_positive_definite", "k_eff_negative_pivots", "dt_restore", "status"});
  std::unique_ptr<CsvTable> contact_csv, roller_csv;
  if (scene_.roller) {
    contact_csv = std::make_unique<CsvTable>(
        options.out_dir / "contact.csv",
        std::vector<std::string>{"step", "node", "x", "y", "gap", "p_n", "p_t", "status", "slip"});
    roller_csv = std::make_unique<CsvTable>(
        options.out_dir / "roller.csv", std::vector<std::string>{"step", "time", "xc", "yc", "phi", "fx", "fy"});
    roller_csv->add_row({Index{0}, 0.0, pose_.centre.x(), pose_.centre.y(), pose_.angle, 0.0, 0.0});
  }
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
  bool pointwise_loss_reported = false;
  for (int step = 1; step <= scene_.steps.n_steps; ++step) {
    const auto t_step = Clock::now();
    const StepResult res = advance_step(step);
    const double wall = seconds_since(t_step);
    summary.iterations_total += res.iterations;
    summary.cuts_total += res.cuts;
    summary.max_penetration = std::max(summary.max_penetration, res.max_penetration);
    auto stat = [&](const char* key) {
      const auto it = res.last.stats.find(key);
      return it == res.last.stats.end() ? 0.0 : it->second;
    };
    Index n_contact = 0;
    for (const auto& c : contact_) n_contact += c.contact.status != ContactStatus::Open ? 1 : 0;
    const Index n_yielded = model_->n_yielded_last();  // before the monitor re-evaluates the strip
    // Run-time monotonicity monitor (SPEC §3): operator A at the integration points and the
    // definiteness of the assembled strip tangent (contact terms excluded) at the new state.
    const Real dt_dynamic = 0.0;  // quasistatic strip: no rho/dt^2 term (dynamics: issue 5)
    const StripMonotonicity mono = check_strip(*model_, dt_dynamic);
    SparseMatrix k_eff;
    model_->evaluate(VecX::Zero(model_->n_dofs()), nullptr, &k_eff);
    const SparseDefiniteness kdef = sparse_definiteness(k_eff);
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
    if (!kdef.positive_definite() && options.progress)
      *options.progress << fmt::format(
          "warning: step {}: the assembled tangent stiffness is not positive definite ({} negative, {} zero "
          "pivots) near x = {:.4g}, y = {:.4g} mm: operator A lost monotonicity ({}); {}\n",
          step, kdef.n_negative, kdef.n_zero, where.x(), where.y(), mono.brief_report(),
          mono.dt_restore_all > 0.0 && std::isfinite(mono.dt_restore_all)
              ? fmt::format("a time step below {:.3g} s would restore it (3.18)", mono.dt_restore_all)
              : "in a quasistatic strip no time step restores it: use smaller steps or check the supports");
    solver_csv.add_row({static_cast<Index>(step), step * scene_.steps.dt, static_cast<Index>(res.iterations),
                        res.last.residual, res.max_penetration, wall, static_cast<Index>(res.cuts), n_yielded,
                        static_cast<Index>(res.factorizations), stat("complementarity"),
                        stat("constraint_violation"), stat("fixed_point_iterations"), n_contact,
                        mono.n_not_pd, std::isfinite(mono.lambda_min) ? mono.lambda_min : 0.0,
                        static_cast<Index>(kdef.positive_definite() ? 1 : 0), kdef.n_negative,
                        std::isfinite(mono.dt_restore_all) ? mono.dt_restore_all : 0.0,
                        std::string(res.converged ? "converged" : "failed")});
    if (!res.converged) {
      summary.converged = false;
      summary.message = res.message;
      if (options.progress) *options.progress << "error: " << res.message << "\n";
      break;
    }
    summary.steps_done = step;
    if (scene_.roller) {
      for (const auto& c : contact_)
        contact_csv->add_row({static_cast<Index>(step), c.node + 1, c.position.x(), c.position.y(),
                              c.contact.gap, c.contact.normal_force / c.tributary_length,
                              c.contact.tangential_force / c.tributary_length,
                              std::string(to_string(c.contact.status)), c.contact.slip});
      const Vec2 f = roller_force();
      roller_csv->add_row({static_cast<Index>(step), step * scene_.steps.dt, pose_.centre.x(),
                           pose_.centre.y(), pose_.angle, f.x(), f.y()});
    }
    if (step % scene_.output.every == 0 || step == scene_.steps.n_steps) write_fields(step);
    if (options.progress) {
      std::string contact_text;
      if (scene_.roller)
        contact_text = fmt::format("  contact {:>3}  pen {:8.2e}  Fy {:10.4g}", n_contact, res.max_penetration,
                                   roller_force().y());
      *options.progress << fmt::format(
                               "step {:>4}/{:<4} t={:<9.4g} its {:>3}  |r|/F {:8.2e}  cuts {}  yielded {:>5}{}  {:7.3f} s\n",
                               step, scene_.steps.n_steps, step * scene_.steps.dt, res.iterations, res.last.residual,
                               res.cuts, n_yielded, contact_text, wall)
                        << std::flush;
    }
  }
  summary.wall_s = seconds_since(t_start);
  if (summary.converged) summary.message = fmt::format("{} steps converged", summary.steps_done);

  nlohmann::json j;
  j["scene"] = scene_.name;
  j["backend"] = scene_.roller ? scene_.contact.backend : "none";
  j["ndof"] = model_->n_dofs();
  j["n_free_dofs"] = model_->dof_map().n_free();
  j["n_elements"] = model_->mesh().n_elements();
  j["steps"] = scene_.steps.n_steps;
  j["steps_done"] = summary.steps_done;
  j["converged"] = summary.converged;
  j["wall_s"] = summary.wall_s;
  j["iterations_total"] = summary.iterations_total;
  j["cuts_total"] = summary.cuts_total;
  j["max_penetration"] = summary.max_penetration;
  j["message"] = summary.message;
  std::ofstream(options.out_dir / "summary.json") << j.dump(2) << "\n";
  return summary;
}

}  // namespace roller
