#include "roller/assembly/dof_map.hpp"

#include "roller/core/error.hpp"

namespace roller {

namespace {

// Every node its own master.
std::vector<Index> own_masters(std::size_t n_dofs) {
  std::vector<Index> masters(n_dofs / 2);
  for (std::size_t a = 0; a < masters.size(); ++a) masters[a] = static_cast<Index>(a);
  return masters;
}

}  // namespace

DofMap::DofMap(const std::vector<bool>& constrained) : DofMap(constrained, own_masters(constrained.size())) {}

DofMap::DofMap(const std::vector<bool>& constrained, const std::vector<Index>& masters)
    : free_index_(constrained.size(), -1) {
  ROLLER_ASSERT(2 * masters.size() == constrained.size(), "one master per node");
  auto master_of = [&](std::size_t d) { return static_cast<std::size_t>(2 * masters[d / 2]) + d % 2; };
  for (std::size_t d = 0; d < constrained.size(); ++d) {
    const std::size_t m = master_of(d);
    ROLLER_ASSERT(masters[m / 2] == static_cast<Index>(m / 2), "a master is its own master");
    if (m != d) continue;  // after every master: the repeating dofs take theirs below
    if (constrained[d]) {
      constrained_dofs_.push_back(static_cast<Index>(d));
    } else {
      free_index_[d] = static_cast<Index>(free_dofs_.size());
      free_dofs_.push_back(static_cast<Index>(d));
    }
  }
  for (std::size_t d = 0; d < constrained.size(); ++d) {
    const std::size_t m = master_of(d);
    if (m == d) continue;
    has_masters_ = true;
    free_index_[d] = free_index_[m];
    if (free_index_[d] < 0) constrained_dofs_.push_back(static_cast<Index>(d));
  }
}

VecX DofMap::restrict_to_free(const VecX& full) const {
  ROLLER_ASSERT(full.size() == static_cast<Index>(free_index_.size()), "a vector of all dofs");
  VecX out(n_free());
  for (Index i = 0; i < n_free(); ++i) out(i) = full(free_dofs_[i]);
  return out;
}

VecX DofMap::gather_free(const VecX& full) const {
  if (!has_masters_) return restrict_to_free(full);
  ROLLER_ASSERT(full.size() == static_cast<Index>(free_index_.size()), "a vector of all dofs");
  VecX out = VecX::Zero(n_free());
  for (Index d = 0; d < full.size(); ++d)
    if (free_index_[d] >= 0) out(free_index_[d]) += full(d);
  return out;
}

void DofMap::scatter_free(const VecX& free, VecX& full) const {
  ROLLER_ASSERT(free.size() == n_free() && full.size() == static_cast<Index>(free_index_.size()),
                "a vector of the free dofs into one of all dofs");
  if (!has_masters_) {
    for (Index i = 0; i < n_free(); ++i) full(free_dofs_[i]) = free(i);
    return;
  }
  for (Index d = 0; d < full.size(); ++d)
    if (free_index_[d] >= 0) full(d) = free(free_index_[d]);
}

}  // namespace roller
