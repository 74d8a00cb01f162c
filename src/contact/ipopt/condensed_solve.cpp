#include "condensed_solve.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

namespace roller::ipopt_detail {

namespace {

constexpr int kMaxLinearisations = 30;
constexpr int kMaxBacktracks = 12;

// Merit of a point: strip energy + friction (with the pass's weights) + nu * penetration.
Real merit(const IncrementProblem& problem, const std::vector<RowMap>& rows, const FrictionTerms& friction, Real energy,
           const VecX& x, Real nu) {
  Real m = energy;
  const auto& cands = problem.candidates();
  for (std::size_t j = 0; j < friction.rows.size(); ++j) {
    const Real s = problem.slip(cands[rows[friction.rows[j]].candidate], x);
    m += friction.weight[j] * (friction.split() ? std::abs(s) : std::sqrt(s * s + friction.eps * friction.eps));
  }
  for (const auto& c : cands)
    if (c.free_dof[0] >= 0 || c.free_dof[1] >= 0) m += nu * std::max(0.0, -problem.gap(c, x));
  return m;
}

CondensedOutcome formulation_failed(BackendResult result, Termination status, std::string message) {
  result.status = status;
  result.message = std::move(message);
  return {std::move(result), true};
}

}  // namespace

CondensedSolve::CondensedSolve(const IncrementProblem& problem, const ContactOptions& options,
                               SchurCondenser& condenser)
    : problem_(problem),
      o_(options.ipopt),
      condenser_(condenser),
      spring_(problem.roller_potential()),
      tangent_changes_(!problem.strip_tangent_is_constant()) {}

Real CondensedSolve::rim_energy(const VecX& w) const {
  return problem_.rim() ? 0.5 * w.dot(problem_.rim()->stiffness * w) : 0.0;
}

void CondensedSolve::move_rim(const VecX& w0, Real alpha, const VecX& dw) {
  if (problem_.rim()) problem_.set_rim_displacement(w0 + alpha * dw);
}

CondensedOutcome CondensedSolve::run(const VecX& x0) {
  if (End end = start(x0)) return std::move(*end);
  for (int outer = 1; outer <= kMaxLinearisations && !converged_; ++outer) {
    linearisations_ = outer;
    if (End end = condense_working_set()) return std::move(*end);
    OrEnd<ModelStep> model = solve_model(outer);
    if (auto* end = std::get_if<CondensedOutcome>(&model)) return std::move(*end);
    const ModelStep& answer = std::get<ModelStep>(model);
    const Step step = whole_step(answer);
    OrEnd<Trial> trial = line_search(outer, step, answer.friction);
    if (auto* end = std::get_if<CondensedOutcome>(&trial)) return std::move(*end);
    if (End end = relinearise(std::get<Trial>(std::move(trial)))) return std::move(*end);
  }
  return finish();
}

// The strip at the start vector, the increment's scales, Ipopt, and the first working set.
CondensedSolve::End CondensedSolve::start(const VecX& x0) {
  const auto& cands = problem_.candidates();
  const std::size_t n_c = cands.size();
  result_.x = x0;
  result_.contact.assign(n_c, NodeContact{});
  x_ = x0;
  const Expected<ObjectiveValue> start = problem_.strip_energy(x_, &g_, &k_eff_);
  if (!start)
    return formulation_failed(result_, Termination::Failed,
                              fmt::format("ipopt backend: the strip cannot be evaluated at the start vector ({}); "
                                          "use smaller steps (a larger steps.count, or steps.max_cuts)",
                                          start.error()));
  energy_ = start->value;
  scales_ = increment_scales(problem_, x0, start->force_scale);
  app_ = make_application(o_, scales_);
  if (app_->Initialize("") != Ipopt::Solve_Succeeded)
    return formulation_failed(result_, Termination::Failed, "ipopt backend: Ipopt failed to initialise");
  fixed_point_.emplace(problem_, o_, scales_.force);
  normal_.assign(n_c, 0.0);
  tangential_.assign(n_c, 0.0);
  fbar_used_ = fixed_point_->fbar();
  has_friction_.assign(n_c, false);
  for (std::size_t i = 0; i < n_c; ++i) {
    normal_[i] = std::max(cands[i].normal_force_guess, 0.0);
    tangential_[i] = cands[i].tangential_force;
  }
  working_ = initial_working_set(problem_, x_, scales_.length);
  return std::nullopt;
}

// Condensation of K onto the working candidates' free dofs.
CondensedSolve::End CondensedSolve::condense_working_set() {
  const SchurCondenser::Outcome condensed = condense(problem_, working_, x_, g_, k_eff_, condenser_, &cond_);
  if (condensed == SchurCondenser::Outcome::Failed)
    return formulation_failed(
        result_, Termination::Failed,
        fmt::format("ipopt backend (condensed): the strip tangent cannot be factorised on its interior dofs ({}): "
                    "the strip is held against rigid-body motion only through contact",
                    condenser_.message()));
  if (condensed == SchurCondenser::Outcome::Factorised) ++result_.counters.factorizations;
  return std::nullopt;
}

// The friction fixed point on this linearisation (Tresca passes on the dense NLP). Far from
// convergence one pass per linearisation suffices (Fbar follows the linearisations); the fixed
// point is converged once the model is close (model error <= 1e-3).
CondensedSolve::OrEnd<CondensedSolve::ModelStep> CondensedSolve::solve_model(int outer) {
  const auto m = static_cast<Index>(cond_.dofs.size());
  fixed_point_->restart();
  ModelStep answer;
  answer.d_c = VecX::Zero(m);
  if (m == 0) {  // no working candidate: the strip alone (and the roller hangs free)
    if (spring_ && !(spring_->stiffness > 0.0))
      return formulation_failed(result_, Termination::Failed,
                                "ipopt backend (condensed): the roller carries a prescribed force but touches no "
                                "candidate: nothing holds it");
    if (spring_) answer.dw = -spring_->derivative(problem_.roller_offset()) / spring_->stiffness;
    if (problem_.rim()) answer.rim = VecX::Zero(problem_.n_rim());  // nothing loads the rim
    fixed_point_converged_ = true;
    std::fill(normal_.begin(), normal_.end(), 0.0);
    std::fill(tangential_.begin(), tangential_.end(), 0.0);
    std::fill(has_friction_.begin(), has_friction_.end(), false);
    details().nlp_variables = 0;
    details().nlp_constraints = 0;
    return answer;
  }
  NlpStart start;
  for (const RowMap& r : cond_.rows) {
    start.guess.normal.push_back(normal_[r.candidate]);
    start.guess.tangential.push_back(tangential_[r.candidate]);
  }
  QuadraticModel strip = spring_ ? QuadraticModel(cond_, *spring_, problem_.roller_offset()) : QuadraticModel(cond_);
  // An elastic roller's rim displacements follow the condensed strip's variables, as in the full
  // formulation (docs/model.md, Elastic roller): absolute, since their energy is exactly quadratic.
  std::optional<RimObjective> with_rim;
  if (problem_.rim()) with_rim.emplace(strip, problem_.rim()->stiffness);
  NlpObjective& model = with_rim ? static_cast<NlpObjective&>(*with_rim) : strip;
  start.primal = VecX::Zero(model.n());
  if (with_rim) start.primal.tail(problem_.n_rim()) = problem_.rim_displacement();
  const int max_passes = fixed_point_->iterated() ? o_.fixed_point_max : 1;
  const int passes_here = outer > 1 && model_error_ <= 1e-3 ? max_passes : 1;
  const FrictionPasses passes = solve_friction_passes(*app_, model, problem_, cond_.rows, *fixed_point_,
                                                      std::move(start), passes_here, o_.warm_start, o_);
  result_.counters.iterations += passes.iterations;
  details().nlp_solves += passes.nlp_solves;
  details().cold_restarts += passes.cold_restarts;
  details().ipopt_time_s += passes.ipopt_time_s;
  details().acceptable_level = details().acceptable_level || passes.acceptable_level;
  if (passes.status != Termination::Converged) {
    // Ipopt's own failure on the small NLP: reported as such (the driver cuts the step), no
    // fall-back to the full formulation, which would meet the same NLP.
    result_.status = passes.status;
    result_.message =
        fmt::format("{} (condensed NLP, linearisation {}, friction pass {})", passes.message, outer, passes.passes);
    return CondensedOutcome{std::move(result_), false};
  }
  passes_last_ = passes.passes;
  fixed_point_converged_ = passes.fixed_point_converged;
  normal_ = passes.normal;
  tangential_ = passes.tangential;
  has_friction_ = passes.has_friction;
  fbar_used_ = passes.fbar;
  answer.friction = passes.friction;
  answer.d_c = passes.last.z.head(m);
  if (spring_) answer.dw = passes.last.z(m);
  if (with_rim) answer.rim = passes.last.z.segment(with_rim->rim_slot(), problem_.n_rim());
  details().nlp_variables = passes.nlp_variables;
  details().nlp_constraints = passes.nlp_constraints;
  return answer;
}

// The whole step: d_C from Ipopt, d_I from the interior solve; the tangent is released (the next
// comes with the full step or anew: one K in memory).
CondensedSolve::Step CondensedSolve::whole_step(const ModelStep& model) {
  VecX e = VecX::Zero(x_.size());
  for (Index s = 0; s < static_cast<Index>(cond_.dofs.size()); ++s) e(cond_.dofs[s]) = model.d_c(s);
  const VecX ke = k_eff_ * e;
  Step step;
  step.d = condenser_.solve_interior(-g_ - ke) + e;
  step.kd = k_eff_ * step.d;
  k_eff_ = SparseMatrix();
  step.dw = model.dw;
  const Real w0 = problem_.roller_offset();
  step.model_change = g_.dot(step.d) + 0.5 * step.d.dot(step.kd) + roller_energy(w0 + step.dw) - roller_energy(w0);
  if (problem_.rim()) {
    const VecX& rim0 = problem_.rim_displacement();
    step.d_rim = model.rim - rim0;
    step.model_change += rim_energy(model.rim) - rim_energy(rim0);
  }
  return step;
}

// Backtracking on the merit function; the roller moves with the strip.
CondensedSolve::OrEnd<CondensedSolve::Trial> CondensedSolve::line_search(int outer, const Step& step,
                                                                         const FrictionTerms& friction) {
  const std::vector<RowMap>& rows = cond_.rows;
  Real fn_max = 0.0;
  for (const Real f : normal_) fn_max = std::max(fn_max, f);
  const Real w0 = problem_.roller_offset();
  const VecX rim0 = problem_.rim_displacement();
  const Real nu = 2.0 * std::max(fn_max, 1e-6 * scales_.force);
  const Real phi0 = merit(problem_, rows, friction, energy_ + roller_energy(w0) + rim_energy(rim0), x_, nu);
  Real pred = -step.model_change;
  {
    VecX x1 = x_ + step.d;
    pred += merit(problem_, rows, friction, 0.0, x_, nu);
    problem_.move_roller(w0 + step.dw);
    move_rim(rim0, 1.0, step.d_rim);
    pred -= merit(problem_, rows, friction, 0.0, x1, nu);
    problem_.move_roller(w0);
    move_rim(rim0, 0.0, step.d_rim);
  }
  const Real roundoff = 1e-10 * (std::abs(energy_) + scales_.force * scales_.length);
  Trial trial;
  bool accepted = false;
  std::string evaluation_error;
  Real next_alpha = 0.5;
  for (int b = 0; b <= kMaxBacktracks && !accepted; ++b, trial.alpha = next_alpha) {
    const Real alpha = trial.alpha;
    next_alpha = 0.5 * alpha;
    trial.x = x_ + alpha * step.d;
    const Expected<ObjectiveValue> at_trial =
        problem_.strip_energy(trial.x, &trial.g, alpha == 1.0 && tangent_changes_ ? &trial.k : nullptr);
    if (!at_trial) {
      evaluation_error = at_trial.error();
      continue;
    }
    trial.energy = at_trial->value;
    problem_.move_roller(w0 + alpha * step.dw);
    move_rim(rim0, alpha, step.d_rim);
    const Real phi = merit(problem_, rows, friction,
                           trial.energy + roller_energy(w0 + alpha * step.dw) + rim_energy(problem_.rim_displacement()),
                           trial.x, nu);
    accepted = std::isfinite(phi) &&
               (pred <= roundoff || phi <= phi0 - 1e-4 * alpha * pred || (alpha == 1.0 && phi <= phi0 + roundoff));
    // Minimiser of the parabola through phi0 (slope -pred) and phi(alpha), kept in [0.1, 0.9] alpha.
    if (!accepted && std::isfinite(phi) && pred > 0.0) {
      const Real curvature = phi - phi0 + alpha * pred;
      if (curvature > 0.0) next_alpha = std::clamp(0.5 * pred * alpha * alpha / curvature, 0.1 * alpha, 0.9 * alpha);
    }
    if (accepted) break;
  }
  if (!accepted) {
    problem_.move_roller(w0);
    move_rim(rim0, 0.0, step.d_rim);
    return formulation_failed(result_, Termination::LimitReached,
                              fmt::format("ipopt backend (condensed): no descent along the step of linearisation "
                                          "{}{}; use smaller steps (a larger steps.count, or steps.max_cuts)",
                                          outer, evaluation_error.empty() ? "" : " (" + evaluation_error + ")"));
  }
  model_error_ = (trial.g - g_ - trial.alpha * step.kd).lpNorm<Eigen::Infinity>() / scales_.force;
  return trial;
}

// Candidates outside the working set must not penetrate: when one does, the set grows and the
// increment goes on with a new linearisation.
bool CondensedSolve::grow_working_set() {
  const auto& cands = problem_.candidates();
  std::vector<char> in(cands.size(), 0);
  for (const int i : working_) in[i] = 1;
  bool grew = false;
  for (std::size_t i = 0; i < cands.size() && !grew; ++i)
    if (!in[i] && (cands[i].free_dof[0] >= 0 || cands[i].free_dof[1] >= 0) && problem_.gap(cands[i], x_) < 0.0)
      grew = true;
  if (grew) working_ = grown_working_set(problem_, x_, scales_.length, working_);
  return grew;
}

// Takes the accepted point, tests convergence and, when the increment goes on, linearises there
// (the full step's tangent when it was evaluated with it: energy and g are x's already).
CondensedSolve::End CondensedSolve::relinearise(Trial&& trial) {
  x_ = std::move(trial.x);
  g_ = std::move(trial.g);
  energy_ = trial.energy;
  const bool grew = grow_working_set();
  converged_ = trial.alpha == 1.0 && !grew && fixed_point_converged_ && model_error_ <= o_.tol;
  if (converged_) return std::nullopt;
  if (trial.alpha == 1.0 && trial.k.size() > 0) {
    k_eff_ = std::move(trial.k);
    return std::nullopt;
  }
  const Expected<ObjectiveValue> at_x = problem_.strip_energy(x_, &g_, &k_eff_);
  if (!at_x)
    return formulation_failed(result_, Termination::Failed,
                              fmt::format("ipopt backend (condensed): the strip tangent cannot be evaluated ({}); "
                                          "use smaller steps (a larger steps.count, or steps.max_cuts)",
                                          at_x.error()));
  energy_ = at_x->value;
  return std::nullopt;
}

// The report of the increment at the last iterate.
CondensedOutcome CondensedSolve::finish() {
  result_.x = x_;
  if (spring_) result_.roller_offset = problem_.roller_offset();
  if (problem_.rim()) result_.rim = problem_.rim_displacement();
  details().fixed_point_iterations = passes_last_;  // Coulomb passes on the last linearisation
  details().linearisations = linearisations_;
  details().condensed_dofs = static_cast<int>(cond_.dofs.size());
  if (!report_increment(problem_, x_, normal_, tangential_, fbar_used_, has_friction_, scales_, &result_))
    return {std::move(result_), true};
  if (!converged_) {
    if (!fixed_point_converged_) {
      result_.status = Termination::LimitReached;
      result_.message = fixed_point_->failure_message(details().nlp_solves);
      return {std::move(result_), false};
    }
    return formulation_failed(result_, Termination::LimitReached,
                              fmt::format("ipopt backend (condensed): {} linearisations without convergence (model "
                                          "error {:.3g} against contact.ipopt.tol = {:g}); use smaller steps (a larger "
                                          "steps.count, or steps.max_cuts)",
                                          kMaxLinearisations, model_error_, o_.tol));
  }
  result_.status = Termination::Converged;
  const int nlp_solves = details().nlp_solves;
  result_.message = fmt::format("Ipopt converged: {} linearisation{}, {} interior-point iterations ({} pass{})",
                                linearisations_, linearisations_ == 1 ? "" : "s", result_.counters.iterations,
                                nlp_solves, nlp_solves == 1 ? "" : "es");
  return {std::move(result_), false};
}

}  // namespace roller::ipopt_detail
