#include "roller/contact/rolling_predictor.hpp"

#include <algorithm>
#include <stdexcept>

namespace roller {

VecX translate_increment(const Mesh& mesh, const std::vector<Vec2>& positions, const VecX& increment, Real dx) {
  if (dx == 0.0) return increment;
  // Columns of ny+1 nodes, left to right (mesh/mesh.hpp): the left edge holds one column.
  const Index per_column = static_cast<Index>(mesh.node_set("left").size());
  const Index n = mesh.n_nodes();
  if (per_column < 2 || n % per_column != 0 || increment.size() != 2 * n || static_cast<Index>(positions.size()) != n)
    throw std::logic_error("translate_increment: not a structured strip mesh with this increment");
  const Index columns = n / per_column;
  VecX out = increment;
  std::vector<Real> xs(static_cast<std::size_t>(columns));
  for (Index j = 0; j < per_column; ++j) {
    for (Index i = 0; i < columns; ++i) xs[i] = positions[i * per_column + j].x();
    for (Index i = 0; i < columns; ++i) {
      const Real target = xs[i] - dx;
      if (target < xs.front() || target > xs.back()) continue;
      // The row's x grows with the column (a mesh folded over itself has no translate).
      const auto right = std::upper_bound(xs.begin(), xs.end(), target);
      const Index b = std::min<Index>(static_cast<Index>(right - xs.begin()), columns - 1);
      const Index a = b - 1;
      const Real w = xs[b] > xs[a] ? (target - xs[a]) / (xs[b] - xs[a]) : 0.0;
      const Index na = a * per_column + j, nb = b * per_column + j, node = i * per_column + j;
      for (int c = 0; c < 2; ++c) out(2 * node + c) = (1.0 - w) * increment(2 * na + c) + w * increment(2 * nb + c);
    }
  }
  return out;
}

}  // namespace roller
