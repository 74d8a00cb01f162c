#pragma once
// The smallest ball enclosing a set of points in three dimensions: Welzl's incremental algorithm
// (E. Welzl, "Smallest enclosing disks (balls and ellipsoids)", LNCS 555, 1991; B. Gärtner,
// "Fast and robust smallest enclosing balls", ESA 1999), exact up to round-off. Dang Van's
// criterion takes the centre of a deviatoric stress path from it (analysis/fatigue.hpp).
#include <vector>

#include "roller/core/types.hpp"

namespace roller {

struct Ball {
  Vec3 centre = Vec3::Zero();
  Real radius = 0.0;
  bool contains(const Vec3& p, Real tolerance) const { return (p - centre).norm() <= radius + tolerance; }
};

// The smallest ball holding every point (a ball of radius 0 at the origin for none). The points
// are visited in a fixed pseudo-random order, so the answer is reproducible.
Ball smallest_enclosing_ball(const std::vector<Vec3>& points);

}  // namespace roller
