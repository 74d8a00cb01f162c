#include "roller/contact/increment_problem.hpp"

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

Vec2 IncrementProblem::increment(const ContactCandidate& c, const VecX& x) const {
  Vec2 u = c.prescribed;
  for (int k = 0; k < 2; ++k)
    if (c.free_dof[k] >= 0) u(k) = x(c.free_dof[k]);
  return u;
}

}  // namespace roller
