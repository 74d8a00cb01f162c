#pragma once
// The rolling predictor (contact.predictor = "rolling"; docs/model.md, Rolling predictor): in
// steady rolling the increment of a step is nearly the previous increment carried along with the
// roller, u_{n+1}(x, y) ~ u_n(x - dx, y) with dx the roller centre's advance in x, so the solver
// starts from that translate instead of from u_n where it was. On the structured strip
// (mesh/mesh.hpp: columns of ny+1 nodes, rows at equal j) a node takes the previous increment
// interpolated linearly along its own row at its x minus dx; nodes whose source lies beyond the
// row's ends keep their own value (the plain extrapolation). dx = 0 returns the increment itself.
#include <vector>

#include "roller/mesh/mesh.hpp"

namespace roller {

// `increment` over all dofs of `mesh` (node a: 2a, 2a+1); `positions` are the nodes' current
// positions. Throws std::logic_error when the mesh is not a structured strip.
VecX translate_increment(const Mesh& mesh, const std::vector<Vec2>& positions, const VecX& increment, Real dx);

}  // namespace roller
