#include "roller/io/contact_settings.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "roller/analysis/hertz.hpp"
#include "roller/io/scene_strip.hpp"

namespace roller {

RimArc elastic_rim_arc(const Scene& scene, const Mesh& mesh) {
  const RollerSpec& r = *scene.roller;
  std::vector<Real> xs;
  for (Index a : contact_candidate_nodes(scene, mesh)) xs.push_back(mesh.nodes[a].x());
  std::sort(xs.begin(), xs.end());
  Real spacing = std::numeric_limits<Real>::infinity();
  for (std::size_t i = 1; i < xs.size(); ++i)
    if (xs[i] - xs[i - 1] > 1e-9 * scene.mesh.length) spacing = std::min(spacing, xs[i] - xs[i - 1]);
  if (!std::isfinite(spacing)) spacing = scene.mesh.length / std::max(scene.mesh.nx, 1);
  Real largest_fy = 0.0, depth = 0.0, down = 0.0;
  for (const PathSegment& seg : r.path) {
    if (seg.fy) largest_fy = std::max(largest_fy, *seg.fy);
    down += seg.dy;
    depth = std::max(depth, -down);
  }
  const Real half_width =
      std::max(largest_fy > 0.0 ? hertz_line_contact(largest_fy, r.radius, scene.contact_modulus()).half_width : 0.0,
               std::sqrt(2.0 * r.radius * depth));
  RimArc arc;
  arc.spacing = spacing;
  arc.half_length = std::min(std::max(4.0 * half_width, 10.0 * spacing), 0.45 * M_PI * r.radius);
  return arc;
}

ContactSessionSettings contact_session_settings(const Scene& scene, const Mesh& mesh) {
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
  s.rim = elastic_rim(scene, mesh);
  return s;
}

ElasticRollerSpec elastic_roller_spec(const Scene& scene) {
  const RollerSpec& r = *scene.roller;
  return {r.radius, r.inner_radius, r.youngs_modulus, r.poisson_ratio};
}

std::shared_ptr<const RimStiffness> elastic_rim(const Scene& scene, const Mesh& mesh) {
  if (!scene.roller || !scene.roller->elastic()) return nullptr;
  return std::make_shared<const RimStiffness>(
      condensed_rim_stiffness(elastic_roller_spec(scene), elastic_rim_arc(scene, mesh)));
}

}  // namespace roller
