#pragma once
// A small strip for the stationary pass's tests: 8 x 2 mm of Q4 (48 x 12, B-bar, small strain)
// held at its base, its elastic stiffness over the free dofs, and an elliptic pressure of peak
// p0/k times k over |x - 4| < 1 mm on the nodes of its top.
#include <cmath>
#include <vector>

#include "strip_spec.hpp"

#include "roller/assembly/dof_map.hpp"
#include "roller/assembly/strip_model.hpp"
#include "roller/mesh/strip_mesher.hpp"

namespace roller::test {

// The strips' steel: yield stress 300 MPa, perfectly plastic (isotropic, E_T = 0) until a test
// gives it a hardening law.
inline MaterialParams plastic_steel() {
  MaterialParams m;
  m.plastic = true;
  m.yield_stress = 300.0;
  return m;
}

struct SmallStationaryStrip {
  Mesh mesh = make_strip_mesh(strip_spec(ElementType::Q4, 8.0, 2.0, 48, 12));
  ElementOptions options{Kinematics::Small, Q4Formulation::BBar};
  ElementMaterials materials;
  DofMap dofs;
  SparseMatrix elastic;  // K_e over the free dofs
  VecX load;             // all dofs

  SmallStationaryStrip(const MaterialParams& material, Real p0_over_k)
      : materials(uniform_materials(material, mesh.n_elements())) {
    std::vector<bool> held(static_cast<std::size_t>(mesh.n_dofs()), false);
    for (const Index a : mesh.node_set("bottom")) held[2 * a] = held[2 * a + 1] = true;
    dofs = DofMap(held);
    StripModel model(mesh, linear_elastic(materials), options);
    model.set_dof_map(dofs);
    model.evaluate(VecX::Zero(mesh.n_dofs()), nullptr, &elastic);
    const Real p0 = p0_over_k * material.yield_stress / std::sqrt(3.0), dx = 8.0 / 48;
    load = VecX::Zero(mesh.n_dofs());
    for (const Index n : mesh.node_set("top")) {
      const Real x = mesh.nodes[n].x() - 4.0;
      if (std::abs(x) < 1.0) load[2 * n + 1] = -p0 * std::sqrt(1.0 - x * x) * dx;
    }
  }
};

}  // namespace roller::test
