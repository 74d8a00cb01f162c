#pragma once
// The thesis's contact strategy as a predictor ((4.25); docs/model.md, Arc predictor), option
// contact.predictor = "arc". In the frame of the roller centre at the end of the increment, a
// node moves (apparently) along the straight segment from its start position P_i to its
// predicted position P_{i+1}. If P_{i+1} lies inside the roller, the node first touches the
// roller at C, where the segment enters the circle, after the distance W_FR = |P_i C| outside,
// and would travel W_IN = |C P_{i+1}| inside. It is put back on the circle at C_1, reached from
// C along the circle in the sense of the roller's rotation by the arc
//   C C_1 = R dphi W_IN / (W_FR + W_IN)                                        (4.25)
// i.e. the node sticks to the roller surface for the fraction of the rotation it spends in
// contact. A node already inside at the start (W_FR = 0) starts from its radial projection and
// turns with the roller by the whole R dphi. Only the starting point of the solver changes: the
// contact conditions are then satisfied by the backend.
#include <vector>

#include "roller/assembly/dof_map.hpp"
#include "roller/contact/increment_problem.hpp"

namespace roller {

// Position C_1 for one node: start and predicted end positions, roller centre at the end of the
// increment, radius, rotation increment (counter-clockwise positive). Returns `end` unchanged
// when it is outside the roller.
Vec2 arc_predicted_position(const Vec2& start, const Vec2& end, const Vec2& centre, Real radius, Real dphi);

// Applies it to the free components of `predictor` (all dofs) for the candidate nodes;
// `positions` are the nodes' start-of-increment positions. Returns how many nodes it moved.
int apply_arc_predictor(const std::vector<Index>& nodes, const std::vector<Vec2>& positions, const DofMap& dofs,
                        const RollerMotion& motion, VecX& predictor);

}  // namespace roller
