#pragma once
// Hertz line contact of a rigid cylinder on an elastic half-plane (docs/validation.md, Hertz line
// contact):
//   E* = E/(1 - nu^2),  a = sqrt(4 P R / (pi E*)),  p0 = 2P/(pi a),  p(x) = p0 sqrt(1 - x^2/a^2)
// and the comparison of a computed pressure profile with it.
#include <vector>

#include "roller/core/types.hpp"

namespace roller {

struct HertzSolution {
  Real load = 0.0;              // P [N per mm width]
  Real half_width = 0.0;        // a [mm]
  Real peak = 0.0;              // p0 [MPa]
  Real pressure(Real x) const;  // p at distance x from the centre (0 outside the contact)
};

HertzSolution hertz_line_contact(Real load, Real radius, Real plane_strain_modulus);
// The load per unit length whose Hertz peak pressure is p0: P = pi R p0^2 / E* (the inverse of
// hertz_line_contact's p0 = sqrt(P E* / (pi R))).
Real hertz_line_load(Real peak_pressure, Real radius, Real plane_strain_modulus);

// A pressure sample at surface position x (mm from the contact centre).
struct PressureSample {
  Real x = 0.0;
  Real p = 0.0;
};

struct HertzComparison {
  HertzSolution analytic;
  Real half_width = 0.0;        // a fitted to the computed profile: least squares of p^2 = p0^2 - (p0/a)^2 x^2
                                // over the samples with p > 1e-6 of the largest
  Real peak = 0.0;              // largest computed pressure
  Real half_width_error = 0.0;  // (a_h - a)/a
  Real peak_error = 0.0;        // (p0_h - p0)/p0
  Real l2_error = 0.0;          // ||p_h - p||_L2 / ||p||_L2 over the samples (trapezoidal)
  // The same norm against the analytic pressure as a node-to-surface contact sees it: the
  // work-equivalent nodal force of p (the integral of p times the node's hat function over its
  // neighbouring segments) over the node's tributary length, i.e. p averaged the way a nodal
  // force averages it. Nodal sampling puts the full weight of the square-root edge on the
  // nearest nodes (a node 0.2 % of a outside the analytic edge carries 10 % of p0 and counts
  // as all error); this measure compares like with like and converges where l2_error stalls.
  Real l2_error_averaged = 0.0;
};

// Work-equivalent nodal forces of the analytic pressure on a surface chain with nodes at x
// (sorted): F_i = integral of p times the hat function of node i (per unit width). They sum to
// the load carried within [x_0, x_last].
std::vector<Real> hertz_nodal_forces(const HertzSolution& h, const std::vector<Real>& x);

// Samples sorted by x; `load` is the computed total normal load.
HertzComparison compare_with_hertz(const std::vector<PressureSample>& samples, Real load, Real radius,
                                   Real plane_strain_modulus);

}  // namespace roller
