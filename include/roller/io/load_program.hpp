#pragma once
// The scene's displacement and load conditions resolved against the mesh: which dofs are
// prescribed, and the prescribed total displacements and external forces at any (fractional)
// step. Fractional steps serve sub-increments after a step cut.
#include <vector>

#include "roller/assembly/dof_map.hpp"
#include "roller/io/scene.hpp"
#include "roller/mesh/mesh.hpp"

namespace roller {

class LoadProgram {
 public:
  // Throws InputError naming the block ("displacement[1].nodes") for unresolvable selectors and
  // for a dof prescribed twice with different values. On a periodic strip a node of the right edge
  // is its left edge's node (node_masters): it takes that node's prescribed displacement, and one
  // prescribed there alone, or differently, is an InputError.
  LoadProgram(const Scene& scene, const Mesh& mesh);

  // Dofs with a prescribed displacement (and each node's master on a periodic strip).
  DofMap dof_map() const;
  // Prescribed total displacement of each constrained dof at step s (s = 2.5: halfway through
  // step 3), entries of free dofs are 0.
  VecX prescribed_displacement(Real s) const;
  // External nodal forces at step s.
  VecX external_force(Real s) const;

 private:
  struct Entry {
    Index dof;
    Ramp ramp;
  };
  static Real ramp_value(const Ramp& r, Real s);
  Index n_dofs_;
  std::vector<Index> masters_;  // per node (node_masters); empty when the strip is not periodic
  std::vector<Entry> prescribed_;
  std::vector<Entry> forces_;
};

}  // namespace roller
