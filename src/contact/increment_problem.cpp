#include "roller/contact/increment_problem.hpp"

#include <algorithm>

#include "roller/core/error.hpp"

namespace roller {

IncrementProblem::IncrementProblem(IncrementEnergy& strip, std::vector<ContactCandidate> candidates,
                                   RollerMotion roller, Real youngs_modulus, Real poisson_ratio)
    : strip_(strip),
      candidates_(std::move(candidates)),
      roller_(roller),
      youngs_modulus_(youngs_modulus),
      poisson_ratio_(poisson_ratio),
      n_free_(strip.n_free()) {}

Real IncrementProblem::plane_strain_modulus() const {
  return youngs_modulus_ / (1.0 - poisson_ratio_ * poisson_ratio_);
}

void IncrementProblem::attach_rim(const RimStiffness& rim, const VecX* start) {
  rim_ = &rim;
  rim_start_ = start ? *start : VecX::Zero(n_rim());
  ROLLER_ASSERT(rim_start_.size() == n_rim(), "attach_rim: one start displacement per rim dof");
  rim_w_ = rim_start_;
  const Real first = rim_angle(rim.positions.front()), last = rim_angle(rim.positions.back());
  const Real radius = rim.positions.front().norm();
  for (ContactCandidate& c : candidates_) {
    c.rim = RimSample{};
    const Real angle = rim_angle(c.position - roller_.end.centre);
    if (!(angle >= first && angle <= last)) continue;
    const Real reach = c.tributary_length / radius;
    for (const RimWeight& k : rim_sample(rim.positions, angle, reach)) {
      c.rim.node.push_back(k.node);
      c.rim.gap_weight.push_back(-k.weight * rim_radial(rim_angle(rim.positions[k.node])));
      c.rim.slip_weight.push_back(-k.weight * c.tangent);
    }
    // The material now there lay dphi behind (counter-clockwise positive); beyond the arc its
    // displacement is taken as the arc end's.
    const Real back = roller_.dphi();
    for (const RimWeight& k : rim_sample(rim.positions, angle - back, reach))
      c.rim.slip_start += k.weight * c.tangent.dot(rim_start_.segment<2>(2 * k.node));
  }
}

namespace {

// sum_k weight[k] . w_node[k]: a sample's share of the rim displacements w.
Real weighted_rim(const RimSample& s, const std::vector<Vec2>& weight, const Real* w) {
  Real sum = 0.0;
  for (std::size_t k = 0; k < s.node.size(); ++k) sum += weight[k].dot(Vec2(w[2 * s.node[k]], w[2 * s.node[k] + 1]));
  return sum;
}

}  // namespace

Real IncrementProblem::rim_gap_shift(const ContactCandidate& c, const Real* w) const {
  return rim_ ? weighted_rim(c.rim, c.rim.gap_weight, w) : 0.0;
}

Real IncrementProblem::rim_slip_shift(const ContactCandidate& c, const Real* w) const {
  return rim_ ? c.rim.slip_start + weighted_rim(c.rim, c.rim.slip_weight, w) : 0.0;
}

Vec2 IncrementProblem::increment(const ContactCandidate& c, const VecX& x) const {
  Vec2 u = c.prescribed;
  for (int k = 0; k < 2; ++k)
    if (c.free_dof[k] >= 0) u(k) = x(c.free_dof[k]);
  return u;
}

}  // namespace roller
