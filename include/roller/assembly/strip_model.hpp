#pragma once
// The deformable strip: mesh, start-of-increment configuration, committed material state per
// integration point, and assembly of the incremental energy, its gradient and Hessian over the
// whole mesh. History is committed only after an increment converges (deal.II step-18).
#include <vector>

#include "roller/assembly/dof_map.hpp"
#include "roller/assembly/element_materials.hpp"
#include "roller/fem/element_kernel.hpp"
#include "roller/mesh/mesh.hpp"

namespace roller {

// What one evaluation of the strip computed besides its gradient and Hessian.
struct StripEvaluation {
  Real energy = 0.0;    // incremental strain energy
  Index n_yielded = 0;  // integration points that yield in this increment
};

// Whether a strip's tangent cannot change with the state: no initial-stress term, no plastic
// branch, a mesh that never moves (a linear elastic strip with small kinematics). K is then the
// same matrix at every increment, which the condensed contact solve keeps factorised for the run
// and the run-time monitor checks once.
inline bool tangent_is_constant(Kinematics kinematics, bool any_plastic) {
  return kinematics == Kinematics::Small && !any_plastic;
}

class StripModel {
 public:
  // A homogeneous strip of `material`.
  StripModel(Mesh mesh, MaterialParams material, ElementOptions options);
  // A strip whose elements have their own materials (layers, a yield profile: assign_materials).
  StripModel(Mesh mesh, ElementMaterials materials, ElementOptions options);
  StripModel(const StripModel&) = delete;
  StripModel& operator=(const StripModel&) = delete;

  const Mesh& mesh() const { return mesh_; }
  // The material of element e, and the table of them all (one entry for a homogeneous strip).
  const MaterialParams& material(Index e) const { return materials_.of(e); }
  const ElementMaterials& materials() const { return materials_; }
  const ElementOptions& options() const { return options_; }
  Index n_dofs() const { return mesh_.n_dofs(); }
  // Whether the tangent cannot change with the state (tangent_is_constant below).
  bool tangent_is_constant() const {
    return roller::tangent_is_constant(options_.kinematics, materials_.any_plastic());
  }

  // Selects the free dofs and builds the sparsity pattern of the Hessian over them. Call again
  // whenever the set of constrained dofs changes.
  void set_dof_map(DofMap dofs);
  const DofMap& dof_map() const { return dofs_; }

  // Incremental strain energy of the increment `u` (all dofs; constrained entries hold their
  // prescribed increments). Optionally the gradient over all dofs (internal forces, including
  // reactions at constrained dofs) and the Hessian over the free dofs (full symmetric storage,
  // fixed pattern). Throws NumericalError on inverted elements or failed material updates.
  StripEvaluation evaluate(const VecX& u, VecX* gradient, SparseMatrix* hessian_free);

  // Accepts the converged increment: material states become the trial states at `u` (stress
  // pushed forward for finite kinematics), the total displacement grows by u, and for finite
  // kinematics the reference configuration moves to the new one. Throws NumericalError (and
  // changes nothing) when an element would be inverted in the new configuration. Returns the
  // number of integration points that yielded in the committed increment.
  Index commit(const VecX& u);

  // Replaces the committed state by one saved earlier (state files): start-of-increment
  // coordinates, total displacement and the integration-point states. Throws InputError when the
  // sizes do not fit this mesh, NumericalError when an element is inverted.
  void restore(std::vector<Vec2> reference, VecX total_displacement, std::vector<MaterialState> states);

  // Nodal forces (all dofs; empty: none) that do not follow the increment: the energy of an
  // increment u gains -load.u and its gradient -load. The stationary pass's contact correction
  // carries its residual with them (steady/roller_contact_correction.cpp).
  void set_dead_load(VecX load) { dead_load_ = std::move(load); }

