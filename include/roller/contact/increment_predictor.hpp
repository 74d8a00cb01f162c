#pragma once
// Where an increment starts: the previous converged increment scaled to this one's length (a
// linear extrapolation of the path starts Newton near the solution on smooth paths), moved with
// the roller (contact.predictor = "rolling") or with the nodes it puts inside the roller placed on
// its surface at the arc position (4.25) (contact.predictor = "arc"; docs/model.md, Arc predictor).
#include <vector>

#include "roller/assembly/strip_model.hpp"
#include "roller/contact/contact_options.hpp"
#include "roller/contact/increment_problem.hpp"

namespace roller {

// `last` (all dofs, or empty: none yet) spanned `last_length` steps (0: no predictor of the next);
// the increment spans `length`. `motion`: the roller's over the increment (nullptr: no roller).
VecX increment_predictor(const StripModel& model, const std::vector<Index>& candidate_nodes, const VecX& last,
                         Real last_length, Real length, const RollerMotion* motion, IncrementPredictor mode);

}  // namespace roller
