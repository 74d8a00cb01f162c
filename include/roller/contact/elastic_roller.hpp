#pragma once
// An elastic roller's stiffness condensed onto its rim where it touches the strip (docs/model.md,
// Elastic roller): a plane-strain, small-strain, linear elastic disc or ring meshed in polar Q4
// elements, held at its bore (the axle; a solid disc at a hub of a tenth of its radius), and
// statically condensed onto the rim nodes of an arc around the contact. In the roller's frame
// the contact does not move, so this is computed once a run: the superelement of the Abaqus
// rollover models' elastic wheel (docs/elastic-roller-design.md), on the contact arc only.
#include <vector>

#include "roller/core/types.hpp"
#include "roller/mesh/mesh.hpp"

namespace roller {

struct ElasticRollerSpec {
  Real radius = 0.0;        // R [mm]
  Real inner_radius = 0.0;  // the bore [mm]; 0: a solid disc
  Real youngs_modulus = 0.0;
  Real poisson_ratio = 0.0;
};

// The retained arc and the mesh's size along it.
struct RimArc {
  Real half_length = 0.0;  // the arc's half-length along the rim [mm], around the contact's direction
  Real spacing = 0.0;      // the rim nodes' spacing along it [mm] (the elements under the rim the same deep)
};

// The disc's polar mesh: nodes on rings from the bore (ring 0) to the rim, the angle measured from
// the contact's direction (straight down: the rim's lowest point at angle 0, positive towards +x),
// fine over the arc and to its length's depth, graded beyond; the centre at the origin.
struct RollerDiscMesh {
  Mesh mesh;
  std::vector<Index> bore;  // the nodes held (the innermost ring)
  std::vector<Index> arc;   // the rim nodes of the arc, by increasing angle
};
RollerDiscMesh roller_disc_mesh(const ElasticRollerSpec& roller, const RimArc& arc);

// The condensed stiffness: the rim forces f that the arc's displacements w (the roller's frame,
// x along the strip, y up; [w_x0, w_y0, w_x1, ...] by increasing angle) need with the bore held:
// f = K w. Symmetric positive definite.
struct RimStiffness {
  std::vector<Vec2> positions;  // the arc's rim nodes relative to the centre, undeformed [mm]
  MatX stiffness;               // 2n x 2n [N/mm per mm of roller length]
};
RimStiffness condensed_rim_stiffness(const ElasticRollerSpec& roller, const RimArc& arc);

}  // namespace roller
