#pragma once
// Carter's traction of steady rolling under a tangential force Q on the Hertz pressure
// p(x) = p0 sqrt(1 - x^2/a^2) (Carter 1926; Johnson, Contact Mechanics, 1985, §8.2;
// docs/validation.md, Carter). With the friction coefficient mu and |Q| <= mu P:
//   c/a = sqrt(1 - |Q| / (mu P)),
//   q(x) = mu p(x) - mu (c/a) p0 sqrt(1 - (x - d)^2 / c^2)   in the stick zone |x - d| < c,
//   q(x) = mu p(x)                                           in the slip zone,
// with d = a - c: the stick zone touches the leading edge. x runs along the travel from the
// contact's centre (the leading edge at x = a); q is signed as Q (> 0: the strip is dragged along
// the travel). On an elastic strip with nu = 0.5 (normal and tangential problems uncoupled) it is
// the traction of rolling with the creep s = (mu a / R)(1 - c/a); on a plastic strip, or with
// nu < 0.5, the creep that carries Q is another.
#include <vector>

#include "roller/analysis/hertz.hpp"

namespace roller {

struct CarterTraction {
  HertzSolution hertz;
  Real friction = 0.0;          // mu
  Real ratio = 0.0;             // Q / P, signed
  Real stick_half_width = 0.0;  // c [mm]: 0 when the contact slides everywhere
  Real stick_centre() const;    // d = a - c [mm], along the travel
  bool sticks(Real x) const;    // whether x (along the travel, from the centre) lies in the stick zone
  // The semi-ellipse q takes off mu p over the stick zone, divided by mu: half-width c, peak p0 c/a.
  HertzSolution stick_relief() const;
  Real direction() const { return ratio < 0.0 ? -1.0 : 1.0; }  // the sign of Q
  Real traction(Real x) const;                                 // q(x)
  // The creep s = (mu a / R)(1 - c/a) with which a rigid roller of radius R carries Q on an
  // elastic strip whose normal and tangential problems uncouple (nu = 0.5).
  Real elastic_creep(Real radius) const;
};

// Throws InputError when |Q/P| exceeds mu (the roller would slide) or is not finite.
CarterTraction carter_traction(const HertzSolution& hertz, Real ratio, Real friction);

// Work-equivalent nodal forces of stick_relief() on a surface chain with nodes at x (along the
// travel from the contact's centre, sorted): what q takes off mu p at each node, divided by mu; zero
// when the contact slides everywhere.
std::vector<Real> stick_relief_forces(const CarterTraction& t, const std::vector<Real>& x);

// Work-equivalent nodal forces of q on a surface chain with nodes at x (along the travel from the
// contact's centre, sorted), as hertz_nodal_forces gives them for p: they sum to Q.
std::vector<Real> carter_nodal_forces(const CarterTraction& t, const std::vector<Real>& x);

}  // namespace roller