  // Armstrong-Frederick's recovery for the minimisers (docs/model.md, Hardening laws): whether the
  // law has a recovery term (no incremental potential), and evaluate() with each point's recovery
  // frozen at the given plastic multipliers (one per integration point; empty: the exact update).
  bool has_recovery() const { return materials_.any_recovery(); }
  void freeze_recovery(std::vector<Real> multipliers);
  // Each integration point's plastic multiplier (trial minus committed eq_plastic_strain) of the
  // increment u, with the recovery as it is frozen now.
  std::vector<Real> plastic_multipliers(const VecX& u);

  // Start-of-increment coordinates of each node (the reference of the next increment).
  const std::vector<Vec2>& reference_coordinates() const { return reference_; }
  // Current coordinates X0 + total displacement (equal to reference_coordinates() for finite
  // kinematics; for small kinematics the mesh never moves but the contact sees these).
  std::vector<Vec2> current_coordinates() const;
  const VecX& total_displacement() const { return total_displacement_; }

  int points_per_element() const { return n_points_; }
  // Committed state of integration point q of element e.
  const MaterialState& state(Index e, int q) const { return committed_[e * n_points_ + q]; }
  const std::vector<MaterialState>& states() const { return committed_; }

  // Total Green-Lagrange strain [xx, yy, zz, 2xy] of each integration point of element e with
  // respect to the initial mesh (linearised for small kinematics), from the total displacement.
  std::vector<Vec4> total_strain(Index e) const;
  // Green-Lagrange strain [xx, yy, zz, 2xy] of the committed increment `du` (all dofs) at each
  // integration point of element e, with respect to the configuration before it: the thesis's
  // updated-Lagrangian strain of one step. Finite kinematics: E = (H + H^T + H^T H)/2 with
  // H = d(du)/dX over the start-of-increment configuration (reference - du); small: the
  // linearised strain over the initial mesh, so that it is the difference of two total_strain().
  std::vector<Vec4> increment_strain(Index e, const VecX& du) const;

  // Mass matrix over all dofs (rho from each element's material); lumped = diagonal row-sum lumping.
  SparseMatrix mass_matrix(bool lumped) const;

  // Volume (per unit width) of the strip in the start-of-increment configuration.
  Real volume() const;

 private:
  // Integration-point geometry of element e in the given configuration, recomputed when needed
  // rather than stored (at 1.3e6 dofs it would hold 370 MB through every factorisation).
  // Throws NumericalError naming an inverted element.
  std::vector<PointGeometry> point_geometry(Index e, const std::vector<Vec2>& coordinates) const;
  // The same into `out`, with `xe` for the element's coordinates (buffers reused over a loop).
  void point_geometry(Index e, const std::vector<Vec2>& coordinates, std::vector<Vec2>& xe,
                      std::vector<PointGeometry>& out) const;
  void check_not_inverted(const std::vector<Vec2>& coordinates) const;
  // evaluate(), and the trial states at u when `trial` is given (only commit needs them, so
  // they are not kept between evaluations).
  StripEvaluation evaluate_states(const VecX& u, VecX* gradient, SparseMatrix* hessian_free,
                                  std::vector<MaterialState>* trial);
  ElementVector element_values(Index e, const VecX& u) const;
  // Gives `h` the Hessian's sparsity (reusing it when it already has it) with zero values.
  void zero_hessian(SparseMatrix& h) const;

  Mesh mesh_;
  ElementMaterials materials_;
  ElementOptions options_;
  int n_points_;
  std::vector<Vec2> reference_;
  VecX total_displacement_;
  std::vector<MaterialState> committed_;
  std::vector<Real> frozen_recovery_;  // per integration point, or empty (freeze_recovery)
  VecX dead_load_;                     // all dofs, or empty (set_dead_load)

  DofMap dofs_;
  // Sparsity of the Hessian over the free dofs (compressed columns, full symmetric storage).
  std::vector<int> outer_, inner_;
  // Value slot of the first free row of node a in column dof (c, j) of each element, or -1:
  // element e's slots start at e * m * m * 2, m = nodes per element (set_dof_map).
  std::vector<int> scatter_;
};

}  // namespace roller
