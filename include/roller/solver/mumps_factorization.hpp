#pragma once
// Sparse direct factorisation of a symmetric matrix by MUMPS (sequential, the same library Ipopt
// uses): LDL^T with pivoting, so indefinite matrices factorise too and the inertia is known
// (INFOG(12) = negative pivots). It is the reference "one sparse factorisation of K_eff" of the
// scaling benchmark, and the supernodal replacement for Eigen's SimplicialLDLT (4.8 s at 1e5
// and 165 s at 1e6 dofs, docs/benchmarks.md).
#include <memory>

#include "roller/core/types.hpp"

namespace roller {

class MumpsLdlt {
 public:
  MumpsLdlt();
  ~MumpsLdlt();
  MumpsLdlt(const MumpsLdlt&) = delete;
  MumpsLdlt& operator=(const MumpsLdlt&) = delete;

  // Analysis and numerical factorisation of the symmetric matrix `a` (full or lower storage;
  // only the lower triangle is read). Returns false when MUMPS fails (singular, out of memory);
  // message() says why.
  bool factorize(const SparseMatrix& a);
  VecX solve(const VecX& b);
  Index negative_pivots() const;  // of the last factorisation
  const std::string& message() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace roller
