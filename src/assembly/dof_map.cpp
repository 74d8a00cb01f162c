#include "roller/assembly/dof_map.hpp"

#include "roller/core/error.hpp"

namespace roller {

DofMap::DofMap(const std::vector<bool>& constrained) : free_index_(constrained.size(), -1) {
  for (std::size_t d = 0; d < constrained.size(); ++d) {
    if (constrained[d]) {
      constrained_dofs_.push_back(static_cast<Index>(d));
    } else {
      free_index_[d] = static_cast<Index>(free_dofs_.size());
      free_dofs_.push_back(static_cast<Index>(d));
    }
  }
}

VecX DofMap::restrict_to_free(const VecX& full) const {
  ROLLER_ASSERT(full.size() == static_cast<Index>(free_index_.size()), "a vector of all dofs");
  VecX out(n_free());
  for (Index i = 0; i < n_free(); ++i) out(i) = full(free_dofs_[i]);
  return out;
}

void DofMap::scatter_free(const VecX& free, VecX& full) const {
  ROLLER_ASSERT(free.size() == n_free() && full.size() == static_cast<Index>(free_index_.size()),
                "a vector of the free dofs into one of all dofs");
  for (Index i = 0; i < n_free(); ++i) full(free_dofs_[i]) = free(i);
}

}  // namespace roller
