#pragma once
// Builds the contact candidates of one increment from the strip's state: start-of-step
// positions, free-dof indices, tributary lengths (pressure = force / tributary length), the
// depth of the surface element under each node (penalty scale), and the tangent at the
// predictor.
#include <vector>

#include "roller/assembly/strip_model.hpp"
#include "roller/contact/increment_problem.hpp"

namespace roller {

// `nodes`: candidate node indices (e.g. the "contact" set: the top edge sorted by x).
// `prescribed`: the full increment vector's prescribed entries (constrained dofs).
// `predictor`: full increment used to evaluate the tangent direction (e.g. the previous
// increment scaled, or zero). `roller_end_centre`: c^{n+1}.
// Candidates farther than `reach` [mm] from the roller surface at the start are left out: they
// cannot touch it within the increment (no wasted contact variables). Use reach = infinity to
// keep all.
std::vector<ContactCandidate> make_contact_candidates(const StripModel& model, const std::vector<Index>& nodes,
                                                      const VecX& prescribed, const VecX& predictor,
                                                      const Vec2& roller_end_centre, Real radius, Real reach);

}  // namespace roller
