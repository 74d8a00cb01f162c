#pragma once
// The Schur complement of a small symmetric positive definite interior block by Eigen's simplicial
// LDL^T: what MumpsSolver::factorize_with_schur and its solves do, for strips of a few hundred to
// a few thousand dofs (solver/schur_condenser.hpp picks it below kSimplicialSchurMaxDofs).
//
// Why. The condensed interior-point formulation factorises the strip once per linearisation and
// on the thesis's coarse meshes makes hundreds of them. MUMPS pays a fixed cost on every call
// (Debian's 5.5 walks its whole structure each time, docs/benchmarks.md): on Z1 at refine 1
// (321 free dofs, 24 Schur variables) a factorisation with its Schur complement and two interior
// solves took 0.53 ms with MUMPS and 0.20 ms here; at 1,182 dofs 1.5 and 0.9 ms; at ~5,000 dofs
// the two were 6 and 4 ms on Z1's mesh and 9 and 12 ms on Z3's. Hence the bound.
//
// Only a positive definite A_II is factorised here (every pivot of D above a null threshold):
// LDL^T without pivoting is stable for it; any other matrix is refused (factorize_with_schur
// returns false) and the caller falls back to MUMPS, which pivots.
#include <vector>

#include <Eigen/SparseCholesky>

#include "roller/core/types.hpp"

namespace roller {

constexpr Index kSimplicialSchurMaxDofs = 2000;

class SimplicialSchur {
 public:
  // Factorises A_II (I: every variable not in `schur`) and returns S = A_ss - A_si A_ii^-1 A_is
  // (both triangles filled, in the order of `schur`). Only the lower triangle of `a` is read.
  // False when A_II is not positive definite: a pivot of D at or below null_pivot * max |a_ij|.
  bool factorize_with_schur(const SparseMatrix& a, const std::vector<Index>& schur, Real null_pivot, MatX* s);
  // After factorize_with_schur: x_i = A_ii^-1 b_i, x_s = 0.
  VecX solve_interior(const VecX& b) const;
  // After factorize_with_schur: the solution of A x = b, the Schur system solved by the caller:
  // `schur_solve` gets r = b_s - A_si A_ii^-1 b_i and returns x_s; then x_i = A_ii^-1 (b_i - A_is x_s).
  template <class SchurSolve>
  VecX solve_with_schur(const VecX& b, const SchurSolve& schur_solve) const {
    const VecX bi = gather_interior(b);
    const VecX xs = schur_solve(VecX(gather_schur(b) - a_is_.transpose() * interior_solve(bi)));
    return scatter(interior_solve(bi - a_is_ * xs), xs);
  }
  // Whether the factors held are those of exactly `a` (pattern and values) with this Schur list.
  bool holds_factors_of(const SparseMatrix& a, const std::vector<Index>& schur) const;

 private:
  VecX gather_interior(const VecX& b) const;
  VecX gather_schur(const VecX& b) const;
  VecX interior_solve(const VecX& bi) const { return ldlt_.solve(bi); }
  VecX scatter(const VecX& xi, const VecX& xs) const;

  bool factorised_ = false;
  SparseMatrix held_;                    // the lower triangle of the matrix factorised
  std::vector<Index> schur_, interior_;  // variables, in order
  SparseMatrix a_is_;                    // A_is (interior rows, Schur columns)
  Eigen::SimplicialLDLT<SparseMatrix> ldlt_;
  Index analysed_n_ = -1;
  std::vector<int> analysed_outer_, analysed_inner_;  // A_II's pattern at the last analysis
};

}  // namespace roller
