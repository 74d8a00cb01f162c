#pragma once
// Which material each element of the strip is made of (docs/model.md, Layered strips and
// hardness profiles): a table of the distinct materials and one index per element, so that a
// strip of 1e5+ elements with a depth profile holds a few hundred MaterialParams (one per row of
// elements) and 4 bytes per element. A homogeneous strip is a table of one.
#include <cstdint>
#include <vector>

#include "roller/material/layered_material.hpp"
#include "roller/mesh/mesh.hpp"

namespace roller {

struct ElementMaterials {
  std::vector<MaterialParams> table;  // distinct materials
  std::vector<int> layer;             // of each table entry: its band (LayeredMaterial::at_depth)
  std::vector<std::uint32_t> index;   // of each element: its entry in `table`

  const MaterialParams& of(Index e) const { return table[index[e]]; }
  int layer_of(Index e) const { return layer[index[e]]; }
  bool any_plastic() const;
  // The most back-stresses any material carries (the state files and VTU hold that many per point).
  int max_back_stresses() const;
  // Whether any material has Armstrong-Frederick recovery (no incremental potential).
  bool any_recovery() const;
};

// The same strip made linear elastic: every material's plasticity switched off (the elastic
// solutions and stiffness of the steady solves: shakedown-limit, the stationary pass).
ElementMaterials linear_elastic(ElementMaterials materials);

// Every element made of `m`.
ElementMaterials uniform_materials(const MaterialParams& m, Index n_elements);

// Each element takes the band of its centroid's depth, measured from the top of the initial mesh
// (the largest y of its nodes), and the yield profile at that depth. A uniform LayeredMaterial
// gives uniform_materials.
ElementMaterials assign_materials(const Mesh& mesh, const LayeredMaterial& layered);

// Depth of element e's centroid (the mean of its nodes) below `top` in the initial mesh.
Real centroid_depth(const Mesh& mesh, Index e, Real top);
// The largest y of the mesh's nodes: its top surface.
Real mesh_top(const Mesh& mesh);

}  // namespace roller
