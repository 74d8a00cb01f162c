#include "roller/solver/anderson.hpp"

#include <Eigen/Jacobi>

namespace roller {

namespace {

// A new difference whose component outside the held ones is below this fraction of its norm
// repeats them: the history starts again.
constexpr Real kDependent = 1e-14;

}  // namespace

Anderson::Anderson(int depth, Real conditioning) : depth_(depth), conditioning_(conditioning) {}

VecX Anderson::next(const VecX& u, const VecX& g) {
  if (last_u_.size() == u.size()) {
    if (q_.rows() != u.size()) q_.resize(u.size(), depth_), r_ = MatX::Zero(depth_, depth_);
    if (m_ == depth_) drop_oldest();
    VecX v = g - last_g_;
    const Real norm = v.norm();
    r_.col(m_).setZero();
    for (int pass = 0; pass < 2 && m_ > 0; ++pass) {  // Gram-Schmidt twice: orthogonal to rounding
      const VecX c = q_.leftCols(m_).transpose() * v;
      r_.col(m_).head(m_) += c;
      v -= q_.leftCols(m_) * c;
    }
    const Real rho = v.norm();
    if (!(rho > kDependent * norm)) {
      m_ = 0;
      du_.clear();
    } else {
      r_(m_, m_) = rho;
      q_.col(m_) = v / rho;
      du_.push_back(u - last_u_);
      ++m_;
      auto diagonal = [&] { return r_.diagonal().head(m_).cwiseAbs(); };
      while (m_ > 1 && diagonal().maxCoeff() > conditioning_ * diagonal().minCoeff()) drop_oldest();
    }
  }
  last_u_ = u;
  last_g_ = g;
  VecX out = u + g;
  if (m_ == 0) return out;
  // gamma = argmin |g - DG gamma| = R^-1 Q^T g; then DG gamma = Q Q^T g.
  const VecX qtg = q_.leftCols(m_).transpose() * g;
  const VecX gamma = r_.topLeftCorner(m_, m_).triangularView<Eigen::Upper>().solve(qtg);
  out -= q_.leftCols(m_) * qtg;
  for (int j = 0; j < m_; ++j) out -= gamma[j] * du_[static_cast<std::size_t>(j)];
  return out;
}

void Anderson::drop_oldest() {
  // R without its first column is upper Hessenberg: Givens rotations G restore the triangle
  // (R <- G^* R) and Q <- Q G keeps the product. Columns past m_ - 1 are zeroed before use.
  for (int j = 0; j + 1 < m_; ++j) r_.col(j).head(m_) = r_.col(j + 1).head(m_);
  for (int i = 0; i + 1 < m_; ++i) {
    Eigen::JacobiRotation<Real> g;
    g.makeGivens(r_(i, i), r_(i + 1, i));
    r_.applyOnTheLeft(i, i + 1, g.adjoint());
    q_.applyOnTheRight(i, i + 1, g);
  }
  r_.row(m_ - 1).setZero();
  r_.col(m_ - 1).setZero();
  --m_;
  du_.pop_front();
}

}  // namespace roller
