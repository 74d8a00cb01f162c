#pragma once
// Degrees of freedom: node a has dofs 2a (x) and 2a+1 (y). Constrained dofs (prescribed
// displacement, symmetry plane) are eliminated: solvers work on the free dofs only. A node may
// have a master (a periodic strip's right edge, node_masters): its dofs are its master's, so they
// share one free index.
#include <vector>

#include "roller/core/types.hpp"

namespace roller {

class DofMap {
 public:
  DofMap() = default;
  // `constrained[d]` marks dof d as prescribed.
  explicit DofMap(const std::vector<bool>& constrained);
  // The same with each node's master (one per node; a node is its own master unless it repeats
  // another): a node's dofs are constrained or free as its master's are.
  DofMap(const std::vector<bool>& constrained, const std::vector<Index>& masters);

  Index n_dofs() const { return static_cast<Index>(free_index_.size()); }
  Index n_free() const { return static_cast<Index>(free_dofs_.size()); }
  Index free_index(Index dof) const { return free_index_[dof]; }  // -1 when constrained
  bool is_constrained(Index dof) const { return free_index_[dof] < 0; }
  const std::vector<Index>& free_dofs() const { return free_dofs_; }
  const std::vector<Index>& constrained_dofs() const { return constrained_dofs_; }

  // The free entries of a vector of all dofs that holds a displacement (a node repeating another
  // holds its master's value).
  VecX restrict_to_free(const VecX& full) const;
  // The free entries of a vector of all dofs that holds forces: a repeating node's force adds to its
  // master's.
  VecX gather_free(const VecX& full) const;
  // Overwrites the free entries of `full` with `free`, a repeating node's with its master's
  // (constrained entries are left as they are).
  void scatter_free(const VecX& free, VecX& full) const;
  // Whether some node repeats another (a periodic strip).
  bool has_masters() const { return has_masters_; }

 private:
  std::vector<Index> free_index_;
  std::vector<Index> free_dofs_;
  std::vector<Index> constrained_dofs_;
  bool has_masters_ = false;
};

}  // namespace roller
