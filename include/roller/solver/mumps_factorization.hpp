#pragma once
// Sparse direct solver MUMPS (sequential, the library Ipopt uses; multifrontal, BLAS-3): the
// linear solver of the Newton iterations (penalty backend, contact-free scenes) and the
// reference "one sparse factorisation of K_eff" of the scaling study. Eigen's SimplicialLDLT,
// used before, is not supernodal: 4.8 s at 1e5 and 165 s at 1e6 dofs against MUMPS's 0.9 s and
// ~10 s (docs/benchmarks.md).
//   Symmetric: LDL^T with pivoting (indefinite matrices factorise; only the lower triangle is
//              read), inertia from the negative pivots.
//   General:   LU (the unsymmetric tangent of Coulomb friction).
// The symbolic analysis is kept while the sparsity pattern stays the same (Newton iterations).
#include <memory>
#include <string>

#include "roller/core/types.hpp"

namespace roller {

class MumpsSolver {
 public:
  enum class Symmetry { Symmetric, General };
  explicit MumpsSolver(Symmetry symmetry = Symmetry::Symmetric);
  ~MumpsSolver();
  MumpsSolver(const MumpsSolver&) = delete;
  MumpsSolver& operator=(const MumpsSolver&) = delete;

  // Numerical factorisation of `a` (analysis first when its pattern is new). Returns false when
  // MUMPS fails (numerically singular, out of memory); message() says why.
  bool factorize(const SparseMatrix& a);
  VecX solve(const VecX& b);
  Index negative_pivots() const;  // Symmetric: negative eigenvalues of the last matrix
  const std::string& message() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace roller
