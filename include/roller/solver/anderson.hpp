#pragma once
// Anderson's acceleration of a fixed-point iteration u <- u + g(u) (Walker & Ni, SIAM J. Numer.
// Anal. 49 (2011) 1715-1735; docs/model.md, "Stationary pass"): the next iterate combines the last
// `depth` iterates so that the linear model of their corrections g is least in norm. The least-
// squares problem is held as a QR factorisation of the corrections' differences, updated by one
// column a step (classical Gram-Schmidt, twice) and downdated by Givens rotations when the oldest
// column leaves, so that a step costs O(n depth) instead of a new QR's O(n depth^2).
#include <deque>

#include "roller/core/types.hpp"

namespace roller {

class Anderson {
 public:
  // `depth`: how many differences the least squares keeps. `conditioning`: the largest ratio of
  // R's diagonal entries kept; older columns leave until it holds (an ill-conditioned history
  // gives combinations dominated by rounding).
  explicit Anderson(int depth, Real conditioning = 1e10);
  // The next iterate from the iterate u and its correction g = g(u).
  VecX next(const VecX& u, const VecX& g);
  // How many differences the least squares used in the last call.
  int columns() const { return m_; }

 private:
  void drop_oldest();

  int depth_;
  Real conditioning_;
  int m_ = 0;  // columns held
  VecX last_u_, last_g_;
  std::deque<VecX> du_;  // u_k - u_{k-1}, oldest first
  MatX q_;               // n x depth: orthonormal columns 0..m-1 span the g differences
  MatX r_;               // depth x depth: upper triangular, g differences = Q R
};

}  // namespace roller
