#pragma once
// Carter's zones measured on a run's contact (docs/validation.md, "Carter: steady rolling with
// creep"): a from a least-squares parabola through p_n^2 over the nodes carrying pressure; the stick
// zone from the moments of the traction deficit w = mu F_N - |F_T| (zero where the node slips;
// Carter's w = mu p0 (c/a) sqrt(1 - (x - d)^2/c^2) on the stick zone, so its centroid is d and its
// standard deviation c/2).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "roller/contact/contact_records.hpp"

namespace roller::test {

struct Parabola {  // y = amp (1 - (x - centre)^2 / half_width^2)
  Real centre = 0.0, half_width = 0.0, amp = 0.0;
  bool ok = false;
};

// Least-squares y = c0 + c1 x + c2 x^2 (x shifted by its mean for conditioning).
inline Parabola fit_parabola(const std::vector<Real>& x, const std::vector<Real>& y) {
  Parabola out;
  const std::size_t n = x.size();
  if (n < 3) return out;
  Real xm = 0.0;
  for (Real v : x) xm += v / static_cast<Real>(n);
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const Real s = x[i] - xm;
    const Eigen::Vector3d phi(1.0, s, s * s);
    A += phi * phi.transpose();
    b += phi * y[i];
  }
  const Eigen::Vector3d c = A.ldlt().solve(b);
  const Real curv = -c(2);
  if (!(curv > 0.0)) return out;
  const Real s0 = c(1) / (2.0 * curv);
  out.amp = c(0) + curv * s0 * s0;
  if (!(out.amp > 0.0)) return out;
  out.centre = xm + s0;
  out.half_width = std::sqrt(out.amp / curv);
  out.ok = true;
  return out;
}

// The contact of the last step: a from a parabola through p_n^2, the stick zone's centre d and
// half-width c from the moments of the traction deficit, the sticking nodes' extent.
struct StickZone {
  Parabola contact;
  Real a = 0.0, d_abs = 0.0, c = 0.0;
  Real x_stick_min = 1e300, x_stick_max = -1e300;
  int n_stick = 0, n_slip = 0;
};

inline StickZone measure_stick_zone(const std::vector<NodeContactRecord>& contact, Real mu) {
  StickZone z;
  Real p_max = 0.0;
  for (const auto& c : contact) p_max = std::max(p_max, c.contact.normal_force / c.tributary_length);
  REQUIRE(p_max > 0.0);
  std::vector<Real> xa, p2;
  Real w0 = 0.0, w1 = 0.0, w2 = 0.0;
  for (const auto& c : contact) {
    const Real p = c.contact.normal_force / c.tributary_length;
    if (p <= 1e-3 * p_max) continue;
    const Real x = c.position.x();
    xa.push_back(x);
    p2.push_back(p * p);
    const Real w = std::max(mu * c.contact.normal_force - std::abs(c.contact.tangential_force), 0.0);
    w0 += w;
    w1 += w * x;
    w2 += w * x * x;
    if (c.contact.status == ContactStatus::Stick) {
      ++z.n_stick;
      z.x_stick_min = std::min(z.x_stick_min, x);
      z.x_stick_max = std::max(z.x_stick_max, x);
    }
    z.n_slip += c.contact.status == ContactStatus::Slip;
  }
  z.contact = fit_parabola(xa, p2);
  REQUIRE(z.contact.ok);
  REQUIRE(w0 > 0.0);
  z.a = z.contact.half_width;
  z.d_abs = w1 / w0;                                                  // centre of the stick zone
  z.c = 2.0 * std::sqrt(std::max(w2 / w0 - z.d_abs * z.d_abs, 0.0));  // its half-width
  return z;
}

}  // namespace roller::test
