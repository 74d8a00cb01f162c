#pragma once
// The roller's vertical suspension (thesis (4.20)-(4.21); docs/model.md, Roller suspension), per
// mm of roller length:
//   m w'' + c w' + k w = F_y,
// w the deflection of the centre from the prescribed anchor (positive up), F_y the vertical
// force of the strip on the roller. Houbolt in time, like the strip (houbolt.hpp), so with
// w = w_{n+1} the equation at the end of the increment is linear in w:
//   r(w) = k_eff w + h - F_y(w),  k_eff = m c_a + c c_v + k,  h = m a_off + c v_off.
// The strip's force depends on w through the contact solve; couple_suspension() converges the
// two in the same increment.
#include <functional>
#include <optional>
#include <string>

#include "roller/dynamics/houbolt.hpp"
#include "roller/dynamics/suspension_spec.hpp"
#include "roller/solver/termination.hpp"

namespace roller {

class Suspension {
 public:
  Suspension() = default;
  Suspension(SuspensionSpec spec, HouboltHistory history) : spec_(spec), history_(std::move(history)) {}

  const SuspensionSpec& spec() const { return spec_; }
  HouboltHistory& history() { return history_; }
  const HouboltHistory& history() const { return history_; }
  Real deflection() const { return history_.u_n()(0); }
  // Where the coupling starts: w_n + (w_n - w_{n-1}), the deflection's last increment carried on,
  // as the strip's own predictor carries on its last increment.
  Real predicted_deflection() const { return 2.0 * history_.u_n()(0) - history_.u_nm1()(0); }

  Real effective_stiffness() const;
  Real history_force() const;  // h above
  Real residual(Real w, Real force) const { return effective_stiffness() * w + history_force() - force; }
  Real velocity(Real w) const;
  Real acceleration(Real w) const;

 private:
  SuspensionSpec spec_;
  HouboltHistory history_;  // 1-vectors
};

struct CouplingResult {
  Termination status = Termination::Failed;
  int iterations = 0;  // contact solves
  Real deflection = 0.0;
  Real force = 0.0;  // F_y at the final deflection
  std::string message;
  bool converged() const { return status == Termination::Converged; }
};

// Finds w with r(w) = 0. `contact_force(w)` solves the strip's contact increment with the roller
// at anchor + w and returns F_y, or nullopt when that solve fails. The first update is the fixed
// point w1 = (F_y(w0) - h)/k_eff; later ones take the secant slope of r (k_eff plus the contact
// stiffness), which converges superlinearly. Converged when the change of w is below
// `w_tolerance` [mm]; fails (with a message, never a non-finite w) when an update would take
// |w| beyond `max_deflection` [mm]: a suspension too soft for the force.
CouplingResult couple_suspension(const Suspension& suspension, Real w0,
                                 const std::function<std::optional<Real>(Real)>& contact_force, Real w_tolerance,
                                 Real max_deflection, int max_iterations);

}  // namespace roller
