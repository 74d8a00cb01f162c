#include "roller/dynamics/suspension.hpp"

#include <cmath>

#include <fmt/format.h>

namespace roller {

Real Suspension::effective_stiffness() const {
  return spec_.mass * history_.acceleration_coefficient() + spec_.damping * history_.velocity_coefficient() +
         spec_.stiffness;
}

Real Suspension::history_force() const {
  return spec_.mass * history_.acceleration_offset()(0) + spec_.damping * history_.velocity_offset()(0);
}

Real Suspension::velocity(Real w) const { return history_.velocity(VecX::Constant(1, w))(0); }

Real Suspension::acceleration(Real w) const { return history_.acceleration(VecX::Constant(1, w))(0); }

CouplingResult couple_suspension(const Suspension& suspension, Real w0,
                                 const std::function<std::optional<Real>(Real)>& contact_force, Real w_tolerance,
                                 Real max_deflection, int max_iterations) {
  CouplingResult out;
  const Real k_eff = suspension.effective_stiffness();
  Real w = w0;
  Real w_prev = 0.0, r_prev = 0.0;
  bool have_prev = false;
  for (int it = 1; it <= max_iterations; ++it) {
    const std::optional<Real> f = contact_force(w);
    out.iterations = it;
    if (!f) {
      out.message = fmt::format("the contact solve failed at suspension deflection w = {:.6g} mm", w);
      return out;
    }
    const Real r = suspension.residual(w, *f);
    // Slope of r: the secant when it is usable (r grows with w: lifting the roller relieves the
    // contact), else k_eff alone (the fixed-point step).
    Real slope = k_eff;
    if (have_prev && w != w_prev) {
      const Real secant = (r - r_prev) / (w - w_prev);
      if (secant >= k_eff && std::isfinite(secant)) slope = secant;
    }
    const Real w_next = w - r / slope;
    out.deflection = w;
    out.force = *f;
    if (!(std::abs(w_next) <= max_deflection)) {
      out.message = fmt::format(
          "the suspension deflection would exceed {:.3g} mm under F_y = {:.6g} N/mm (effective stiffness {:.3g} N/mm "
          "per mm): the suspension is too soft for the contact force; raise roller.suspension.stiffness or mass, or "
          "take smaller steps (a larger steps.count, or steps.max_cuts)",
          max_deflection, *f, k_eff);
      return out;
    }
    if (std::abs(w_next - w) <= w_tolerance) {
      out.status = Termination::Converged;
      return out;
    }
    w_prev = w;
    r_prev = r;
    have_prev = true;
    w = w_next;
  }
  out.status = Termination::LimitReached;
  out.message = fmt::format(
      "the roller suspension and the contact did not converge in {} passes (last change of the deflection "
      "above {:.3g} mm): use a smaller time step or a stiffer suspension",
      max_iterations, w_tolerance);
  return out;
}

}  // namespace roller
