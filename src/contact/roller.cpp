#include "roller/contact/roller.hpp"

#include <cmath>

#include <fmt/format.h>

namespace roller {

bool RollerSpec::is_valid(std::string* why) const {
  auto bad = [why](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  if (!(radius > 0.0)) return bad(fmt::format("roller.radius = {}: must be > 0", radius));
  if (suspension) {
    const SuspensionSpec& q = *suspension;
    for (auto [name, v] : {std::pair{"mass", q.mass}, {"damping", q.damping}, {"stiffness", q.stiffness}})
      if (!(v >= 0.0 && std::isfinite(v)))
        return bad(fmt::format("roller.suspension.{} = {}: must be a finite value >= 0", name, v));
    if (!(q.stiffness > 0.0 || q.mass > 0.0))
      return bad(
          fmt::format("roller.suspension.stiffness = {}: a suspension needs stiffness > 0 or mass > 0", q.stiffness));
  }
  for (std::size_t i = 0; i < path.size(); ++i) {
    const PathSegment& s = path[i];
    const std::string at = fmt::format("roller.path[{}]", i);
    if (s.first_step < 1 || s.last_step < s.first_step)
      return bad(fmt::format("{}.steps = [{}, {}]: expected 1 <= first <= last", at, s.first_step, s.last_step));
    if (i > 0 && s.first_step <= path[i - 1].last_step)
      return bad(fmt::format("{}.steps = [{}, {}]: overlaps the previous segment (ends at step {})", at, s.first_step,
                             s.last_step, path[i - 1].last_step));
    for (Real slip : {s.slip_start, s.slip_end})
      if (!(slip >= -1.0 && slip <= 1.0))
        return bad(
            fmt::format("{}.slip = {}: expected -1 <= slip <= 1 (1: the roller slides "
                        "without turning)",
                        at, slip));
    if (s.harmonic_wavelength < 0.0)
      return bad(fmt::format("{}.harmonic.wavelength = {}: must be > 0", at, s.harmonic_wavelength));
  }
  return true;
}

namespace {

// Pose at the end of integer step n.
RollerPose pose_at_step(const RollerSpec& spec, const Vec2& start_centre, int n) {
  const Real s = n;
  RollerPose pose;
  pose.centre = start_centre;
  pose.angle = spec.start_angle;
  for (const PathSegment& seg : spec.path) {
    const Real begin = seg.first_step - 1;
    const Real length = seg.last_step - begin;
    if (s <= begin) break;
    const Real f = std::min(1.0, (s - begin) / length);  // fraction of the segment done
    const Real dx = f * seg.dx;
    pose.centre.x() += dx;
    pose.centre.y() += f * seg.dy;
    // d(phi) = -dx (1 - slip)/R with the slip varying linearly over the segment: integrate.
    const Real slip_mean = seg.slip_start + 0.5 * f * (seg.slip_end - seg.slip_start);
    pose.angle += -dx * (1.0 - slip_mean) / spec.radius;
    // The harmonic offset follows the distance rolled within the segment (|dx|, thesis: u_x is
    // the distance travelled) and is held after it.
    if (seg.harmonic_wavelength > 0.0)
      pose.centre.y() += seg.harmonic_amplitude * std::sin(2.0 * M_PI * std::abs(dx) / seg.harmonic_wavelength);
  }
  return pose;
}

}  // namespace

RollerPose roller_pose(const RollerSpec& spec, const Vec2& start_centre, Real s) {
  // The path is defined at step ends (the thesis moves the roller once per step); within a
  // step (sub-increments after a cut) the pose is interpolated linearly, so cutting a step
  // never changes the path.
  const int lo = static_cast<int>(std::floor(s));
  const Real f = s - lo;
  const RollerPose a = pose_at_step(spec, start_centre, lo);
  if (f == 0.0) return a;
  const RollerPose b = pose_at_step(spec, start_centre, lo + 1);
  return {a.centre + f * (b.centre - a.centre), a.angle + f * (b.angle - a.angle)};
}

}  // namespace roller
