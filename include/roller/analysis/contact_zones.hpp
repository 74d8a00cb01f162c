#pragma once
// Extent of a zone of surface nodes (contact, stick) along x: the zone's boundary is placed
// halfway between its outermost member and the next node outside it, on each side. The
// resolution is therefore half a node spacing.
#include <functional>
#include <vector>

#include "roller/core/types.hpp"

namespace roller {

struct ZoneExtent {
  Real left = 0.0;
  Real right = 0.0;
  Real half_width() const { return 0.5 * (right - left); }
  Real centre() const { return 0.5 * (right + left); }
  bool empty = true;
};

// `x`: node positions sorted by x; `member[i]`: whether node i belongs to the zone. The zone is
// taken from the first to the last member (gaps inside it are ignored).
ZoneExtent zone_extent(const std::vector<Real>& x, const std::vector<bool>& member);

}  // namespace roller
