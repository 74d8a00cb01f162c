#pragma once
// An elastic roller's stiffness condensed onto its rim where it touches the strip (docs/model.md,
// Elastic roller): a plane-strain, small-strain, linear elastic disc or ring meshed in polar Q4
// elements, held at its bore (the axle; a solid disc at a hub of a tenth of its radius), and
// statically condensed onto the rim nodes of an arc around the contact. In the roller's frame
// the contact does not move, so this is computed once a run: the superelement of the Abaqus
// rollover models' elastic wheel (docs/elastic-roller-design.md), on the contact arc only.
#include <memory>
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
// fine over the arc and to a quarter of its half-length deep, graded beyond; the centre at the origin.
struct RollerDiscMesh {
  Mesh mesh;
  std::vector<Index> bore;  // the nodes held (the innermost ring)
  std::vector<Index> arc;   // the rim nodes of the arc, by increasing angle
};
RollerDiscMesh roller_disc_mesh(const ElasticRollerSpec& roller, const RimArc& arc);

// The disc as a plane-strain, small-strain, linear elastic body (B-bar Q4) with its bore held: the
// model whose stiffness condensed_rim_stiffness condenses, and whose fields the VTU shows.
class StripModel;
std::unique_ptr<StripModel> roller_disc_model(const ElasticRollerSpec& roller, const RollerDiscMesh& disc);

// The condensed stiffness: the rim forces f that the arc's displacements w (the roller's frame,
// x along the strip, y up; [w_x0, w_y0, w_x1, ...] by increasing angle) need with the bore held:
// f = K w. Symmetric positive definite.
struct RimStiffness {
  std::vector<Vec2> positions;   // the arc's rim nodes relative to the centre, undeformed [mm]
  MatX stiffness;                // 2n x 2n [N/mm per mm of roller length]
  Real arc_half_length() const;  // along the rim [mm]
};
RimStiffness condensed_rim_stiffness(const ElasticRollerSpec& roller, const RimArc& arc);

// Where on the rim arc a direction from the centre points: the arc nodes `segment` and
// `segment + 1` around it and its place between them, linear in the angle (measured from straight
// down, positive towards +x). Throws NumericalError when the angle lies outside the arc (the
// contact left it).
struct RimPoint {
  Index segment = -1;
  Real weight = 0.0;  // 0 at the first node, 1 at the second
};
Real rim_angle(const Vec2& from_centre);
Vec2 rim_radial(Real angle);  // the outward unit vector at that angle
RimPoint rim_point(const std::vector<Vec2>& positions, Real angle);

// The rim's displacement where a strip node touches it, as weights of the arc nodes (summing to 1):
// the rim weighted with the node's dual (biorthogonal) shape function psi = 2 - 3 |t - angle| / reach
// over its support [angle - reach, angle + reach], reach = the node's tributary length over R (the
// rim's displacement at `angle` when reach is 0). Where the rim's nodes lie on the strip's nodes it
// is their displacement itself, which the strip's nodal contact sees; a strip node's force loads
// the rim with the same weights. Wohlmuth's dual mortar (docs/model.md, Elastic roller).
struct RimWeight {
  Index node = 0;
  Real weight = 0.0;
};
std::vector<RimWeight> rim_sample(const std::vector<Vec2>& positions, Real angle, Real reach);

// The rim's compliance at points of the strip's surface, for the steady contact
// (contact/condensed_contact.hpp): point j at the angle angles[j] from the lowest point with the
// reach reaches[j] (its tributary length over R); forces f_j on the strip (the roller takes -f_j,
// spread with rim_sample's weights W) move the rim at point i, sampled with the same weights, by
// -(H f)_i, H = W^T K^-1 W (2n x 2n, x and y of each point in turn).
MatX rim_compliance(const RimStiffness& rim, const std::vector<Real>& angles, const std::vector<Real>& reaches);

}  // namespace roller
