#include "roller/contact/roller.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace roller {

bool RollerSpec::is_valid(std::string* why) const {
  auto bad = [why](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  if (!(radius > 0.0)) return bad(fmt::format("roller.radius = {}: must be > 0", radius));
  if (elastic()) {
    if (!(poisson_ratio > -1.0 && poisson_ratio < 0.5))
      return bad(
          fmt::format("roller.nu = {}: an elastic roller's Poisson's ratio must lie in (-1, 0.5)", poisson_ratio));
    if (!(inner_radius >= 0.0 && inner_radius < radius))
      return bad(
          fmt::format("roller.inner_radius = {}: the bore must lie in [0, radius = {}) mm", inner_radius, radius));
  } else if (inner_radius != 0.0) {
    return bad(fmt::format("roller.inner_radius = {}: a bore needs an elastic roller (roller.E)", inner_radius));
  }
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
    if (s.fy) {
      if (!(*s.fy >= 0.0 && std::isfinite(*s.fy)))
        return bad(
            fmt::format("{}.fy = {}: must be a finite force >= 0 [N per mm] (the contact only pushes)", at, *s.fy));
      if (s.dy != 0.0)
        return bad(
            fmt::format("{}.fy = {}: give either dy (motion) or fy (force) for the vertical direction, not "
                        "both (dy = {})",
                        at, *s.fy, s.dy));
      if (s.harmonic_wavelength > 0.0)
        return bad(
            fmt::format("{}.fy = {}: a harmonic moves the centre's height, which fy leaves free: remove "
                        "one of them",
                        at, *s.fy));
      if (suspension)
        return bad(
            fmt::format("{}.fy = {}: a suspended roller's height is already an unknown; prescribe the "
                        "force without roller.suspension",
                        at, *s.fy));
    }
    if (s.fx) {
      if (!std::isfinite(*s.fx)) return bad(fmt::format("{}.fx = {}: must be a finite force [N per mm]", at, *s.fx));
      if (suspension)
        return bad(
            fmt::format("{}.fx = {}: prescribe forces on a roller without roller.suspension (the suspension "
                        "already makes its height an unknown)",
                        at, *s.fx));
    }
    if (s.q_over_p) {
      if (!(std::abs(*s.q_over_p) <= 10.0))
        return bad(
            fmt::format("{}.q_over_p = {}: expected a traction ratio with |q/p| <= 10 (below the friction "
                        "coefficient for a roller that rolls)",
                        at, *s.q_over_p));
      if (s.fx) return bad(fmt::format("{}.q_over_p = {}: give fx or q_over_p, not both", at, *s.q_over_p));
      if (!s.fy)
        return bad(
            fmt::format("{}.q_over_p = {}: the ratio is taken of the segment's vertical force: give the "
                        "segment fy, p0 or p0_over_k (or prescribe fx)",
                        at, *s.q_over_p));
      if (s.dx == 0.0)
        return bad(
            fmt::format("{}.q_over_p = {}: the traction acts along the travel, and the segment has dx = 0: "
                        "give it its travel, or prescribe fx (the strip's force on the roller in x)",
                        at, *s.q_over_p));
    }
    if (s.friction && !(*s.friction >= 0.0 && *s.friction <= 10.0))
      return bad(fmt::format("{}.friction = {}: must satisfy 0 <= friction <= 10", at, *s.friction));
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

namespace {

const PathSegment* segment_of_step(const RollerSpec& spec, int step) {
  for (const PathSegment& seg : spec.path)
    if (step >= seg.first_step && step <= seg.last_step) return &seg;
  return nullptr;
}

// The force `end_of` gives a segment at step s: ramped from the last earlier segment that has one.
template <class EndOf>
std::optional<Real> ramped_force(const RollerSpec& spec, Real s, EndOf end_of) {
  const int step = static_cast<int>(std::ceil(s - 1e-12));
  Real start = 0.0;  // the force reached by the last earlier force segment
  for (const PathSegment& seg : spec.path) {
    if (step < seg.first_step) break;
    const std::optional<Real> end = end_of(seg);
    if (step <= seg.last_step) {
      if (!end) return std::nullopt;
      const Real begin = seg.first_step - 1;
      const Real f = std::clamp((s - begin) / (seg.last_step - begin), 0.0, 1.0);
      return start + f * (*end - start);
    }
    if (end) start = *end;
  }
  return std::nullopt;
}

// The strip's horizontal force on the roller at q/p of the vertical `fy`: the roller's traction on
// the strip points along the travel.
Real traction_fx(const PathSegment& seg, Real fy) { return -(seg.dx > 0.0 ? 1.0 : -1.0) * *seg.q_over_p * fy; }

}  // namespace

const PathSegment* travel_segment(const RollerSpec& spec) {
  const auto it = std::max_element(spec.path.begin(), spec.path.end(), [](const PathSegment& a, const PathSegment& b) {
    return std::abs(a.dx) < std::abs(b.dx);
  });
  return it == spec.path.end() || it->dx == 0.0 ? nullptr : &*it;
}

std::optional<Real> segment_end_fx(const PathSegment& seg) {
  if (seg.q_over_p && seg.fy) return traction_fx(seg, *seg.fy);
  return seg.fx;
}

PrescribedForce prescribed_force(const RollerSpec& spec, Real s) {
  PrescribedForce out;
  out.fy = ramped_force(spec, s, [](const PathSegment& seg) { return seg.fy; });
  // q/p holds at every step, the press's ramp of fy included; fx ramps from the force before.
  const PathSegment* seg = segment_of_step(spec, static_cast<int>(std::ceil(s - 1e-12)));
  if (seg && seg->q_over_p && out.fy)
    out.fx = traction_fx(*seg, *out.fy);
  else
    out.fx = ramped_force(spec, s, segment_end_fx);
  return out;
}

Real friction_in_step(const RollerSpec& spec, int step, Real fallback) {
  const PathSegment* seg = segment_of_step(spec, step);
  return seg && seg->friction ? *seg->friction : fallback;
}

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
