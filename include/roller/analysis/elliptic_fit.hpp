#pragma once
// A semi-elliptic traction t(x) = t0 sqrt(1 - (x - d)^2 / w^2) fitted to a surface chain's nodal
// forces like with like: each node's force against the work-equivalent nodal force of the ellipse
// (hertz_nodal_forces), so an exact finite-element solution of that traction is fitted exactly.
// Hertz's pressure is such an ellipse (w = a); so is Cattaneo's and Carter's stick correction
// mu p - q (w = c, centred on the stick zone). A zone read off the nodes' statuses is resolved to
// half a node spacing, and a least-squares fit of p^2 to nodal pressures underestimates the edge
// the lumped edge nodes carry; this fit has neither bias (docs/validation.md, Elastic roller).
#include <vector>

#include "roller/core/types.hpp"

namespace roller {

struct EllipticFit {
  Real centre = 0.0;      // d [mm]
  Real half_width = 0.0;  // w [mm]
  Real peak = 0.0;        // t0 [force per area]
  Real residual = 0.0;    // ||F - F_fit|| / ||F||
  bool valid = false;     // fewer than three loaded nodes, or no ellipse fits
};

// `x`: node positions sorted by x (mm); `force[i]`: node i's force (per unit width) of the traction
// fitted; forces at or below 1e-6 of the largest count as unloaded.
EllipticFit fit_elliptic_forces(const std::vector<Real>& x, const std::vector<Real>& force);

}  // namespace roller
