#include "roller/solver/sparse_solver.hpp"

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
  // Eigen: the analysis is redone when the size or the number of entries changes.
  const bool same = a.rows() == analysed_n_ && a.nonZeros() == analysed_nnz_;
  analysed_n_ = a.rows();
  analysed_nnz_ = a.nonZeros();
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
