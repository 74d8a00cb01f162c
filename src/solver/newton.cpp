#include "roller/solver/newton.hpp"

#include <cmath>

#include <fmt/format.h>

#include "roller/solver/sparse_solver.hpp"

namespace roller {

namespace {

constexpr char kSmallerSteps[] = "use smaller steps (a larger steps.count, or steps.max_cuts)";

// Whether the step to a trial point with merit `trial` (Pi, or ||r||) and residual norm
// `trial_rnorm` is accepted, from a point with merit `merit` and residual norm `rnorm`.
// Energy: Armijo on Pi; near the solution Pi changes only at round-off level, so a full step that
// halves the residual without raising Pi beyond round-off is accepted too. Residual: a sufficient
// decrease of ||r||.
bool sufficient_decrease(NewtonMerit kind, Real alpha, Real slope, Real merit, Real trial, Real rnorm,
                         Real trial_rnorm) {
  if (kind == NewtonMerit::Residual) return trial_rnorm <= (1.0 - 1e-4 * alpha) * rnorm;
  const bool armijo = trial <= merit + 1e-4 * alpha * slope;
  const bool residual_drop = alpha == 1.0 && trial_rnorm < 0.5 * rnorm && trial <= merit + 1e-12 * std::abs(merit);
  return armijo || residual_drop;
}

}  // namespace

// Solves H d = -g by LDL^T (solver/sparse_solver.hpp; indefinite allowed: geometric stiffness
// under compression); when the result is not a descent direction the Hessian is shifted (Levenberg)
// until it is.
bool NewtonMinimiser::descent_direction(const SparseMatrix& h, const VecX& g, VecX& d, int& factorizations) {
  Real shift = 0.0;
  const Real diag_scale = h.diagonal().cwiseAbs().maxCoeff();
  for (int attempt = 0; attempt < 8; ++attempt) {
    SparseMatrix shifted = h;
    if (shift > 0.0) shifted.diagonal().array() += shift;
    ++factorizations;
    if (symmetric_->factorize(shifted)) {
      d = symmetric_->solve(-g);
      if (d.allFinite() && d.dot(g) < 0.0) return true;
    }
    shift = shift == 0.0 ? 1e-8 * diag_scale : shift * 100.0;
  }
  return false;
}

// Newton's direction J d = -r: LDL^T for a symmetric J, LU for an unsymmetric one and as the
// fallback when LDL^T fails.
bool NewtonMinimiser::newton_direction(const SparseMatrix& j, const VecX& r, bool symmetric, VecX& d,
                                       int& factorizations) {
  if (symmetric) {
    ++factorizations;
    if (symmetric_->factorize(j)) {
      d = symmetric_->solve(-r);
      if (d.allFinite()) return true;
    }
  }
  ++factorizations;
  if (!general_->factorize(j)) return false;
  d = general_->solve(-r);
  return d.allFinite();
}

bool NewtonMinimiser::direction(NewtonMerit merit, const SparseMatrix& j, const VecX& r, bool symmetric,
                                const LinearSolverOptions& linear, VecX& d, int& factorizations) {
  symmetric_->configure(linear);
  if (merit == NewtonMerit::Energy) return descent_direction(j, r, d, factorizations);
  if (!general_) general_ = std::make_unique<SparseSolver>(MumpsSolver::Symmetry::General);
  general_->configure(linear);
  return newton_direction(j, r, symmetric, d, factorizations);
}

NewtonReport minimise_newton(NewtonObjective& objective, VecX& x, const NewtonOptions& options) {
  NewtonMinimiser newton;
  return newton.minimise(objective, x, options);
}

NewtonReport NewtonMinimiser::minimise(NewtonObjective& objective, VecX& x, const NewtonOptions& options,
                                       NewtonMerit merit) {
  NewtonReport report;
  VecX g, d, x_trial, g_trial;
  SparseMatrix h;
  Expected<ObjectiveValue> start = objective.evaluate(x, &g, &h);
  if (!start) {
    report.message = fmt::format("cannot evaluate the start of the increment: {}", start.error());
    return report;
  }
  ObjectiveValue value = *start;
  const int max_cuts = merit == NewtonMerit::Energy ? 30 : 20;
  int full_steps = 0;  // consecutive full steps taken without a decrease of the merit
  for (int it = 0;; ++it) {
    const Real scale = std::max(value.force_scale, 1e-300);
    const Real gnorm = g.norm();
    report.residual_history.push_back(gnorm);
    report.residual = gnorm / scale;
    report.counters.iterations = it;
    if (!std::isfinite(gnorm)) {
      report.message = fmt::format("the residual is not finite (NaN/Inf): the increment diverged; {}", kSmallerSteps);
      return report;
    }
    if (report.residual <= options.residual_tolerance || gnorm <= value.roundoff_floor || g.size() == 0) {
      report.status = Termination::Converged;
      report.at_roundoff_floor = report.residual > options.residual_tolerance;
      report.message = fmt::format("converged in {} iterations, |r|/F = {:.2e}", it, report.residual);
      return report;
    }
    if (it >= options.max_iterations) {
      report.status = Termination::LimitReached;
      report.message = fmt::format(
          "no convergence in {} Newton iterations (|r|/F = {:.2e} > {:.1e}); {} or raise newton.max_iterations", it,
          report.residual, options.residual_tolerance, kSmallerSteps);
      return report;
    }
    if (!direction(merit, h, g, value.symmetric, options.linear, d, report.counters.factorizations)) {
      report.message = fmt::format(
          "the tangent stiffness could not be factorised into a descent direction "
          "(singular or strongly indefinite: a mechanism, missing supports, or loss "
          "of monotonicity); check the boundary conditions or {}",
          kSmallerSteps);
      return report;
    }
    Real alpha = 1.0;
    const Real slope = g.dot(d);
    bool accepted = false;
    for (int ls = 0; ls < max_cuts && !accepted; ++ls) {
      x_trial = x + alpha * d;
      // A point that cannot be evaluated (e.g. an inverted element) shortens the step.
      if (const Expected<ObjectiveValue> trial = objective.evaluate(x_trial, &g_trial, nullptr))
        accepted = !options.line_search ||
                   sufficient_decrease(merit, alpha, slope, value.value, trial->value, gnorm, g_trial.norm());
      if (!accepted) {
        alpha *= 0.5;
        ++report.line_search_cuts;
      }
    }
    if (accepted) {
      full_steps = 0;
    } else if (merit == NewtonMerit::Residual && ++full_steps <= kMaxFullStepsInARow) {
      x_trial = x + d;
    } else {
      report.status = merit == NewtonMerit::Residual ? Termination::LimitReached : Termination::Failed;
      report.message =
          fmt::format("the line search found no decrease of the {} (|r|/F = {:.2e}); {}",
                      merit == NewtonMerit::Energy ? "incremental energy" : "residual", report.residual, kSmallerSteps);
      return report;
    }
    x = x_trial;
    const Expected<ObjectiveValue> next = objective.evaluate(x, &g, &h);
    if (!next) {
      report.message = next.error();
      return report;
    }
    value = *next;
  }
}

}  // namespace roller
