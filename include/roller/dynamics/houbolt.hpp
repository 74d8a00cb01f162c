#pragma once
// Houbolt's backward-difference integration (docs/model.md, Houbolt scheme) of one vector
// quantity u(t) (the strip's nodal displacements, or the roller's suspension deflection):
//   a_{n+1} = (2 u_{n+1} - 5 u_n + 4 u_{n-1} - u_{n-2}) / dt^2
//   v_{n+1} = (11 u_{n+1} - 18 u_n + 9 u_{n-1} - 2 u_{n-2}) / (6 dt)
// The history holds u_n, u_{n-1}, u_{n-2} at a uniform spacing dt.
//
// Starting procedure (stated and tested, tests/dynamics/test_houbolt.cpp): the two fictitious
// past values come from the Taylor expansion of the initial state (u0, v0, a0),
//   u_{-1} = u0 - dt v0 + dt^2/2 a0,   u_{-2} = u0 - 2 dt v0 + 2 dt^2 a0,
// so the scheme's cubic through them reproduces v0 and a0 to O(dt^2). A body at rest has
// u_{-1} = u_{-2} = u0.
//
// Cut steps: Houbolt needs equally spaced history, so a step cut into sub-increments of
// length h runs on the history resampled at spacing h (the quadratic through the three stored
// values); when the whole step is done, the driver returns to the step-level history.
#include "roller/core/types.hpp"

namespace roller {

class HouboltHistory {
 public:
  HouboltHistory() = default;
  // History of a state starting at (u0, v0, a0) with time step dt (Taylor start, above).
  static HouboltHistory start(const VecX& u0, const VecX& v0, const VecX& a0, Real dt);
  // History of a body at rest at u0.
  static HouboltHistory at_rest(const VecX& u0, Real dt);
  // History from three stored values (u_n, u_{n-1}, u_{n-2}) at spacing dt (for state files).
  static HouboltHistory from_values(VecX u_n, VecX u_nm1, VecX u_nm2, Real dt);

  bool empty() const { return dt_ <= 0.0; }
  Real dt() const { return dt_; }
  const VecX& u_n() const { return u_[0]; }
  const VecX& u_nm1() const { return u_[1]; }
  const VecX& u_nm2() const { return u_[2]; }

  // a_{n+1} = acceleration_coefficient() * u_{n+1} + acceleration_offset(); likewise v.
  Real acceleration_coefficient() const { return 2.0 / (dt_ * dt_); }
  VecX acceleration_offset() const;
  Real velocity_coefficient() const { return 11.0 / (6.0 * dt_); }
  VecX velocity_offset() const;
  VecX acceleration(const VecX& u_next) const;
  VecX velocity(const VecX& u_next) const;

  // Shifts the history by one step: u_{n+1} becomes u_n.
  void advance(const VecX& u_next);
  // The same motion sampled at spacing h: quadratic through the stored values at t_n - h, t_n - 2h.
  HouboltHistory resampled(Real h) const;

 private:
  VecX u_[3];  // u_n, u_{n-1}, u_{n-2}
  Real dt_ = 0.0;
};

// Roots of Houbolt's characteristic polynomial for the undamped oscillator with
// Omega = omega dt: (2 + Omega^2) z^3 - 5 z^2 + 4 z - 1 = 0. The principal (complex) root
// z = |z| e^{i omega_bar dt} gives the scheme's period T_bar = 2 pi / omega_bar and its
// amplitude decay |z| per step (the reference for the integrator's tests and docs).
struct HouboltSpectrum {
  Real modulus = 0.0;        // |z| of the principal root: amplitude ratio per step
  Real period_ratio = 0.0;   // T_bar / T
  Real damping_ratio = 0.0;  // xi_bar = -ln|z| / (omega_bar dt)
};
HouboltSpectrum houbolt_spectrum(Real omega_dt);

}  // namespace roller
