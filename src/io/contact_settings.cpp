#include "roller/io/contact_settings.hpp"

#include <algorithm>
#include <cmath>

namespace roller {

ContactSessionSettings contact_session_settings(const Scene& scene) {
  ContactSessionSettings s;
  s.roller = scene.roller.has_value();
  const MaterialParams surface = scene.strip_material().surface();  // what the roller touches
  s.surface_youngs_modulus = surface.youngs_modulus;
  s.surface_poisson_ratio = surface.poisson_ratio;
  s.contact_modulus = scene.contact_modulus();
  s.roller_coupling = scene.contact.roller_coupling;
  s.body_size = std::max(scene.mesh.length, scene.mesh.height);
  if (scene.roller)
    for (const PathSegment& seg : scene.roller->path) {
      if (const std::optional<Real> fx = segment_end_fx(seg))
        s.largest_force.x() = std::max(s.largest_force.x(), std::abs(*fx));
      if (seg.fy) s.largest_force.y() = std::max(s.largest_force.y(), *seg.fy);
    }
  return s;
}

}  // namespace roller
