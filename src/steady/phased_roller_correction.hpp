#pragma once
// The roller's contact on every phase's copy of the strip (assembly/phased_strip.hpp): one
// roller correction per copy, each with the roller k/P of an element further along the base
// strip, on its own block of the iterate. The first copy's contact and pose are the pass's.
#include <memory>
#include <vector>

#include "roller/steady/stationary_passes.hpp"

namespace roller {

class PhasedRollerCorrection final : public RollerCorrection {
 public:
  // `copies[k]` corrects copy k; each copy has `n_dofs` dofs, `n_free` free ones and `n_points`
  // integration points.
  PhasedRollerCorrection(std::vector<std::unique_ptr<RollerCorrection>> copies, Index n_dofs, Index n_free,
                         Index n_points);
  Result correct(const VecX& u, const std::vector<MaterialState>& states, const VecX& r) override;
  const std::vector<NodeContactRecord>& contact() const override { return copies_.front()->contact(); }
  RollerPose pose() const override { return copies_.front()->pose(); }
  Real creep() const override { return copies_.front()->creep(); }

 private:
  std::vector<std::unique_ptr<RollerCorrection>> copies_;
  Index n_dofs_, n_free_, n_points_;
};

}  // namespace roller
