#include "roller/io/roller_program.hpp"

#include <algorithm>
#include <cmath>

#include "roller/core/error.hpp"

namespace roller {

RollerProgram::RollerProgram(const std::optional<RollerSpec>& roller, const PassSpec& passes, int steps_per_pass,
                             const Vec2& start_centre)
    : forward_(roller),
      alternate_(passes.direction == PassDirection::Alternate),
      steps_per_pass_(steps_per_pass),
      start_(start_centre),
      backward_start_(start_centre) {
  ROLLER_ASSERT(steps_per_pass >= 1, "a pass has at least one step");
  if (!roller || !alternate_) return;
  // Back the way the odd passes came: from where the scene's path ends (in x), every travel and
  // horizontal force in x reversed (a traction acts along the rolling direction).
  backward_ = roller;
  for (PathSegment& seg : backward_->path) {
    seg.dx = -seg.dx;
    if (seg.fx) seg.fx = -*seg.fx;
  }
  backward_start_.x() = roller_pose(*roller, start_centre, steps_per_pass).centre.x();
}

PassPosition RollerProgram::locate(Real s) const {
  if (s <= 0.0) return {1, 0.0};
  const int pass = std::max(1, static_cast<int>(std::ceil(s / steps_per_pass_ - 1e-12)));
  const PassPosition at{pass, s - (pass - 1) * steps_per_pass_};
  ROLLER_ASSERT(at.local > -1e-9 && at.local <= steps_per_pass_ + 1e-9, "a step lies within its pass");
  return at;
}

RollerPose RollerProgram::pose_in_pass(int pass, Real local) const {
  ROLLER_ASSERT(forward_, "a pose is asked of a run without a roller");
  return mirrored(pass) ? roller_pose(*backward_, backward_start_, local) : roller_pose(*forward_, start_, local);
}

RollerPose RollerProgram::pose(Real s) const {
  const PassPosition at = locate(s);
  return pose_in_pass(at.pass, at.local);
}

PrescribedForce RollerProgram::force(Real s) const {
  if (!forward_) return {};
  const PassPosition at = locate(s);
  return prescribed_force(mirrored(at.pass) ? *backward_ : *forward_, at.local);
}

Real RollerProgram::friction(Real s, Real fallback) const {
  ROLLER_ASSERT(forward_, "a friction coefficient is asked of a run without a roller");
  const PassPosition at = locate(s);
  // Mirroring keeps the segments' friction: the scene's path answers for every pass.
  return friction_in_step(*forward_, static_cast<int>(std::ceil(at.local - 1e-12)), fallback);
}

}  // namespace roller
