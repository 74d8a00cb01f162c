#include "roller/contact/arc_predictor.hpp"

#include <cmath>

namespace roller {

Vec2 arc_predicted_position(const Vec2& start, const Vec2& end, const Vec2& centre, Real radius, Real dphi) {
  const Vec2 p0 = start - centre, p1 = end - centre;
  if (p1.norm() >= radius) return end;
  Vec2 c;           // first touch, relative to the centre
  Real w_fr = 0.0;  // distance travelled outside
  Real w_in = 0.0;  // distance that would be travelled inside
  if (p0.norm() <= radius) {
    c = p0.norm() > 0.0 ? Vec2(radius * p0.normalized()) : Vec2(0.0, -radius);
    w_in = (p1 - p0).norm();
  } else {
    // |p0 + t d| = R for the entry t in (0, 1): the smaller root of the quadratic.
    const Vec2 d = p1 - p0;
    const Real a = d.squaredNorm(), b = 2.0 * p0.dot(d), q = p0.squaredNorm() - radius * radius;
    const Real t = (-b - std::sqrt(std::max(b * b - 4.0 * a * q, 0.0))) / (2.0 * a);
    c = p0 + t * d;
    w_fr = t * std::sqrt(a);
    w_in = (1.0 - t) * std::sqrt(a);
  }
  const Real fraction = w_fr + w_in > 0.0 ? w_in / (w_fr + w_in) : 1.0;
  const Real theta = std::atan2(c.y(), c.x()) + dphi * fraction;  // arc R dphi fraction
  return centre + radius * Vec2(std::cos(theta), std::sin(theta));
}

int apply_arc_predictor(const std::vector<Index>& nodes, const std::vector<Vec2>& positions, const DofMap& dofs,
                        const RollerMotion& motion, VecX& predictor) {
  int moved = 0;
  for (Index a : nodes) {
    const Vec2 start = positions[a];
    const Vec2 end = start + Vec2(predictor(2 * a), predictor(2 * a + 1));
    const Vec2 on_circle = arc_predicted_position(start, end, motion.end.centre, motion.radius, motion.dphi());
    if (on_circle == end) continue;
    for (int k = 0; k < 2; ++k)
      if (!dofs.is_constrained(2 * a + k)) predictor(2 * a + k) = on_circle(k) - start(k);
    ++moved;
  }
  return moved;
}

}  // namespace roller
