#pragma once
// The "condensed" formulation of the interior-point backend (contact.ipopt.formulation; the
// default). See ipopt_condensed.cpp.
#include "roller/contact/backend.hpp"
#include "roller/solver/linear_solver_options.hpp"

namespace roller::ipopt_detail {

struct CondensedOutcome {
  BackendResult result;
  // The formulation itself failed (singular strip tangent, no descent, linearisations ran out):
  // the caller may solve the increment with the full formulation instead.
  bool formulation_failed = false;
};

CondensedOutcome solve_condensed(IncrementProblem& problem, const VecX& x0, const ContactOptions& options,
                                 const LinearSolverOptions& linear);

}  // namespace roller::ipopt_detail
