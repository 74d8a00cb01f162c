#include "roller/solver/sparse_solver.hpp"

#include <algorithm>

namespace roller {

void SparseSolver::configure(const LinearSolverOptions& options) {
  if (options == options_) return;
  options_ = options;
  mumps_.reset();
}

bool SparseSolver::factorize(const SparseMatrix& a) {
  use_mumps_ = a.rows() >= kMumpsFromUnknowns;
  if (use_mumps_) {
    if (!mumps_) mumps_ = std::make_unique<MumpsSolver>(symmetry_, options_);
    return mumps_->factorize(a);
  }
  // Eigen: the analysis is redone when the pattern changes (the steady Jacobian's follows the
  // yielding points and may keep its size and number of entries).
  const auto* outer = a.outerIndexPtr();
  const auto* inner = a.innerIndexPtr();
  const bool same = a.isCompressed() && analysed_outer_.size() == static_cast<std::size_t>(a.outerSize() + 1) &&
                    analysed_inner_.size() == static_cast<std::size_t>(a.nonZeros()) &&
                    std::equal(analysed_outer_.begin(), analysed_outer_.end(), outer) &&
                    std::equal(analysed_inner_.begin(), analysed_inner_.end(), inner);
  if (!same) {
    analysed_outer_.assign(outer, outer + a.outerSize() + 1);
    analysed_inner_.assign(inner, inner + a.nonZeros());
  }
  if (symmetry_ == MumpsSolver::Symmetry::Symmetric) {
    if (!same) ldlt_.analyzePattern(a);
    ldlt_.factorize(a);
    return ldlt_.info() == Eigen::Success;
  }
  if (!same) lu_.analyzePattern(a);
  lu_.factorize(a);
  return lu_.info() == Eigen::Success;
}

VecX SparseSolver::solve(const VecX& b) {
  if (use_mumps_) return mumps_->solve(b);
  if (symmetry_ == MumpsSolver::Symmetry::Symmetric) return ldlt_.solve(b);
  return lu_.solve(b);
}

}  // namespace roller
