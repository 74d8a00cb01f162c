#pragma once
// The "condensed" formulation of the interior-point backend (contact.ipopt.formulation; the
// default). See ipopt_condensed.cpp.
#include "roller/contact/backend.hpp"
#include "roller/solver/linear_solver_options.hpp"

namespace roller::ipopt_detail {

// Solves one increment; result.stats["condensed_failed"] = 1 marks a failure of the formulation
// itself (singular strip tangent, no descent, linearisations ran out), after which the caller
// may retry with the full formulation.
BackendResult solve_condensed(IncrementProblem& problem, const VecX& x0, const ContactOptions& options,
                              const LinearSolverOptions& linear);

}  // namespace roller::ipopt_detail
