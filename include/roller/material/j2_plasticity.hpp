#pragma once
// Plane-strain isotropic elasticity and J2 (von Mises) plasticity with isotropic, kinematic,
// mixed and Chaboche hardening (docs/model.md, Material and Hardening laws).
//
//   yield function  f = 1/2 xi:xi - 1/3 sigma_Y^2 <= 0, xi = s - sum alpha_i
//                   (s = deviator of the 3D stress, zz kept; alpha_i the back-stresses)
//   isotropic       sigma_Y = sigma_y0 + H_iso eps_p + Q (1 - exp(-b eps_p)),  H' = E E_T / (E - E_T)
//   kinematic       d alpha_i = 2/3 C_i d eps_p - gamma_i alpha_i d p   (gamma_i = 0: Prager)
//
// The update is a pure function: it never touches the committed state.
//
// Incremental potential. With ReturnMapping the stress is the derivative of the energy density
//   W(dE) = psi_e(eps_e_new) - psi_e(eps_e_old) + int_{eps_p_old}^{eps_p_new} sigma_pl(a) da,
//   psi_e(eps) = 1/2 eps:C:eps, eps_e_old = C^-1 stress_old, eps_e_new = C^-1 stress_new,
// because backward Euler radial return minimises that expression over the plastic increment; a
// linear back-stress adds its stored energy 3/(4 C) alpha:alpha. Armstrong-Frederick's recovery
// (gamma > 0) has no potential: update_material then reports the trapezoidal work as `energy`,
// and the overload with FrozenRecovery restores a potential (docs/model.md, Hardening laws).
// So `energy` is a true objective for the interior-point backend and a merit function for
// Newton line searches. With Substep the energy is the trapezoidal work int S:dE over the
// sub-steps (no potential exists for the forward-Euler update).
#include "roller/material/material_params.hpp"
#include "roller/material/material_state.hpp"

namespace roller {

struct MaterialUpdate {
  Vec4 stress = Vec4::Zero();   // S = stress_old + dS  [xx, yy, zz, xy]
  Mat4 tangent = Mat4::Zero();  // dS/d(strain increment): consistent tangent (ReturnMapping) or
                                // continuum C^EP at the end state (Substep); maps the engineering
                                // strain vector [xx, yy, zz, 2xy] to the stress vector
  Real energy = 0.0;            // energy density of the increment, dW/d(strain) = stress
  MaterialState trial;          // state to commit if the increment converges
  bool yielded = false;         // plastic flow occurred in this increment
};

// Plane-strain elasticity matrix in the [xx, yy, zz, 2xy] -> [xx, yy, zz, xy] convention.
Mat4 elastic_matrix(const MaterialParams& p);

// Continuum elastoplastic tangent C^EP (thesis (2.29)-(2.30)) at a stress on the yield surface
// with yield stress sigma_pl; returns the elastic matrix when the state is inside the surface
// (f < 0, von Mises below sigma_pl by more than a relative 1e-8), sigma_pl <= 0, or the
// material is elastic; otherwise plastic_tangent.
Mat4 continuum_tangent(const MaterialParams& p, const Vec4& stress, Real yield_stress);

// The plastic branch of C^EP without the yield check, in the thesis's explicit form (2.29)/(3.4):
//   C^EP = C - 2G beta s s^T,  beta = 3 / (2 sigma_pl^2 (1 + H'/(3G))),
// s the deviator as [xx, yy, zz, xy]. It equals (2.29) with s:s = 2/3 sigma_pl^2, i.e. on the
// surface; off it, deviator and sigma_pl enter separately (monotonicity maps; docs/model.md,
// Pointwise operator A).
// Requires sigma_pl > 0 (throws std::logic_error otherwise).
Mat4 plastic_tangent(const MaterialParams& p, const Vec4& stress, Real yield_stress);

// C^EP at a state: the plastic branch with xi = s - sum alpha_i and the state's hardening
// modulus when the state is on its yield surface, the elastic matrix otherwise (the run-time
// monotonicity monitor's tangent).
Mat4 continuum_tangent(const MaterialParams& p, const MaterialState& state);

// Initial state of an integration point (stress free, yield stress sigma_y0).
MaterialState initial_state(const MaterialParams& p);

// Stress update for a strain increment [xx, yy, zz, 2xy] (Green-Lagrange increment of the step,
// referred to the configuration at its start) from the committed state.
// The hardening variable is committed.eq_plastic_strain: the yield stress used is
// sigma_Y(eps_p) (committed.yield_stress is an output, recomputed in trial); the back-stresses are
// committed.back_stress.
// Zero and purely volumetric increments are always elastic (ReturnMapping: a trial stress
// within a relative 1e-12 of the yield stress is elastic). Substep ends every plastic sub-step
// with a closed-form backward-Euler return of the drifted stress at fixed strain (consistent
// drift correction: eps_p moves with the stress), so its end state lies on the yield surface.
// Throws NumericalError when the strain increment or committed state is not finite, or when
// the result is (inadmissible parameters).
MaterialUpdate update_material(const MaterialParams& p, const Vec4& strain_increment, const MaterialState& committed);

// The Armstrong-Frederick recovery frozen at a plastic multiplier d*: back-stress i ends at
// beta_i (alpha_i^n + 2/3 C_i deps_p) with beta_i = 1/(1 + gamma_i d*) fixed, a linear kinematic
// update that has an incremental potential (a true `energy`, a symmetric tangent). When the
// returned multiplier (trial minus committed eq_plastic_strain) equals d*, the result is
// update_material's: the interior-point backend iterates d* to that fixed point.
struct FrozenRecovery {
  Real multiplier = 0.0;  // d* >= 0
};
MaterialUpdate update_material(const MaterialParams& p, const Vec4& strain_increment, const MaterialState& committed,
                               FrozenRecovery frozen);

// sqrt(I2) of the thesis: square root of the second invariant of the stress deviator,
// sqrt(1/2 s:s) (the von Mises stress divided by sqrt(3)).
Real sqrt_j2(const Vec4& stress);
// Von Mises equivalent stress sqrt(3/2 s:s).
Real von_mises(const Vec4& stress);

}  // namespace roller
