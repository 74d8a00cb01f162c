#include "roller/dynamics/houbolt.hpp"

#include <cmath>
#include <complex>

#include <Eigen/Eigenvalues>

#include "roller/core/error.hpp"

namespace roller {

HouboltHistory HouboltHistory::start(const VecX& u0, const VecX& v0, const VecX& a0, Real dt) {
  return from_values(u0, u0 - dt * v0 + 0.5 * dt * dt * a0, u0 - 2.0 * dt * v0 + 2.0 * dt * dt * a0, dt);
}

HouboltHistory HouboltHistory::at_rest(const VecX& u0, Real dt) { return from_values(u0, u0, u0, dt); }

HouboltHistory HouboltHistory::from_values(VecX u_n, VecX u_nm1, VecX u_nm2, Real dt) {
  if (!(dt > 0.0)) throw NumericalError("Houbolt history needs a time step > 0");
  HouboltHistory h;
  h.u_[0] = std::move(u_n);
  h.u_[1] = std::move(u_nm1);
  h.u_[2] = std::move(u_nm2);
  h.dt_ = dt;
  return h;
}

VecX HouboltHistory::acceleration_offset() const { return (-5.0 * u_[0] + 4.0 * u_[1] - u_[2]) / (dt_ * dt_); }

VecX HouboltHistory::velocity_offset() const { return (-18.0 * u_[0] + 9.0 * u_[1] - 2.0 * u_[2]) / (6.0 * dt_); }

VecX HouboltHistory::acceleration(const VecX& u_next) const {
  return acceleration_coefficient() * u_next + acceleration_offset();
}

VecX HouboltHistory::velocity(const VecX& u_next) const { return velocity_coefficient() * u_next + velocity_offset(); }

void HouboltHistory::advance(const VecX& u_next) {
  u_[2] = std::move(u_[1]);
  u_[1] = std::move(u_[0]);
  u_[0] = u_next;
}

HouboltHistory HouboltHistory::resampled(Real h) const {
  if (h == dt_) return *this;
  // Lagrange quadratic through (0, u_n), (-dt, u_{n-1}), (-2dt, u_{n-2}) at t = -r dt.
  auto at = [&](Real r) {
    const Real l0 = (r - 1.0) * (r - 2.0) / 2.0;  // weights in terms of r = -t/dt
    const Real l1 = -r * (r - 2.0);
    const Real l2 = r * (r - 1.0) / 2.0;
    return VecX(l0 * u_[0] + l1 * u_[1] + l2 * u_[2]);
  };
  const Real r = h / dt_;
  return from_values(u_[0], at(r), at(2.0 * r), h);
}

HouboltSpectrum houbolt_spectrum(Real omega_dt) {
  // Companion matrix of z^3 - (5 z^2 - 4 z + 1)/(2 + W^2).
  const Real d = 2.0 + omega_dt * omega_dt;
  Eigen::Matrix3d c;
  c << 5.0 / d, -4.0 / d, 1.0 / d, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0;
  const Eigen::Vector3cd roots = c.eigenvalues();
  // The principal root is the complex one with positive imaginary part (it exists for the
  // resolved range omega dt below about 2.7; beyond, the response is overdamped and real).
  std::complex<Real> z(0.0, 0.0);
  for (int i = 0; i < 3; ++i)
    if (roots(i).imag() > 0.0 && std::abs(roots(i)) > std::abs(z)) z = roots(i);
  HouboltSpectrum s;
  if (z == std::complex<Real>(0.0, 0.0)) return s;
  const Real omega_bar_dt = std::arg(z);
  s.modulus = std::abs(z);
  s.period_ratio = omega_dt / omega_bar_dt;
  s.damping_ratio = -std::log(s.modulus) / omega_bar_dt;
  return s;
}

}  // namespace roller
