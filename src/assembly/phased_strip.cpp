#include "roller/assembly/phased_strip.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "roller/core/error.hpp"

namespace roller {

PhasedStrip phased_strip(const Mesh& mesh, const ElementMaterials& materials, const DofMap& dofs, int phases,
                         Real shift) {
  if (phases < 1) throw InputError(fmt::format("the stationary pass's phases must be at least 1, not {}", phases));
  if (mesh.period != 0.0 || dofs.has_masters())
    throw InputError("the stationary pass needs a strip with two ends, not a periodic one");
  PhasedStrip out;
  out.phases = phases;
  out.shift = shift;
  out.base_nodes = mesh.n_nodes();
  out.base_elements = mesh.n_elements();
  out.mesh.element_type = mesh.element_type;
  std::vector<bool> constrained;
  for (int k = 0; k < phases; ++k) {
    const Index offset = k * mesh.n_nodes();
    for (const Vec2& x : mesh.nodes) out.mesh.nodes.emplace_back(x.x() + k * shift, x.y());
    for (auto element : mesh.elements) {
      for (Index& a : element) a += offset;
      out.mesh.elements.push_back(std::move(element));
    }
    for (const auto& [name, set] : mesh.node_sets)
      for (const Index a : set) out.mesh.node_sets[name].push_back(a + offset);
    out.materials.index.insert(out.materials.index.end(), materials.index.begin(), materials.index.end());
    for (Index d = 0; d < mesh.n_dofs(); ++d) constrained.push_back(dofs.is_constrained(d));
  }
  out.materials.table = materials.table;
  out.materials.layer = materials.layer;
  out.dofs = DofMap(constrained);
  return out;
}

Real contact_element_length(const Mesh& mesh, Real centre) {
  std::vector<Real> xs;
  for (const Index a : mesh.node_set("contact")) xs.push_back(mesh.nodes[a].x());
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  ROLLER_ASSERT(xs.size() >= 2, "a contact surface of two nodes at least");
  auto above = std::upper_bound(xs.begin(), xs.end(), centre);
  if (above == xs.end()) --above;
  if (above == xs.begin()) ++above;
  return *above - *(above - 1);
}

}  // namespace roller
