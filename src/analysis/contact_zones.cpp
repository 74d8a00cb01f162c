#include "roller/analysis/contact_zones.hpp"

namespace roller {

ZoneExtent zone_extent(const std::vector<Real>& x, const std::vector<bool>& member) {
  ZoneExtent z;
  std::size_t first = x.size(), last = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (member[i]) {
      first = std::min(first, i);
      last = i;
    }
  if (first == x.size()) return z;
  z.empty = false;
  z.left = first > 0 ? 0.5 * (x[first - 1] + x[first]) : x[first];
  z.right = last + 1 < x.size() ? 0.5 * (x[last] + x[last + 1]) : x[last];
  return z;
}

}  // namespace roller
