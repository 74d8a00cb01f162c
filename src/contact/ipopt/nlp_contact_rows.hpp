#pragma once
// The contact part of an increment's nonlinear program, shared by both formulations of the
// interior-point backend (ipopt_full.cpp: every free dof a variable; ipopt_condensed.cpp: the
// contact dofs of a condensed strip). Each formulation says, per contact candidate, where the
// node's free components sit among its primal variables d and what the node's increment is when
// they are zero (RowMap); everything else — gap and slip rows, friction terms, their derivatives,
// start values and reading the solution — is written once here. Model: docs/model.md, "Contact
// kinematics" and "Friction".
//
// Variables  z = [d, s+, s-]: d the formulation's primal variables, and for the "split" friction
//            one pair s+_j, s-_j >= 0 per friction row j.
// Node       u_k(d) = base_k + sum_a d[slot_k(a)] e_a - d[w] e_y   (a = x, y; slot -1: not a
//            variable; d[w]: the suspended roller's vertical step, when the formulation has one
//            (IncrementProblem::free_roller): moving the roller up is moving every node down
//            relative to it)
// Rows       gap  g_k = |x_k^n + u_k - c| - R >= 0                       (one per RowMap)
//            slip slip_j(d) - s+_j + s-_j = 0                              ("split" only)
// Friction   sum_j w_j (s+_j + s-_j)  ("split")  or  sum_j w_j sqrt(slip_j^2 + eps^2)
//            ("regularized"), w_j = mu Fbar_j.
// Forces     Ipopt's Lagrangian is f + lambda.g: F_N = -lambda_gap, F_T = -lambda_slip (split)
//            or -w slip / sqrt(slip^2 + eps^2) (regularized).
#include <array>
#include <vector>

#include "roller/contact/contact_options.hpp"
#include "roller/contact/increment_problem.hpp"

namespace roller::ipopt_detail {

// One candidate as seen by an NLP (a "row": its gap constraint).
struct RowMap {
  int candidate = -1;               // index into IncrementProblem::candidates()
  std::array<int, 2> slot{-1, -1};  // primal variable of the node's x / y increment, -1: none
  Vec2 base = Vec2::Zero();         // the node's increment when its primal variables are zero
};

// The friction terms of one fixed-point pass.
struct FrictionTerms {
  std::vector<int> rows;     // rows carrying friction
  std::vector<Real> weight;  // mu Fbar per friction row
  IpoptFriction law = IpoptFriction::Split;
  Real eps = 1e-8;  // regularisation [mm] (regularized law)
  bool split() const { return law == IpoptFriction::Split; }
};

// Rows with a friction term: those whose normal-force estimate fbar (per candidate) exceeds
// force_tol (a zero-cost slack pair would be unbounded under the barrier).
FrictionTerms friction_terms(const std::vector<RowMap>& rows, const std::vector<Real>& fbar, Real mu, Real force_tol,
                             const IpoptOptions& o);

// Forces of a solved NLP, per row.
struct RowForces {
  std::vector<Real> normal;      // F_N per row
  std::vector<Real> tangential;  // F_T per row (0 without friction)
};

class ContactRows {
 public:
  // roller_slot: the primal variable of the suspended roller's step, -1: the roller is given;
  // rim_slot: the first of an elastic roller's rim displacements, -1: the roller is rigid (each
  // row's gap and slip are affine in them: constant Jacobian entries, no curvature).
  ContactRows(const IncrementProblem& problem, std::vector<RowMap> rows, FrictionTerms friction, int n_primal,
              int roller_slot = -1, int rim_slot = -1);

  const std::vector<RowMap>& rows() const { return rows_; }
  const FrictionTerms& friction() const { return friction_; }
  int n_primal() const { return n_primal_; }
  int n_variables() const { return n_primal_ + 2 * n_slack_; }
  int n_constraints() const { return static_cast<int>(rows_.size()) + n_slack_; }
  int jacobian_nnz() const;

  // Bounds of the slack variables and of all rows (the primal ones are free).
  void bounds(Real* z_lower, Real* z_upper, Real* g_lower, Real* g_upper) const;
  // Start values: slacks from the slip at z's primal part; bound multipliers of the slacks from
  // stationarity (z+ = w + F_T, z- = w - F_T); row multipliers from forces per row.
  void start_slacks(Real* z) const;
  void start_bound_multipliers(const RowForces& guess, Real* z_lower, Real* z_upper) const;
  void start_multipliers(const RowForces& guess, Real* lambda) const;

  Real friction_energy(const Real* z) const;
  // Sets the slacks' gradient, adds the regularized friction's gradient to the primal part.
  void add_friction_gradient(const Real* z, Real* gradient) const;
  void constraints(const Real* z, Real* g) const;
  void jacobian_structure(int* row, int* col) const;
  void jacobian_values(const Real* z, Real* values) const;

  // Curvature of the gap (lambda (I - n n^T) / rho) and of the regularized friction, as lower-
  // triangle entries (r >= c) of the primal block, in a fixed order.
  int hessian_nnz() const { return static_cast<int>(hessian_entries_.size()); }
  void hessian_structure(int* row, int* col) const;
  // values[position[e]] += entry e.
  void add_hessian(const Real* z, Real obj_factor, const Real* lambda, const std::vector<int>& position,
                   Real* values) const;

  RowForces forces(const Real* z, const Real* lambda) const;

 private:
  struct HessianEntry {
    int row_map, a, b;  // row, components a >= b (0: x, 1: y, 2: the roller's step)
    int r, c;           // primal indices, r >= c
  };
  int slot_of(int k, int component) const { return component == 2 ? roller_slot_ : rows_[k].slot[component]; }
  Vec2 increment(int k, const Real* z) const;
  // The rim displacements at z (the problem's own when the rim is not among the variables).
  const Real* rim(const Real* z) const { return rim_slot_ >= 0 ? z + rim_slot_ : problem_.rim_displacement().data(); }
  const RimSample& rim_sample(int k) const { return problem_.candidates()[rows_[k].candidate].rim; }
  int n_rim_entries(int k) const { return rim_slot_ >= 0 ? 2 * static_cast<int>(rim_sample(k).node.size()) : 0; }
  Real slip(int k, const Real* z) const;
  Real regularized_force(int j, const Real* z) const;  // w slip / sqrt(slip^2 + eps^2)

  const IncrementProblem& problem_;
  std::vector<RowMap> rows_;
  FrictionTerms friction_;
  int n_primal_;
  int roller_slot_;
  int rim_slot_;
  int n_slack_;
  std::vector<int> friction_of_;  // per row: friction index or -1
  std::vector<HessianEntry> hessian_entries_;
};

}  // namespace roller::ipopt_detail
