#include "phased_roller_correction.hpp"

#include <fmt/format.h>

#include "roller/core/error.hpp"

namespace roller {

PhasedRollerCorrection::PhasedRollerCorrection(std::vector<std::unique_ptr<RollerCorrection>> copies, Index n_dofs,
                                               Index n_free, Index n_points)
    : copies_(std::move(copies)), n_dofs_(n_dofs), n_free_(n_free), n_points_(n_points) {
  ROLLER_ASSERT(!copies_.empty(), "one correction per phase");
}

StationaryCorrection::Result PhasedRollerCorrection::correct(const VecX& u, const std::vector<MaterialState>& states,
                                                             const VecX& r) {
  const auto n = static_cast<Index>(copies_.size());
  ROLLER_ASSERT(
      u.size() == n * n_dofs_ && r.size() == n * n_free_ && static_cast<Index>(states.size()) == n * n_points_,
      "the iterate of every copy");
  Result out;
  out.du.resize(n * n_free_);
  out.load.resize(n * n_dofs_);
  for (Index k = 0; k < n; ++k) {
    const std::vector<MaterialState> copy_states(states.begin() + k * n_points_, states.begin() + (k + 1) * n_points_);
    Result c = copies_[static_cast<std::size_t>(k)]->correct(u.segment(k * n_dofs_, n_dofs_), copy_states,
                                                             r.segment(k * n_free_, n_free_));
    if (c.du.size() == 0) return {VecX(), VecX(), fmt::format("phase {} of {}: {}", k + 1, n, c.message)};
    out.du.segment(k * n_free_, n_free_) = c.du;
    out.load.segment(k * n_dofs_, n_dofs_) = c.load;
    out.new_operator = out.new_operator || c.new_operator;
  }
  return out;
}

}  // namespace roller
