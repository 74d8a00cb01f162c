#pragma once
// Carter's zones measured on a run's contact (docs/validation.md, "Carter: steady rolling with
// creep"): a from the semi-ellipse fitted to the normal nodal forces, the stick zone from the one
// fitted to the traction deficit w = mu F_N - |F_T| (zero where the node slips; Carter's
// w = mu p0 (c/a) sqrt(1 - (x - d)^2/c^2) on the stick zone), both like with like
// (analysis/elliptic_fit.hpp).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "roller/analysis/elliptic_fit.hpp"
#include "roller/contact/contact_records.hpp"

namespace roller::test {

// The contact of the last step: a from the ellipse fitted to the normal nodal forces, the stick
// zone's centre d and half-width c from the ellipse fitted to the traction deficit, the sticking
// nodes' extent.
struct StickZone {
  EllipticFit contact, stick;
  Real a = 0.0, d_abs = 0.0, c = 0.0;
  Real x_stick_min = 1e300, x_stick_max = -1e300;
  int n_stick = 0, n_slip = 0;
};

inline StickZone measure_stick_zone(const std::vector<NodeContactRecord>& contact, Real mu) {
  StickZone z;
  std::vector<Real> x, normal, deficit;
  for (const auto& c : contact) {
    const bool touches = c.contact.status != ContactStatus::Open;
    x.push_back(c.position.x());
    normal.push_back(touches ? c.contact.normal_force : 0.0);
    deficit.push_back(touches ? std::max(mu * c.contact.normal_force - std::abs(c.contact.tangential_force), 0.0)
                              : 0.0);
    if (c.contact.status == ContactStatus::Stick) {
      ++z.n_stick;
      z.x_stick_min = std::min(z.x_stick_min, x.back());
      z.x_stick_max = std::max(z.x_stick_max, x.back());
    }
    z.n_slip += c.contact.status == ContactStatus::Slip;
  }
  z.contact = fit_elliptic_forces(x, normal);
  REQUIRE(z.contact.valid);
  z.a = z.contact.half_width;
  if (mu == 0.0) return z;  // frictionless: no stick zone
  z.stick = fit_elliptic_forces(x, deficit);
  REQUIRE(z.stick.valid);
  z.d_abs = z.stick.centre;  // centre of the stick zone
  z.c = z.stick.half_width;  // its half-width
  return z;
}

}  // namespace roller::test
