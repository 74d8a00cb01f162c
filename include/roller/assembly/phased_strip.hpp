#pragma once
// The stationary pass at several places of the roller between two nodes at once (docs/model.md,
// "Phases"): P copies of the strip, copy k moved against the travel by k/P of an element, so that
// the roller, which stands still over them all, stands k/P of an element further along on copy k.
// A transient pass in steps of h/P meets P such places over and over; a material point walks
// through them in turn, so the stationary strip's lanes interleave the copies' points (by their
// places relative to the roller) and the P fields are solved together, each under its own
// contact. The copies share nothing but the lanes: the stiffness is block diagonal.
#include <vector>

#include "roller/assembly/dof_map.hpp"
#include "roller/assembly/element_materials.hpp"
#include "roller/mesh/mesh.hpp"

namespace roller {

struct PhasedStrip {
  int phases = 1;
  Real shift = 0.0;            // how far copy k is moved along x per k [mm]
  Mesh mesh;                   // the copies' union: copy k's nodes and elements in the k-th block
  ElementMaterials materials;  // per element of the union
  DofMap dofs;                 // the base's constraints in every copy
  Index base_nodes = 0, base_elements = 0;
};

// `shift`: how far copy k moves along x per phase [mm] (-travel * h / P). Throws InputError for
// a periodic mesh (a stationary strip has two ends) or phases < 1.
PhasedStrip phased_strip(const Mesh& mesh, const ElementMaterials& materials, const DofMap& dofs, int phases,
                         Real shift);

// The element length along x at x = centre among the mesh's "contact" nodes: the spacing of the
// two that bracket it.
Real contact_element_length(const Mesh& mesh, Real centre);

}  // namespace roller
