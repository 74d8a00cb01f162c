#include "roller/steady/stationary_pass.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>

#include <fmt/format.h>

#include "roller/assembly/steady_jacobian.hpp"
#include "roller/solver/anderson.hpp"

namespace roller {

namespace {

// Anderson's depth: 20 sufficed at 20 elements across a; at 40 elements across a the pass needs a
// depth of 40 (140 iterations against 213 with 20; docs/benchmarks-log.md), and more does not pay.
constexpr int kAndersonDepth = 40;

}  // namespace

SteadyJacobianCorrection::SteadyJacobianCorrection(const StationaryStrip& strip, const DofMap& dofs,
                                                   const SparseMatrix& elastic_free, StationaryCorrection& elastic,
                                                   std::vector<MaterialState> upstream,
                                                   const SteadyJacobianSettings& settings)
    : strip_(strip),
      dofs_(dofs),
      elastic_free_(elastic_free),
      elastic_(elastic),
      upstream_(std::move(upstream)),
      settings_(settings),
      from_(settings.from) {
  LinearSolverOptions options = settings.linear_solver;
  if (options.ordering == "auto") options.ordering = "amd";
  jacobian_.configure(options);
}

void SteadyJacobianCorrection::leave_jacobian(Stage next) {
  if (load_on_jacobian_) elastic_.take_operator(nullptr, settings_.linear_solver);
  load_on_jacobian_ = false;
  stage_ = next;
}

StationaryCorrection::Result SteadyJacobianCorrection::correct(const VecX& u, const std::vector<MaterialState>& states,
                                                               const VecX& r) {
  const bool with_jacobian = stage_ == Stage::Jacobian;
  const bool dropped = stage_ == Stage::Diverged || stage_ == Stage::Singular;
  Result out;
  if (with_jacobian && elastic_.fixed_load()) {
    out.load = *elastic_.fixed_load();  // K_e's step would be thrown away
  } else {
    out = elastic_.correct(u, states, r);  // with J's load correction: J's step already
    if (out.du.size() == 0 || dropped) return out;
  }
  const VecX load = dofs_.gather_free(out.load);
  const VecX rhs = r + load;
  const Real residual = rhs.cwiseAbs().maxCoeff() / std::max(load.cwiseAbs().maxCoeff(), 1e-300);
  if (!with_jacobian && residual > from_) return out;
  if (with_jacobian && residual > settings_.divergence * best_residual_) {
    // J's steps diverge: back to the best iterate they reached, and K_e's correction from there,
    // for the rest of the pass or until it is `retry` times nearer.
    if (retried_ < settings_.retries) {
      ++retried_;
      from_ = settings_.retry * best_residual_;
      leave_jacobian(Stage::Elastic);
      last_residual_ = 0.0;
    } else {
      leave_jacobian(Stage::Diverged);
    }
    out.du = dofs_.restrict_to_free(best_u_ - u);
    out.new_operator = true;
    return out;
  }
  if (residual < best_residual_) best_residual_ = residual, best_u_ = u;
  const bool slow = last_residual_ == 0.0 || residual > settings_.contraction * last_residual_;
  last_residual_ = residual;
  if (!with_jacobian || (slow && residual > settings_.tolerance)) {
    const SteadyJacobian j = steady_jacobian(strip_, dofs_, elastic_free_, strip_.strains(u), upstream_, states);
    if (elastic_.take_operator(&j.matrix, settings_.linear_solver)) {  // the load's correction condenses J
      load_on_jacobian_ = true;
      stage_ = Stage::Jacobian;
      ++factorizations_;
      Result step = elastic_.correct(u, states, r);
      step.new_operator = true;
      if (step.du.size() != 0) return step;
      leave_jacobian(Stage::Singular);  // J's contact failed: K_e's correction carries on alone
      out = elastic_.correct(u, states, r);
      out.new_operator = true;
      return out;
    }
    if (load_on_jacobian_) leave_jacobian(stage_);
    if (!jacobian_.factorize(j.matrix)) {  // K_e's correction carries on alone
      stage_ = Stage::Singular;
      if (out.du.size() == 0) out = elastic_.correct(u, states, r);
      out.new_operator = true;
      return out;
    }
    n_unknowns_ = j.matrix.rows();
    stage_ = Stage::Jacobian;
    ++factorizations_;
    out.new_operator = true;
  }
  if (load_on_jacobian_) return out;  // J's step, with its own contact
  VecX b = VecX::Zero(n_unknowns_);
  b.head(rhs.size()) = rhs;
  out.du = jacobian_.solve(b).head(rhs.size());
  return out;
}

StationaryPassResult solve_stationary_pass(const StationaryStrip& strip, const DofMap& dofs,
                                           StationaryCorrection& correction, const std::vector<MaterialState>& upstream,
                                           const StationarySettings& settings, const LeavingStates& leaving,
                                           const VecX& start) {
  StationaryPassResult out;
  // f(sigma_upstream): the strip beyond both ends holds the mesh with the upstream states; with
  // `leaving`, the downstream end's share becomes the leaving states'.
  const VecX upstream_forces = strip.forces(strip.spread(upstream));
  const VecX upstream_downstream_end =
      leaving ? strip.end_forces(upstream, StationaryStrip::End::Downstream) : VecX::Zero(upstream_forces.size());
  VecX carried = upstream_forces;
  out.displacement = start.size() == carried.size() ? start : VecX::Zero(carried.size());
  out.load = VecX::Zero(carried.size());
  Anderson anderson(kAndersonDepth);
  // Stagnation: the best residual so far and the iteration at which it last halved.
  Real mark = std::numeric_limits<Real>::infinity();
  int mark_iteration = 0;
  for (int k = 0;; ++k) {
    if (settings.stop && settings.stop->load() != 0) {
      out.status = Termination::Interrupted;
      out.message = fmt::format("interrupted by signal {} at iteration {}", settings.stop->load(), k);
      return out;
    }
    SweepReport report;
    out.states = strip.sweep(strip.strains(out.displacement), upstream, &report);
    out.n_yielded = report.n_yielded;
    if (leaving)
      carried = upstream_forces - upstream_downstream_end +
                strip.end_forces(leaving(out.displacement, out.states, out.load), StationaryStrip::End::Downstream);
    const VecX r = dofs.gather_free(carried - strip.forces(out.states));
    const StationaryCorrection::Result c = correction.correct(out.displacement, out.states, r);
    out.iterations = k;
    if (c.du.size() == 0) {
      out.status = Termination::Failed;
      out.message = fmt::format("the stationary iteration's correction {} failed: {}", k, c.message);
      return out;
    }
    out.load = c.load;
    const Real reference = std::max(c.load.cwiseAbs().maxCoeff(), 1e-300);
    out.residual = (r + dofs.gather_free(c.load)).cwiseAbs().maxCoeff() / reference;
    if (!std::isfinite(out.residual)) {
      out.status = Termination::Failed;
      out.message = fmt::format("the stationary iteration diverged (residual not finite after {} iterations)", k);
      return out;
    }
    if (settings.progress && k > 0 && k % settings.report_every == 0)
      *settings.progress << fmt::format("  stationary iteration {:5d}  |r|/F {:.3e}  yielded {}\n", k, out.residual,
                                        out.n_yielded);
    if (out.residual <= settings.tolerance) {
      out.status = Termination::Converged;
      return out;
    }
    if (out.residual <= 0.5 * mark) mark = out.residual, mark_iteration = k;
    const char* fix =
        "the pass may have no steady state at this load (a surface layer that keeps flowing), or the elastic "
        "correction cannot reach it: use passes.method = \"transient\"";
    if (k - mark_iteration >= settings.stagnation_window) {
      out.status = Termination::LimitReached;
      out.message =
          fmt::format("the stationary iteration stagnates: |r|/F = {:.3g} has not halved in {} iterations; {}",
                      out.residual, settings.stagnation_window, fix);
      return out;
    }
    if (k == settings.max_iterations) {
      out.status = Termination::LimitReached;
      out.message = fmt::format("the stationary iteration reached {} iterations at |r|/F = {:.3g} (tolerance {:g}); {}",
                                k, out.residual, settings.tolerance, fix);
      return out;
    }
    if (c.new_operator) anderson = Anderson(kAndersonDepth);
    dofs.scatter_free(anderson.next(dofs.restrict_to_free(out.displacement), c.du), out.displacement);
  }
}

}  // namespace roller
