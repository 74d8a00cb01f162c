#pragma once
// Carter's steady rolling with creep of a rigid cylinder on an elastic half-plane (Carter 1926;
// Johnson, Contact Mechanics, 1985, §8.2; docs/validation.md, Carter), on the Hertz pressure
// p(x) = p0 sqrt(1 - x^2/a^2). With the creep s = (v - omega R)/v and the friction coefficient mu:
//   c/a = 1 - s R / (mu a)   (full sliding, c = 0, when s R >= mu a),   Q / (mu P) = 1 - (c/a)^2,
//   q(x) = mu p(x) - mu (c/a) p0 sqrt(1 - (x - d)^2 / c^2)   in the stick zone |x - d| < c,
//   q(x) = mu p(x)                                           in the slip zone,
// with d = a - c: the stick zone touches the leading edge. x runs along the travel from the
// contact's centre (the leading edge at x = a). q acts on the strip along the travel for s > 0
// (the roller's surface lags its centre), against it for s < 0.
#include <vector>

#include "roller/analysis/hertz.hpp"

namespace roller {

struct CarterTraction {
  HertzSolution hertz;
  Real friction = 0.0;          // mu
  Real creep = 0.0;             // s
  Real stick_half_width = 0.0;  // c [mm]: 0 when the contact slides everywhere
  Real ratio() const;           // Q / (mu P) = 1 - (c/a)^2, signed as the creep
  Real stick_centre() const;    // d = a - c [mm], along the travel
  bool sticks(Real x) const;    // whether x (along the travel, from the centre) lies in the stick zone
  // The semi-ellipse q takes off mu p over the stick zone, divided by mu: half-width c, peak p0 c/a.
  HertzSolution stick_relief() const;
  Real traction(Real x) const;  // q(x), signed as the creep
};

// Throws InputError when mu <= 0 and the creep is not zero, or when the creep is not finite.
CarterTraction carter_traction(const HertzSolution& hertz, Real creep, Real radius, Real friction);

// Work-equivalent nodal forces of q on a surface chain with nodes at x (along the travel from the
// contact's centre, sorted), as hertz_nodal_forces gives them for p: they sum to Q.
std::vector<Real> carter_nodal_forces(const CarterTraction& t, const std::vector<Real>& x);

}  // namespace roller
