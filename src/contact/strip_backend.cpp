#include "roller/contact/strip_backend.hpp"

#include <stdexcept>

namespace roller {

BackendResult StripBackend::do_solve(IncrementProblem& problem, const VecX& x0) {
  if (!problem.candidates().empty())
    throw std::logic_error("newton backend: given contact candidates, which only a contact backend solves");
  VecX x = x0;
  const NewtonReport newton = newton_solver_.minimise(problem.strip(), x, newton_);
  return BackendResult::of(newton, std::move(x));
}

}  // namespace roller
