#pragma once
// Degrees of freedom: node a has dofs 2a (x) and 2a+1 (y). Constrained dofs (prescribed
// displacement, symmetry plane) are eliminated: solvers work on the free dofs only.
#include <vector>

#include "roller/core/types.hpp"

namespace roller {

class DofMap {
 public:
  DofMap() = default;
  // `constrained[d]` marks dof d as prescribed.
  explicit DofMap(const std::vector<bool>& constrained);

  Index n_dofs() const { return static_cast<Index>(free_index_.size()); }
  Index n_free() const { return static_cast<Index>(free_dofs_.size()); }
  Index free_index(Index dof) const { return free_index_[dof]; }  // -1 when constrained
  bool is_constrained(Index dof) const { return free_index_[dof] < 0; }
  const std::vector<Index>& free_dofs() const { return free_dofs_; }
  const std::vector<Index>& constrained_dofs() const { return constrained_dofs_; }

  VecX restrict_to_free(const VecX& full) const;
  // Overwrites the free entries of `full` with `free` (constrained entries are left as they are).
  void scatter_free(const VecX& free, VecX& full) const;

 private:
  std::vector<Index> free_index_;
  std::vector<Index> free_dofs_;
  std::vector<Index> constrained_dofs_;
};

}  // namespace roller
