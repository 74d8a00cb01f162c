#include "roller/solver/simplicial_schur.hpp"

#include <algorithm>
#include <cmath>

namespace roller {

namespace {

// Calls f(row, col, value) for every stored entry of the lower triangle, column by column.
template <class F>
void for_each_lower(const SparseMatrix& a, F&& f) {
  for (Index c = 0; c < a.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(a, c); it; ++it)
      if (it.row() >= c) f(it.row(), c, it.value());
}

}  // namespace

bool SimplicialSchur::factorize_with_schur(const SparseMatrix& a, const std::vector<Index>& schur, Real null_pivot,
                                           MatX* s) {
  factorised_ = false;
  const Index n = a.rows();
  // Position of each variable: >= 0 in the interior, -1 - k for the k-th Schur variable.
  std::vector<Index> position(static_cast<std::size_t>(n), 0);
  for (std::size_t k = 0; k < schur.size(); ++k) position[schur[k]] = -1 - static_cast<Index>(k);
  interior_.clear();
  for (Index i = 0; i < n; ++i)
    if (position[i] >= 0) {
      position[i] = static_cast<Index>(interior_.size());
      interior_.push_back(i);
    }
  schur_ = schur;
  const auto ni = static_cast<Index>(interior_.size()), ns = static_cast<Index>(schur.size());
  std::vector<Eigen::Triplet<Real>> ii, is;
  s->setZero(ns, ns);
  Real a_max = 0.0;
  for_each_lower(a, [&](Index r, Index c, Real v) {
    a_max = std::max(a_max, std::abs(v));
    const Index pr = position[r], pc = position[c];
    if (pr >= 0 && pc >= 0)
      ii.emplace_back(pr, pc, v);
    else if (pr >= 0)
      is.emplace_back(pr, -1 - pc, v);
    else if (pc >= 0)
      is.emplace_back(pc, -1 - pr, v);  // A_si(r, c) = A_is(c, r)
    else
      (*s)(-1 - pr, -1 - pc) = (*s)(-1 - pc, -1 - pr) = v;
  });
  SparseMatrix a_ii(ni, ni);
  a_ii.setFromTriplets(ii.begin(), ii.end());
  a_is_.resize(ni, ns);
  a_is_.setFromTriplets(is.begin(), is.end());
  const bool same_pattern =
      analysed_n_ == ni &&
      std::equal(analysed_outer_.begin(), analysed_outer_.end(), a_ii.outerIndexPtr(), a_ii.outerIndexPtr() + ni + 1) &&
      static_cast<Index>(analysed_inner_.size()) == a_ii.nonZeros() &&
      std::equal(analysed_inner_.begin(), analysed_inner_.end(), a_ii.innerIndexPtr());
  if (!same_pattern) {
    ldlt_.analyzePattern(a_ii);
    analysed_n_ = ni;
    analysed_outer_.assign(a_ii.outerIndexPtr(), a_ii.outerIndexPtr() + ni + 1);
    analysed_inner_.assign(a_ii.innerIndexPtr(), a_ii.innerIndexPtr() + a_ii.nonZeros());
  }
  ldlt_.factorize(a_ii);
  if (ldlt_.info() != Eigen::Success) return false;
  if (ni > 0 && ldlt_.vectorD().minCoeff() <= null_pivot * a_max) return false;
  if (ns > 0 && ni > 0) {
    s->noalias() -= a_is_.transpose() * ldlt_.solve(MatX(a_is_));
    s->triangularView<Eigen::StrictlyUpper>() = s->transpose();  // symmetric to the bit, as MUMPS's
  }
  held_ = a.triangularView<Eigen::Lower>();
  held_.makeCompressed();
  factorised_ = true;
  return true;
}

VecX SimplicialSchur::gather_interior(const VecX& b) const { return b(interior_); }

VecX SimplicialSchur::gather_schur(const VecX& b) const { return b(schur_); }

VecX SimplicialSchur::scatter(const VecX& xi, const VecX& xs) const {
  VecX x(static_cast<Index>(interior_.size() + schur_.size()));
  x(interior_) = xi;
  x(schur_) = xs;
  return x;
}

VecX SimplicialSchur::solve_interior(const VecX& b) const {
  return scatter(interior_solve(gather_interior(b)), VecX::Zero(static_cast<Index>(schur_.size())));
}

bool SimplicialSchur::holds_factors_of(const SparseMatrix& a, const std::vector<Index>& schur) const {
  if (!factorised_ || a.rows() != held_.rows() || schur != schur_) return false;
  const Real* value = held_.valuePtr();
  const int* row = held_.innerIndexPtr();
  const int* column_start = held_.outerIndexPtr();
  const Index count = held_.nonZeros();
  Index e = 0;
  bool same = true;
  for_each_lower(a, [&](Index r, Index c, Real v) {
    same = same && e < count && e >= column_start[c] && e < column_start[c + 1] && row[e] == r && value[e] == v;
    ++e;
  });
  return same && e == count;
}

}  // namespace roller
