#include "roller/io/roller_start.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "roller/core/error.hpp"

namespace roller {

Vec2 given_start_centre(const Scene& scene) {
  return scene.roller->start_centre.value_or(Vec2(0.5 * scene.mesh.length, scene.mesh.height + scene.roller->radius));
}

Real touching_lift(const Scene& scene, const std::vector<Vec2>& x, const std::vector<Index>& candidates) {
  // The lowest centre height at the start's x for which no candidate lies inside the circle.
  const Real radius = scene.roller->radius;
  const Vec2 given = given_start_centre(scene);
  std::optional<Real> touch;
  for (Index a : candidates) {
    const Real dx = x[a].x() - given.x();
    if (std::abs(dx) >= radius) continue;
    const Real y = x[a].y() + std::sqrt(radius * radius - dx * dx);
    touch = std::max(touch.value_or(y), y);
  }
  if (!touch)
    throw InputError(
        fmt::format("{}: roller.touch_strip = true: no contact candidate lies under the roller at x = {} "
                    "(within its radius {} mm); move roller.centre over the strip",
                    scene.file.string(), given.x(), radius));
  return *touch - given.y();
}

void check_roller_starts_outside(const Scene& scene, const std::vector<Vec2>& x, const std::vector<Index>& candidates,
                                 const Vec2& centre) {
  // A roller that starts inside the strip has no admissible first increment; the solvers would
  // blame the supports or the step size instead.
  const Real radius = scene.roller->radius;
  Real depth = 0.0;
  Index deepest = -1;
  for (Index a : candidates) {
    const Real d = radius - (x[a] - centre).norm();
    if (d > depth) {
      depth = d;
      deepest = a;
    }
  }
  // A roller under the strip would press it from below, which no path of ours means.
  Real bottom = x.front().y();
  for (const Vec2& p : x) bottom = std::min(bottom, p.y());
  if (centre.y() + radius < bottom)
    throw InputError(fmt::format(
        "{}: roller.centre = [{}, {}]: the roller lies entirely below the strip (its top at y = {:.6g} mm, the "
        "strip's bottom at y = {:.6g} mm); expected a centre above the strip's top surface",
        scene.file.string(), centre.x(), centre.y(), centre.y() + radius, bottom));
  // Below 1e-6 R an overlap is the rounding of a touching start (the thesis's Z4 corner: 3e-8 R).
  if (depth > 1e-6 * radius)
    throw InputError(fmt::format(
        "{}: roller.centre = [{}, {}]: the roller starts inside the strip (node {} at ({:.6g}, {:.6g}) mm lies "
        "{:.4g} mm inside it); expected a start on or above the surface: raise the centre by at least {:.4g} mm, "
        "or press in with a [[roller.path]] segment (dy < 0)",
        scene.file.string(), centre.x(), centre.y(), deepest + 1, x[deepest].x(), x[deepest].y(), depth, depth));
}

Vec2 start_centre_on(const Scene& scene, const StripModel& strip, const std::vector<Index>& candidates) {
  Vec2 centre = given_start_centre(scene);
  // A periodic strip's nodes at their images nearest the roller, as the contact sees them
  // (docs/model.md, Periodic strip): a roller over the seam touches the left edge's nodes too.
  std::vector<Vec2> x = strip.current_coordinates();
  for (Vec2& p : x) p.x() = nearest_image_x(strip.mesh(), p.x(), centre.x());
  if (scene.roller->touch_strip) centre.y() += touching_lift(scene, x, candidates);
  check_roller_starts_outside(scene, x, candidates, centre);
  return centre;
}

}  // namespace roller
