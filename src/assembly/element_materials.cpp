#include "roller/assembly/element_materials.hpp"

#include <algorithm>
#include <map>
#include <tuple>

namespace roller {

bool ElementMaterials::any_plastic() const {
  return std::any_of(table.begin(), table.end(), [](const MaterialParams& m) { return m.plastic; });
}

int ElementMaterials::max_back_stresses() const {
  int n = 0;
  for (const MaterialParams& m : table) n = std::max(n, m.n_back_stresses());
  return n;
}

bool ElementMaterials::any_recovery() const {
  return std::any_of(table.begin(), table.end(), [](const MaterialParams& m) { return !m.has_potential(); });
}

ElementMaterials uniform_materials(const MaterialParams& m, Index n_elements) {
  ElementMaterials out;
  out.table = {m};
  out.layer = {0};
  out.index.assign(static_cast<std::size_t>(n_elements), 0);
  return out;
}

Real mesh_top(const Mesh& mesh) {
  Real top = mesh.nodes.empty() ? 0.0 : mesh.nodes.front().y();
  for (const Vec2& x : mesh.nodes) top = std::max(top, x.y());
  return top;
}

ElementMaterials linear_elastic(ElementMaterials materials) {
  for (MaterialParams& p : materials.table) p.plastic = false;
  return materials;
}

Real centroid_depth(const Mesh& mesh, Index e, Real top) { return top - element_centroid(mesh, e).y(); }

ElementMaterials assign_materials(const Mesh& mesh, const LayeredMaterial& layered) {
  if (layered.is_homogeneous()) return uniform_materials(layered.base, mesh.n_elements());
  ElementMaterials out;
  out.index.resize(static_cast<std::size_t>(mesh.n_elements()));
  // Elements of one band with the same yield stress share an entry: at most one per row of
  // elements (two for T3, whose triangles' centroids differ in depth).
  std::map<std::pair<int, Real>, std::uint32_t> entry;
  const Real top = mesh_top(mesh);
  for (Index e = 0; e < mesh.n_elements(); ++e) {
    const MaterialAtDepth m = layered.at_depth(centroid_depth(mesh, e, top));
    const auto key = std::make_pair(m.layer, m.material.yield_stress);
    auto it = entry.find(key);
    if (it == entry.end()) {
      it = entry.emplace(key, static_cast<std::uint32_t>(out.table.size())).first;
      out.table.push_back(m.material);
      out.layer.push_back(m.layer);
    }
    out.index[static_cast<std::size_t>(e)] = it->second;
  }
  return out;
}

}  // namespace roller
