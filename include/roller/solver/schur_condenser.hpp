#pragma once
// Condensation of a symmetric sparse matrix A onto a set W of its variables (the contact dofs of
// the condensed interior-point formulation, contact/ipopt/ipopt_condensed.cpp), with the factors kept
// for later sets while A does not change.
//
// Why. A linear elastic strip with small kinematics (Hertz, Cattaneo) has one tangent for the
// whole run, but each increment condenses it onto another working set W, and MUMPS orders the
// Schur variables last: a new W meant a new analysis and factorisation of the whole strip (at
// 2.9e5 dofs 1.7 s of a 2.4 s Hertz step). Here A is factorised once with its Schur complement
// S_C on a superset C of the sets to come (all contact candidates), and each W in C is reduced
// from it densely: with R = C \ W,
//   S_W = S_C[W,W] - S_C[W,R] S_C[R,R]^-1 S_C[R,W]
// (block elimination: the Schur complement of a Schur complement), and the interior solve
// x_I' = A_I'I'^-1 b_I' on I' = everything outside W is MUMPS's reduction of b onto C, a dense
// solve on R, and MUMPS's expansion. The dense work is O(|C|^3), a few hundredths of a second
// for |C| ~ 1000; the factors are reused only when the matrix is bitwise the one factorised.
//
// The held factors also give A's inertia for free (Haynsworth: In(A) = In(A_II) + In(S_C)):
// the run-time monitor's check of the same matrix (driver/step_monitor.hpp).
//
// The factorisation: MUMPS, or for matrices of at most kSimplicialSchurMaxDofs rows Eigen's
// simplicial LDL^T (solver/simplicial_schur.hpp: no per-call fixed cost) while A_II is positive
// definite; the first A_II that is not sends this condenser to MUMPS for good.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Cholesky>

#include "roller/core/types.hpp"
#include "roller/solver/inertia.hpp"
#include "roller/solver/linear_solver_options.hpp"
#include "roller/solver/mumps_factorization.hpp"
#include "roller/solver/simplicial_schur.hpp"

namespace roller {

class SchurCondenser {
 public:
  enum class Outcome {
    Failed,      // A_II does not factorise (singular: message() says why)
    Factorised,  // A was factorised (with its Schur complement on the superset)
    Reused,      // the held factors were A's and covered the set: no factorisation
  };
  explicit SchurCondenser(const LinearSolverOptions& options = {});

  // The Schur complement of `a` on `set` (distinct variables; S in the order of `set`). When the
  // factors held are not those of `a`, or their superset does not contain `set`, `a` is
  // factorised with its Schur complement on `superset` (which must contain `set`). A set's block
  // S_C[R,R] that is not positive definite (an indefinite A) falls back to factorising on `set`.
  Outcome condense(const SparseMatrix& a, const std::vector<Index>& set, const std::vector<Index>& superset,
                   MatX* schur);
  // After condense: x = A_I'I'^-1 b on the variables outside the last set, 0 on the set.
  VecX solve_interior(const VecX& b);
  // The inertia of `a` when the factors held are exactly its own (nullopt otherwise).
  std::optional<Inertia> inertia_of(const SparseMatrix& a);
  // Frees the factors (their memory is the strip's factorisation).
  void release();
  const std::string& message() const { return solver_ ? solver_->message() : message_; }

 private:
  bool factorise(const SparseMatrix& a, const std::vector<Index>& superset);
  bool reduce_to(const std::vector<Index>& set, MatX* schur);
  bool holds_factors_of(const SparseMatrix& a) const;
  VecX solve_with_schur(const VecX& b, const std::function<VecX(const VecX&)>& schur_solve);

  LinearSolverOptions options_;
  std::optional<MumpsSolver> solver_;
  std::optional<SimplicialSchur> simplicial_;  // the factors held, when they are Eigen's
  bool simplicial_refused_ = false;            // an A_II it could not factorise: MUMPS from then on
  std::vector<Index> superset_;                // the Schur variables of the held factors
  MatX schur_superset_;                        // S_C
  Real matrix_norm_ = 0.0;                     // max |a_ij| of the held matrix (the null-pivot scale)
  // The last set: its positions in superset_ and the other positions R with S_C[R,R]'s factors.
  std::vector<Index> in_set_, rest_;
  Eigen::LLT<MatX> rest_factors_;
  std::string message_;
};

}  // namespace roller
