#pragma once
// The stress at the surface of an elastic half-plane under semi-elliptic tractions: a normal
// pressure p(x) = p0 sqrt(1 - ((x - m)/b)^2) (Hertz's) and shear tractions of the same shape
// (q = mu p when the contact slides; Carter's stick zone takes a smaller ellipse off it). At the
// surface sigma_yy = -p and sigma_xy = tau; sigma_xx = -p - (2/pi) PV int tau(s)/(x - s) ds
// (Johnson, Contact Mechanics, (2.25)), which for an ellipse of peak T is -2 T xi under it and
// -2 T (xi - sign(xi) sqrt(xi^2 - 1)) beside it, xi = (x - m)/b: McEwen's surface values, whose
// square-root edges the elements below a surface smooth (steady/shakedown_limit.hpp).
#include <vector>

#include "roller/core/types.hpp"

namespace roller {

// peak * sqrt(1 - ((x - centre)/half_width)^2) on |x - centre| < half_width; the peak signed.
struct EllipticLoad {
  Real centre = 0.0;
  Real half_width = 1.0;
  Real peak = 0.0;
  Real at(Real x) const;
};

// The surface stress [xx, yy, zz, xy] at x (zz, the out-of-plane stress, left 0: nu (xx + yy) in
// plane strain for the caller's nu) under the pressure and the shear tractions (y up, the
// pressure pushing down: sigma_yy = -p; a shear's sign is sigma_xy's).
Vec4 half_plane_surface_stress(Real x, const EllipticLoad& pressure, const std::vector<EllipticLoad>& shears);

// The semi-ellipse with the resultant, centroid and second moment of the nodal forces f at the
// points x, each the load over its tributary length l: P = sum f, m = sum f x / P, b^2/4 = sum f
// ((x - m)^2 - l^2/12) / P (an ellipse's second moment is b^2/4; l^2/12 is what lumping a load
// spread over l into its node adds), peak 2P/(pi b).
EllipticLoad elliptic_fit(const std::vector<Real>& x, const std::vector<Real>& f, const std::vector<Real>& l);

}  // namespace roller
