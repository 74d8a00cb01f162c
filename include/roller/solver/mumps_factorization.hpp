#pragma once
// Sparse direct solver MUMPS (sequential, the library Ipopt uses; multifrontal, BLAS-3): the
// linear solver of the Newton iterations (penalty backend, contact-free scenes) and the
// reference "one sparse factorisation of K_eff" of the scaling study. Eigen's SimplicialLDLT,
// used before, is not supernodal and far slower on large strips (docs/benchmarks.md, "Assembly
// throughput and one sparse factorisation").
//   Symmetric: LDL^T with pivoting (indefinite matrices factorise; only the lower triangle is
//              read), inertia from the negative pivots.
//   General:   LU (the unsymmetric tangent of Coulomb friction).
// The symbolic analysis is kept while the sparsity pattern stays the same (Newton iterations).
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "roller/core/types.hpp"
#include "roller/solver/linear_solver_options.hpp"

namespace roller {

class MumpsSolver {
 public:
  enum class Symmetry { Symmetric, General };
  explicit MumpsSolver(Symmetry symmetry = Symmetry::Symmetric, const LinearSolverOptions& options = {});
  ~MumpsSolver();
  MumpsSolver(const MumpsSolver&) = delete;
  MumpsSolver& operator=(const MumpsSolver&) = delete;

  // Numerical factorisation of `a` (analysis first when its pattern is new). Returns false when
  // MUMPS fails (numerically singular, out of memory); message() says why.
  bool factorize(const SparseMatrix& a);
  VecX solve(const VecX& b);
  // Partial factorisation that eliminates every variable except `schur` (0-based, distinct) and
  // returns their dense Schur complement S = A_ss - A_si A_ii^-1 A_is (both triangles filled):
  // the condensation of the strip onto its contact dofs (contact/ipopt/ipopt_condensed.cpp). The
  // analysis is kept while the pattern and the Schur list stay the same.
  bool factorize_with_schur(const SparseMatrix& a, const std::vector<Index>& schur, MatX* s);
  // After factorize_with_schur: x_i = A_ii^-1 b_i on the eliminated variables, x_s = 0.
  VecX solve_interior(const VecX& b);
  // After factorize_with_schur: the solution of A x = b for a caller who solves the Schur system
  // itself. MUMPS reduces b onto the Schur variables (r = b_s - A_si A_ii^-1 b_i, in the order
  // of the Schur list), `schur_solve` returns their values x_s (any: the caller may fix some),
  // and MUMPS expands: x_i = A_ii^-1 (b_i - A_is x_s). One forward and one backward solve.
  VecX solve_with_schur(const VecX& b, const std::function<VecX(const VecX&)>& schur_solve);
  // Whether the factors held are those of exactly `a` (pattern and values) with this Schur list:
  // then factorising `a` again would compute the same factors. O(nnz), no copy.
  bool holds_factors_of(const SparseMatrix& a, const std::vector<Index>& schur) const;
  // From the next factorisation on, pivots below relative_threshold * ||A|| count as null (and
  // the factorisation goes on past them) instead of failing as singular or passing unnoticed.
  void detect_null_pivots(Real relative_threshold);
  // From the next factorisation on, the factors are discarded as they are computed (ICNTL(31) = 1):
  // the inertia (negative_pivots, null_pivots) without the factors' memory, and no solves.
  void discard_factors();
  Index negative_pivots() const;  // Symmetric: negative eigenvalues of the last matrix (null ones excluded)
  Index null_pivots() const;      // with detect_null_pivots: the null pivots of the last factorisation
  Index memory_mb() const;        // memory MUMPS allocated for the last factorisation (INFOG(19), MB)
  int workspace_percent() const;  // ICNTL(14) now: the option's start, doubled per workspace overrun
  const std::string& message() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace roller
