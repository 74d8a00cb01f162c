#include "roller/contact/passes.hpp"

#include <algorithm>
#include <cmath>

namespace roller {

PassPosition locate_pass(Real s, int steps_per_pass) {
  if (s <= 0.0) return {1, 0.0};
  const int pass = std::max(1, static_cast<int>(std::ceil(s / steps_per_pass - 1e-12)));
  return {pass, s - (pass - 1) * steps_per_pass};
}

RollerSpec roller_of_pass(const RollerSpec& spec, const PassSpec& passes, int pass, const Vec2& start_centre,
                          int steps_per_pass, Vec2* pass_start) {
  *pass_start = start_centre;
  if (passes.direction == PassDirection::Same || pass % 2 == 1) return spec;
  // Back the way the odd passes came: from where the scene's path ends (in x), every travel and
  // horizontal force in x reversed (a traction acts along the rolling direction); heights,
  // vertical forces, slips and harmonics as in the scene.
  RollerSpec mirrored = spec;
  for (PathSegment& seg : mirrored.path) {
    seg.dx = -seg.dx;
    if (seg.fx) seg.fx = -*seg.fx;
  }
  pass_start->x() = roller_pose(spec, start_centre, steps_per_pass).centre.x();
  return mirrored;
}

}  // namespace roller
