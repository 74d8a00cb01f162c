#include "roller/analysis/enclosing_ball.hpp"

#include <algorithm>
#include <array>
#include <numeric>
#include <random>

namespace roller {

namespace {

Ball ball_of(const Vec3& a, const Vec3& b) {
  const Vec3 c = 0.5 * (a + b);
  return {c, (a - c).norm()};
}

// The smallest ball of a set that holds it, among the candidates: what a degenerate boundary
// (collinear or coplanar points) falls back on.
Ball smallest_holding(const std::vector<Ball>& candidates, const std::vector<Vec3>& points, Real tolerance) {
  Ball best{Vec3::Zero(), -1.0}, largest = candidates.front();
  for (const Ball& b : candidates) {
    const bool holds =
        std::all_of(points.begin(), points.end(), [&](const Vec3& p) { return b.contains(p, tolerance); });
    if (holds && (best.radius < 0.0 || b.radius < best.radius)) best = b;
    if (b.radius > largest.radius) largest = b;
  }
  return best.radius >= 0.0 ? best : largest;  // none holds them only by round-off beyond the tolerance
}

// The smallest ball with a, b and c on its sphere: the circumcircle's, centre in their plane.
// Collinear points have none; the smallest of the pairs' balls holding all three stands in.
Ball ball_of(const Vec3& a, const Vec3& b, const Vec3& c, Real tolerance) {
  const Vec3 u = b - a, v = c - a;
  const Vec3 w = u.cross(v);
  const Real w2 = w.squaredNorm();
  if (w2 <= 1e-24 * u.squaredNorm() * v.squaredNorm())
    return smallest_holding({ball_of(a, b), ball_of(a, c), ball_of(b, c)}, {a, b, c}, tolerance);
  const Vec3 centre = a + (v.squaredNorm() * w.cross(u) + u.squaredNorm() * v.cross(w)) / (2.0 * w2);
  return {centre, (a - centre).norm()};
}

// The ball with a, b, c and d on its sphere; coplanar points have none (unless on one circle),
// and the smallest of the triples' and pairs' balls holding all four stands in.
Ball ball_of(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, Real tolerance) {
  Eigen::Matrix3d m;
  m.row(0) = (b - a).transpose();
  m.row(1) = (c - a).transpose();
  m.row(2) = (d - a).transpose();
  const Real scale = m.row(0).norm() * m.row(1).norm() * m.row(2).norm();
  if (std::abs(m.determinant()) <= 1e-12 * scale) {
    return smallest_holding({ball_of(a, b, c, tolerance), ball_of(a, b, d, tolerance), ball_of(a, c, d, tolerance),
                             ball_of(b, c, d, tolerance), ball_of(a, b), ball_of(a, c), ball_of(a, d), ball_of(b, c),
                             ball_of(b, d), ball_of(c, d)},
                            {a, b, c, d}, tolerance);
  }
  const Vec3 rhs(m.row(0).squaredNorm(), m.row(1).squaredNorm(), m.row(2).squaredNorm());
  const Vec3 centre = a + m.partialPivLu().solve(0.5 * rhs);
  return {centre, (a - centre).norm()};
}

}  // namespace

// The incremental form: a point outside the ball of those before it lies on the sphere of the
// ball of those and it; nested three deep (at most four points fix a ball in three dimensions).
Ball smallest_enclosing_ball(const std::vector<Vec3>& points) {
  if (points.empty()) return {};
  std::vector<Vec3> p = points;
  std::shuffle(p.begin(), p.end(), std::mt19937(20261202u));  // expected linear time
  Real extent = 0.0;
  for (const Vec3& x : p) extent = std::max(extent, (x - p[0]).norm());
  const Real tolerance = 1e-12 * extent;
  Ball ball{p[0], 0.0};
  for (std::size_t i = 1; i < p.size(); ++i) {
    if (ball.contains(p[i], tolerance)) continue;
    ball = {p[i], 0.0};
    for (std::size_t j = 0; j < i; ++j) {
      if (ball.contains(p[j], tolerance)) continue;
      ball = ball_of(p[i], p[j]);
      for (std::size_t k = 0; k < j; ++k) {
        if (ball.contains(p[k], tolerance)) continue;
        ball = ball_of(p[i], p[j], p[k], tolerance);
        for (std::size_t l = 0; l < k; ++l) {
          if (ball.contains(p[l], tolerance)) continue;
          ball = ball_of(p[i], p[j], p[k], p[l], tolerance);
        }
      }
    }
  }
  return ball;
}

}  // namespace roller
