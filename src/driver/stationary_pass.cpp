#include "roller/driver/stationary_pass.hpp"

#include <algorithm>
#include <cmath>
#include <ostream>

#include <fmt/format.h>

namespace roller {

namespace {

// Aitken's weight from two successive corrections (Irons & Tuck), kept within [1/8, 8]: beyond
// that a secant over two nearly equal corrections is noise.
Real aitken_weight(Real previous, const VecX& d_old, const VecX& d_new) {
  const VecX change = d_new - d_old;
  const Real denominator = change.squaredNorm();
  if (!(denominator > 0.0)) return previous;
  return std::clamp(-previous * d_old.dot(change) / denominator, 0.125, 8.0);
}

}  // namespace

StationaryPassResult solve_stationary_pass(const StationaryStrip& strip, const DofMap& dofs, SparseSolver& elastic,
                                           const VecX& external, const std::vector<MaterialState>& upstream,
                                           const StationarySettings& settings) {
  StationaryPassResult out;
  const VecX carried = strip.forces(strip.spread(upstream));  // f(sigma_upstream)
  const Real reference = std::max(external.cwiseAbs().maxCoeff(), 1e-300);
  out.displacement = VecX::Zero(external.size());
  VecX previous_step;
  Real omega = 1.0;
  for (int k = 0;; ++k) {
    out.strains = strip.strains(out.displacement);
    SweepReport report;
    out.states = strip.sweep(out.strains, upstream, &report);
    out.n_yielded = report.n_yielded;
    const VecX r = dofs.restrict_to_free(external + carried - strip.forces(out.states));
    out.residual = r.cwiseAbs().maxCoeff() / reference;
    out.iterations = k;
    if (!std::isfinite(out.residual)) {
      out.status = Termination::Failed;
      out.message = fmt::format("the stationary iteration diverged (residual not finite after {} iterations)", k);
      return out;
    }
    if (settings.progress && (k % settings.report_every == 0))
      *settings.progress << fmt::format("  stationary iteration {:5d}  |r|/F {:.3e}  omega {:.3f}  yielded {}\n", k,
                                        out.residual, omega, out.n_yielded);
    if (out.residual <= settings.tolerance) {
      out.status = Termination::Converged;
      return out;
    }
    if (k == settings.max_iterations) {
      out.status = Termination::LimitReached;
      out.message = fmt::format("the stationary iteration reached {} iterations at |r|/F = {:.3g} (tolerance {:g})", k,
                                out.residual, settings.tolerance);
      return out;
    }
    const VecX step = elastic.solve(r);
    if (previous_step.size() == step.size()) omega = aitken_weight(omega, previous_step, step);
    previous_step = step;
    VecX full = VecX::Zero(external.size());
    dofs.scatter_free(omega * step, full);
    out.displacement += full;
  }
}

}  // namespace roller
