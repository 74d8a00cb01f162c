#pragma once
// Testing hooks of the interior-point backend: the NLP of its first fixed-point pass, as the
// backend builds it, evaluated densely or checked by Ipopt's derivative checker. Private to the
// backend (ipopt_backend.hpp keeps Ipopt and test plumbing out of the interface); the tests
// include this header from src/.
#include <string>

#include "roller/contact/contact_options.hpp"
#include "roller/contact/increment_problem.hpp"

namespace roller::ipopt_testing {

// Runs Ipopt's derivative checker ("second-order") on the first pass's NLP at its start point
// and returns its journal output.
std::string derivative_checker_output(IncrementProblem& problem, const VecX& x0, const ContactOptions& options,
                                      double perturbation);

// The first pass's NLP at z (all NLP variables): the objective f, its gradient, the constraints,
// their Jacobian and the Hessian of the Lagrangian obj_factor * f + lambda . g (both triangles).
struct NlpEvaluation {
  long n_variables = 0;
  long n_constraints = 0;
  double f = 0.0;
  VecX grad_f;
  VecX g;
  MatX jacobian;
  MatX hessian;
};

// The NLP is built at x0 = 0; a z of size 0 returns the sizes only.
NlpEvaluation evaluate_nlp(IncrementProblem& problem, const ContactOptions& options, const VecX& z = VecX(),
                           double obj_factor = 1.0, const VecX& lambda = VecX());

}  // namespace roller::ipopt_testing
