#pragma once
// The strip seen from a roller that rolls steadily along it (docs/model.md, "Stationary pass";
// Dang Van & Maitournam, J. Mech. Phys. Solids 41 (1993)): the mesh stays under the roller and the
// material flows through it, so a point's state is the constitutive law integrated along its
// streamline from upstream: the same integration point of every element in a row (a lane), so
// that its strains follow the field as one material point's do when the roller moves by one
// element (docs/model.md, "Streamlines"). Small kinematics.
//
// Three pieces, each pure: the strains of a displacement at every integration point; the sweep of
// the material along every streamline from the upstream states; the nodal forces of the states.
// The strains are linear in the displacement (small strain): a sparse matrix B, assembled once from
// the element kernel's strains of unit displacements, gives them, and its transpose the nodal
// forces sum w B^T sigma (the element loop took three times as long; docs/benchmarks-log.md).
#include <vector>

#include <Eigen/SparseCore>

#include "roller/assembly/element_materials.hpp"
#include "roller/fem/element_kernel.hpp"
#include "roller/material/j2_plasticity.hpp"
#include "roller/material/material_state.hpp"
#include "roller/mesh/mesh.hpp"

namespace roller {

// One lane: the integration point q of every element of a row, in the order the material meets them.
struct Streamline {
  Real y = 0.0;               // of its points in the mesh [mm]
  std::vector<Index> points;  // flat indices e * points_per_element + q, upstream first
};

// What one sweep gave besides the states.
struct SweepReport {
  Index n_yielded = 0;  // points that yield on their way
};

// A step between two points of a lane along which the material yields is walked in this many equal
// parts of the straight strain path by default (passes.stationary_path_parts): at a/h = 20 the
// plastic increments of two passes moved by 3-5 % from 1 to 4 parts and by 1-1.5 % from 4 to 16
// (docs/validation.md, "Streamlines as lanes"). One part is the transient's return mapping a step.
constexpr int kDefaultPathParts = 16;

// One step of a lane: the return mapping of the strain `step` from the state `before`, and where the
// material yields, the straight strain path walked in `parts` equal parts instead (the step's trial
// state; its other fields are the whole step's).
MaterialUpdate lane_step(const MaterialParams& m, const Vec4& step, const MaterialState& before, int parts);

class StationaryStrip {
 public:
  // `travel`: +1 when the roller moves towards +x over the strip (the material then flows towards
  // -x under it), -1 the other way. Throws InputError when the points do not form straight rows
  // (a T3 mesh with alternating diagonals). `phases`: the mesh is that many equal copies of a strip,
  // moved along x by fractions of an element (assembly/phased_strip.hpp); the lanes interleave
  // their points and each copy has its two ends. `path_parts`: lane_step's.
  StationaryStrip(const Mesh& mesh, const ElementMaterials& materials, const ElementOptions& options, Real travel,
                  int phases = 1, int path_parts = kDefaultPathParts);

  const std::vector<Streamline>& streamlines() const { return streamlines_; }
  Index n_points() const { return static_cast<Index>(geometry_.size()) * points_per_element_; }
  int points_per_element() const { return points_per_element_; }
  int path_parts() const { return path_parts_; }
  const Vec2& point_position(Index p) const { return positions_[p]; }

  // B: the points' strains of u, four rows a point ([xx, yy, zz, 2xy]), a column a dof (all dofs).
  using StrainOperator = Eigen::SparseMatrix<Real, Eigen::RowMajor, int>;
  const StrainOperator& strain_operator() const { return strain_operator_; }
  Real weight(Index p) const { return geometry_[p / points_per_element_][p % points_per_element_].weight; }
  const MaterialParams& material(Index p) const { return materials_.of(p / points_per_element_); }

  // The strain of the displacement u (all dofs, from the upstream configuration) at every point.
  std::vector<Vec4> strains(const VecX& u) const;
  // The same at a few points only (in their order).
  std::vector<Vec4> strains(const VecX& u, const std::vector<Index>& points) const;
  // Each streamline's states from its upstream state (one per streamline, in streamlines()' order):
  // the return mapping from point to point with the strain between them, in equal parts along the
  // straight strain path where the material yields.
  std::vector<MaterialState> sweep(const std::vector<Vec4>& strains, const std::vector<MaterialState>& upstream,
                                   SweepReport* report = nullptr) const;
  // Nodal forces sum w B^T sigma of the states' stresses (all dofs).
  VecX forces(const std::vector<MaterialState>& states) const;
  // The states of a strip in which every streamline holds its upstream state.
  std::vector<MaterialState> spread(const std::vector<MaterialState>& upstream) const;

  // The displacement (all dofs) of a strip uniform along x on a base held at u = 0 whose
  // streamlines carry the strains `strains` (one per streamline, [xx, yy, zz, 2xy]; xx and zz
  // must vanish, as a long track's do): u depends on y alone, du_x/dy = 2 eps_xy and du_y/dy =
  // eps_yy, each row of elements taking the mean of its streamlines' strains.
  VecX uniform_displacement(const std::vector<Vec4>& strains) const;

  // The mesh's two cut ends: where the material enters and where it leaves.
  enum class End { Upstream, Downstream };
  // The nodal forces (all dofs) with which the strip beyond one cut end holds the mesh when every
  // streamline holds `states` there (one per streamline): the forces of those states at that
  // end's nodes. Inside the mesh a state uniform along x, with no sigma_yy and sigma_xy, exerts
  // none, so forces(spread(states)) is the sum of both ends'.
  VecX end_forces(const std::vector<MaterialState>& states, End end) const;
  // The x of that end's nodes [mm] (the first copy's).
  Real end_x(End end) const { return end_x_[end == End::Upstream ? 0 : 1]; }
  // Each streamline's virgin state (initial_state of its material).
  std::vector<MaterialState> virgin_upstream() const;

 private:
  void assemble_strain_operator();

  const Mesh& mesh_;
  const ElementMaterials& materials_;
  ElementOptions options_;
  int path_parts_;
  int points_per_element_;
  std::vector<std::vector<PointGeometry>> geometry_;  // per element, in the initial mesh
  std::vector<Vec2> positions_;                       // per point
  std::vector<Streamline> streamlines_;
  std::vector<Index> streamline_of_;    // per point
  Real end_x_[2] = {0.0, 0.0};          // per End (Upstream, Downstream)
  std::vector<Index> end_elements_[2];  // per End: the elements with a node on it
  std::vector<Index> end_nodes_[2];     // per End: its nodes
  StrainOperator strain_operator_;      // B, 4 n_points x n_dofs: the points' strains of u
};

}  // namespace roller
