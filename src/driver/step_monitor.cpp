#include "roller/driver/step_monitor.hpp"

#include <cmath>
#include <ostream>

#include <fmt/format.h>

namespace roller {

MonitorReport StepMonitor::check(int step, StripModel& model, bool pointwise_loss_reported) {
  MonitorReport r;
  if (!enabled_) return r;
  const bool constant = model.tangent_is_constant();
  if (constant && constant_report_ && constant_free_dofs_ == model.dof_map().free_dofs()) {
    r = *constant_report_;
    r.reused = true;
    r.worst_place = Vec2::Zero();
  } else {
    r.checked = true;
    r.pointwise = check_strip(model, mass_free_ ? dt_ : 0.0);
    SparseMatrix k_eff;
    model.evaluate(VecX::Zero(model.n_dofs()), nullptr, &k_eff);
    if (mass_free_) k_eff += (2.0 / (dt_ * dt_)) * *mass_free_;
    const std::optional<Inertia> held = backend_ ? backend_->held_tangent_inertia(k_eff) : std::nullopt;
    if (held) {
      r.assembled.factorized = true;
      r.assembled.n_negative = held->negative;
      r.assembled.n_zero = held->zero;
      r.from_contact_solve = true;
    } else {
      if (!ldlt_) {
        ldlt_ = std::make_unique<MumpsSolver>(MumpsSolver::Symmetry::Symmetric);
        ldlt_->discard_factors();
      }
      r.assembled = sparse_definiteness(k_eff, *ldlt_);
    }
    if (constant) {
      constant_report_ = r;
      constant_free_dofs_ = model.dof_map().free_dofs();
    }
  }
  const StripMonotonicity& mono = r.pointwise;
  if (mono.worst.element >= 0) {
    const auto x = model.current_coordinates();
    const auto& element = model.mesh().elements[mono.worst.element];
    for (Index a : element) r.worst_place += x[a] / static_cast<Real>(element.size());
  }
  if (mono.n_not_pd > 0 && !pointwise_loss_reported) {
    // Once a run: in rolling, shear-dominated plastic points lose pointwise monotonicity routinely
    // while the assembled operator stays positive definite.
    r.warnings.push_back(fmt::format(
        "step {}: operator A (the strip's incremental constitutive operator, docs/monotonicity.md) is not positive "
        "definite at {} integration points (worst near x = {:.4g}, y = {:.4g} mm). This is routine where plastic "
        "points "
        "shear and unload under a rolling contact and does not by itself affect the answer; it matters only if the "
        "assembled tangent stiffness loses positive definiteness too, which a separate warning would say. solver.csv "
        "counts such points every step",
        step, mono.n_not_pd, r.worst_place.x(), r.worst_place.y()));
    r.pointwise_loss_first = true;
  }
  if (!r.assembled.factorized || r.assembled.n_zero > 0)
    r.warnings.push_back(fmt::format(
        "step {}: the assembled tangent stiffness is singular ({}): the strip can move without strain energy; check "
        "the supports ([[displacement]])",
        step, r.assembled.factorized ? fmt::format("{} null pivots", r.assembled.n_zero) : r.assembled.message));
  else if (!r.assembled.positive_definite())
    r.warnings.push_back(fmt::format(
        "step {}: the assembled tangent stiffness is not positive definite ({} negative pivots) near x = {:.4g}, "
        "y = {:.4g} mm: operator A lost monotonicity ({}); {}",
        step, r.assembled.n_negative, r.worst_place.x(), r.worst_place.y(), mono.brief_report(),
        stationary_ ? "a stationary pass solves the steady Jacobian, not this tangent of the strip's states after it, "
                      "so the pass's answer does not rest on it; a transient pass from these states would meet it: "
                      "smaller steps there"
        : mono.dt_restore_all > 0.0 && std::isfinite(mono.dt_restore_all)
            ? fmt::format("a time step below {:.3g} s would restore it (3.18)", mono.dt_restore_all)
            : "in a quasistatic strip no time step restores it: use smaller steps (a larger steps.count, or "
              "steps.max_cuts) or check the supports"));
  if (progress_)
    for (const std::string& w : r.warnings) *progress_ << "warning: " << w << "\n";
  return r;
}

}  // namespace roller
