#include "roller/solver/schur_condenser.hpp"

#include <cmath>
#include <unordered_map>

#include "roller/core/eigenvalues.hpp"

namespace roller {

namespace {
// A pivot below this fraction of max |a_ij| counts as null (analysis/monotonicity.hpp says why).
constexpr Real kNullPivot = 1e-12;
}  // namespace

SchurCondenser::SchurCondenser(const LinearSolverOptions& options) : options_(options) {}

bool SchurCondenser::factorise(const SparseMatrix& a, const std::vector<Index>& superset) {
  superset_.clear();
  if (a.rows() <= kSimplicialSchurMaxDofs && !simplicial_refused_) {
    if (!simplicial_) simplicial_.emplace();
    if (simplicial_->factorize_with_schur(a, superset, kNullPivot, &schur_superset_)) {
      superset_ = superset;
      matrix_norm_ = a.coeffs().cwiseAbs().maxCoeff();
      return true;
    }
    simplicial_refused_ = true;
  }
  simplicial_.reset();
  if (!solver_) {
    solver_.emplace(MumpsSolver::Symmetry::Symmetric, options_);
    solver_->detect_null_pivots(kNullPivot);
  }
  if (!solver_->factorize_with_schur(a, superset, &schur_superset_)) return false;
  if (solver_->null_pivots() > 0) {
    message_ = "the matrix is singular on the variables outside the Schur set";
    solver_.reset();  // its message would say nothing; the factors are of no use
    return false;
  }
  superset_ = superset;
  matrix_norm_ = a.coeffs().cwiseAbs().maxCoeff();
  return true;
}

bool SchurCondenser::reduce_to(const std::vector<Index>& set, MatX* schur) {
  std::unordered_map<Index, Index> position;
  position.reserve(superset_.size());
  for (std::size_t p = 0; p < superset_.size(); ++p) position.emplace(superset_[p], static_cast<Index>(p));
  in_set_.clear();
  std::vector<char> taken(superset_.size(), 0);
  for (const Index v : set) {
    const auto it = position.find(v);
    if (it == position.end()) return false;
    in_set_.push_back(it->second);
    taken[it->second] = 1;
  }
  rest_.clear();
  for (std::size_t p = 0; p < superset_.size(); ++p)
    if (!taken[p]) rest_.push_back(static_cast<Index>(p));
  const MatX& s = schur_superset_;
  *schur = s(in_set_, in_set_);
  if (rest_.empty()) return true;
  rest_factors_.compute(s(rest_, rest_));
  if (rest_factors_.info() != Eigen::Success) return false;
  const MatX coupling = s(rest_, in_set_);  // S_C[R,W]
  schur->noalias() -= coupling.transpose() * rest_factors_.solve(coupling);
  return true;
}

bool SchurCondenser::holds_factors_of(const SparseMatrix& a) const {
  if (simplicial_) return simplicial_->holds_factors_of(a, superset_);
  return solver_ && solver_->holds_factors_of(a, superset_);
}

VecX SchurCondenser::solve_with_schur(const VecX& b, const std::function<VecX(const VecX&)>& schur_solve) {
  if (simplicial_) return simplicial_->solve_with_schur(b, schur_solve);
  return solver_->solve_with_schur(b, schur_solve);
}

SchurCondenser::Outcome SchurCondenser::condense(const SparseMatrix& a, const std::vector<Index>& set,
                                                 const std::vector<Index>& superset, MatX* schur) {
  if (holds_factors_of(a) && reduce_to(set, schur)) return Outcome::Reused;
  if (!factorise(a, superset)) return Outcome::Failed;
  if (reduce_to(set, schur)) return Outcome::Factorised;
  // S_C[R,R] not positive definite (an indefinite matrix): condense on the set alone.
  if (!factorise(a, set) || !reduce_to(set, schur)) return Outcome::Failed;
  return Outcome::Factorised;
}

VecX SchurCondenser::solve_interior(const VecX& b) {
  if (rest_.empty()) return simplicial_ ? simplicial_->solve_interior(b) : solver_->solve_interior(b);
  return solve_with_schur(b, [this](const VecX& reduced) {
    VecX x = VecX::Zero(reduced.size());  // zero on the set
    const VecX on_rest = rest_factors_.solve(VecX(reduced(rest_)));
    x(rest_) = on_rest;
    return x;
  });
}

std::optional<Inertia> SchurCondenser::inertia_of(const SparseMatrix& a) {
  if (!holds_factors_of(a)) return std::nullopt;
  Inertia in;  // of A_II (the Schur variables are not pivoted); Eigen's holds a positive definite one
  in.negative = simplicial_ ? 0 : solver_->negative_pivots();
  in.zero = simplicial_ ? 0 : solver_->null_pivots();
  if (superset_.empty()) return in;
  const Real null = kNullPivot * matrix_norm_;
  const Eigen::LLT<MatX> llt(schur_superset_);
  if (llt.info() == Eigen::Success && llt.matrixLLT().diagonal().cwiseAbs2().minCoeff() > null) return in;
  for (const Real lambda : symmetric_eigenvalues(schur_superset_)) {
    in.negative += lambda < -null ? 1 : 0;
    in.zero += std::abs(lambda) <= null ? 1 : 0;
  }
  return in;
}

void SchurCondenser::release() {
  solver_.reset();
  simplicial_.reset();
  superset_.clear();
  schur_superset_.resize(0, 0);
  in_set_.clear();
  rest_.clear();
}

}  // namespace roller
