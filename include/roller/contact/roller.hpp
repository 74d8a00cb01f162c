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
};

struct RollerSpec {
  Real radius = 300.0;               // R [mm]
  std::optional<Vec2> start_centre;  // default: above the strip's top at x = length/2, touching
  Real start_angle = 0.0;
  std::vector<PathSegment> path;             // steps not covered by a segment keep the roller still
  std::optional<SuspensionSpec> suspension;  // absent: the centre follows the path exactly
  bool is_valid(std::string* why) const;
};

// Pose at (fractional) step s: s = 0 is the start, s = 2.5 halfway through step 3. The path is
// sampled at step ends and interpolated linearly within a step.
RollerPose roller_pose(const RollerSpec& spec, const Vec2& start_centre, Real s);

}  // namespace roller
