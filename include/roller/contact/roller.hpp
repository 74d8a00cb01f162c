#pragma once
// The rigid roller: a circle of radius R with centre c(t) and rotation angle phi(t)
// (counter-clockwise positive, radians); docs/model.md, Contact kinematics and Roller path and
// creep.
//
// Prescribed paths are lists of segments over scene steps. Within a segment the centre moves
// linearly by (dx, dy); an optional harmonic adds A sin(2 pi |x_c - x_segment_start| / L) to y
// (thesis Z1: the argument is the distance rolled); the angle follows the rolling kinematics
// with creep,
//   slip ratio s = (v_x - |omega| R) / v_x   =>   d(phi) = -dx (1 - s) / R,
// so s = 0 is rolling without slip to +x (clockwise rotation), s > 0 a roller that lags.
//
// A segment may prescribe the vertical force on the roller instead of its vertical motion (fy):
// over the segment's steps the centre's height is an unknown that carries the force
// (contact/force_control.hpp), and the offset it reaches from the path is kept afterwards. In the
// same way fx prescribes the horizontal force: the centre's x floats about the path's x while the
// path's dx still turns the roller (rolling kinematics), so dx = 0 blocks the rotation (the
// Cattaneo-Mindlin protocol) and dx != 0 rolls it under a traction with the creep an outcome
// (Carter). fx ramps over its segment like fy; q_over_p instead holds the horizontal force at
// q/p times the vertical one from the segment's first step, along the travel (the traction ratio
// of the stationary pass and of Melan's bound: docs/scenes.md, One traction). A segment may also
// set the friction coefficient for its steps (mu = 0 while pressing, mu once the tangential load
// starts).
#include <optional>
#include <string>
#include <vector>

#include "roller/core/types.hpp"
#include "roller/dynamics/suspension_spec.hpp"

namespace roller {

struct RollerPose {
  Vec2 centre = Vec2::Zero();
  Real angle = 0.0;
};

struct PathSegment {
  int first_step = 1;  // the segment acts over steps first_step..last_step (1-based, inclusive)
  int last_step = 1;
  Real dx = 0.0;  // total centre travel over the segment [mm]
  Real dy = 0.0;
  Real slip_start = 0.0;  // creep ratio at the start and end of the segment (linear in between)
  Real slip_end = 0.0;
  Real harmonic_amplitude = 0.0;   // A [mm]
  Real harmonic_wavelength = 0.0;  // L_p [mm]; 0 = no harmonic
  // Vertical force of the strip on the roller at the segment's end [N per mm], reached linearly
  // from the fy of the last earlier segment that has one (0 if none); replaces dy.
  std::optional<Real> fy;
  // fy given in the users' terms (roller.path.p0 or p0_over_k): how it was computed, for the
  // resolved scene (empty when fy was given).
  std::string fy_origin;
  // Horizontal force of the strip on the roller at the segment's end [N per mm], reached linearly
  // from the fx of the last earlier segment that has one (0 if none); the centre's x carries it.
  std::optional<Real> fx;
  // The traction ratio q/p: the roller's tangential force on the strip along the travel over its
  // normal force, held at every step of the segment (fx = -sign(dx) q/p fy); instead of fx.
  std::optional<Real> q_over_p;
  std::optional<Real> friction;  // Coulomb coefficient over the segment's steps (else contact.friction)
};

// The horizontal force a segment prescribes at its end (its fx, or q/p of its fy), if any.
std::optional<Real> segment_end_fx(const PathSegment& seg);

struct RollerSpec {
  Real radius = 300.0;               // R [mm]
  std::optional<Vec2> start_centre;  // default: above the strip's top at x = length/2, touching
  Real start_angle = 0.0;
  // Start height from the strip as it is at the start (after a restart): the centre, at its x,
  // is moved vertically until the roller touches the highest contact candidate under it, so
  // that the path's dy are depths below the strip's present surface (a second pass over a groove).
  bool touch_strip = false;
  std::vector<PathSegment> path;             // steps not covered by a segment keep the roller still
  std::optional<SuspensionSpec> suspension;  // absent: the centre follows the path exactly
  // An elastic roller (contact/elastic_roller.hpp): Young's modulus [MPa] (0: rigid), Poisson's
  // ratio, and the bore of a ring or sleeve [mm] (0: a solid disc).
  Real youngs_modulus = 0.0;
  Real poisson_ratio = 0.3;
  Real inner_radius = 0.0;
  bool elastic() const { return youngs_modulus > 0.0; }
  // E/(1 - nu^2) of an elastic roller.
  Real plane_strain_modulus() const { return youngs_modulus / (1.0 - poisson_ratio * poisson_ratio); }
  bool is_valid(std::string* why) const;
};

// The segment that moves the roller farthest along the strip (the largest |dx|; the first of
// equals), or null when none moves it along: a pass's travel.
const PathSegment* travel_segment(const RollerSpec& spec);

// Pose at (fractional) step s: s = 0 is the start, s = 2.5 halfway through step 3. The path is
// sampled at step ends and interpolated linearly within a step.
RollerPose roller_pose(const RollerSpec& spec, const Vec2& start_centre, Real s);

// The forces prescribed at (fractional) step s, s in (n - 1, n] belonging to step n: per
// direction, none when step n's segment prescribes the motion (or no segment covers it).
struct PrescribedForce {
  std::optional<Real> fx;
  std::optional<Real> fy;
  bool any() const { return fx || fy; }
};
PrescribedForce prescribed_force(const RollerSpec& spec, Real s);

// The friction coefficient of step n's segment, else `fallback` (contact.friction).
Real friction_in_step(const RollerSpec& spec, int step, Real fallback);

}  // namespace roller
