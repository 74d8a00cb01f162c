#include "roller/solver/newton.hpp"

#include <cmath>

#include <fmt/format.h>

#include "roller/solver/sparse_solver.hpp"

namespace roller {

// Solves H d = -g by LDL^T (solver/sparse_solver.hpp; indefinite allowed: geometric stiffness
// under compression); when the result is not a descent direction the Hessian is shifted (Levenberg)
// until it is.
bool NewtonMinimiser::direction(const SparseMatrix& h, const VecX& g, const LinearSolverOptions& linear, VecX& d,
                                int& factorizations) {
  solver_->configure(linear);
  Real shift = 0.0;
  const Real diag_scale = h.diagonal().cwiseAbs().maxCoeff();
  for (int attempt = 0; attempt < 8; ++attempt) {
    SparseMatrix shifted = h;
    if (shift > 0.0) shifted.diagonal().array() += shift;
    ++factorizations;
    if (solver_->factorize(shifted)) {
      d = solver_->solve(-g);
      if (d.allFinite() && d.dot(g) < 0.0) return true;
    }
    shift = shift == 0.0 ? 1e-8 * diag_scale : shift * 100.0;
  }
  return false;
}

NewtonReport minimise_newton(NewtonObjective& objective, VecX& x, const NewtonOptions& options) {
  NewtonMinimiser newton;
  return newton.minimise(objective, x, options);
}

NewtonReport NewtonMinimiser::minimise(NewtonObjective& objective, VecX& x, const NewtonOptions& options) {
  NewtonReport report;
  VecX g, d, x_trial, g_trial;
  SparseMatrix h;
  Expected<ObjectiveValue> start = objective.evaluate(x, &g, &h);
  if (!start) {
    report.message = fmt::format("cannot evaluate the start of the increment: {}", start.error());
    return report;
  }
  ObjectiveValue value = *start;
  for (int it = 0;; ++it) {
    const Real scale = std::max(value.force_scale, 1e-300);
    const Real gnorm = g.norm();
    report.residual_history.push_back(gnorm);
    report.residual = gnorm / scale;
    report.counters.iterations = it;
    if (!std::isfinite(gnorm)) {
      report.message =
          "the residual is not finite (NaN/Inf): the increment diverged; use smaller steps (a larger steps.count, or "
          "steps.max_cuts)";
      return report;
    }
    if (report.residual <= options.residual_tolerance || g.size() == 0) {
      report.status = Termination::Converged;
      report.message = fmt::format("converged in {} iterations, |r|/F = {:.2e}", it, report.residual);
      return report;
    }
    if (it >= options.max_iterations) {
      report.status = Termination::LimitReached;
      report.message = fmt::format(
          "no convergence in {} Newton iterations (|r|/F = {:.2e} > {:.1e}); use smaller steps (a larger steps.count, "
          "or steps.max_cuts) "
          "or raise newton.max_iterations",
          it, report.residual, options.residual_tolerance);
      return report;
    }
    if (!direction(h, g, options.linear, d, report.counters.factorizations)) {
      report.message =
          "the tangent stiffness could not be factorised into a descent direction "
          "(singular or strongly indefinite: a mechanism, missing supports, or loss "
          "of monotonicity); check the boundary conditions or use smaller steps (a larger steps.count, or "
          "steps.max_cuts)";
      return report;
    }
    // Backtracking on Pi (Armijo). Near the solution Pi changes only at round-off level, so a
    // full step that halves the residual without raising Pi beyond round-off is accepted too.
    Real alpha = 1.0;
    const Real slope = g.dot(d);
    bool accepted = false;
    for (int ls = 0; ls < 30 && !accepted; ++ls) {
      x_trial = x + alpha * d;
      // A point that cannot be evaluated (e.g. an inverted element) shortens the step.
      if (const Expected<ObjectiveValue> trial = objective.evaluate(x_trial, &g_trial, nullptr)) {
        const Real pi_trial = trial->value;
        const bool armijo = pi_trial <= value.value + 1e-4 * alpha * slope;
        const bool residual_drop =
            alpha == 1.0 && g_trial.norm() < 0.5 * gnorm && pi_trial <= value.value + 1e-12 * std::abs(value.value);
        accepted = !options.line_search || armijo || residual_drop;
      } else {
        accepted = false;
      }
      if (!accepted) {
        alpha *= 0.5;
        ++report.line_search_cuts;
      }
    }
    if (!accepted) {
      report.message =
          "the line search found no decrease of the incremental energy; use smaller steps (a larger steps.count, or "
          "steps.max_cuts)";
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
