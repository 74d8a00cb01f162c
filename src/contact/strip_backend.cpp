#include "roller/contact/strip_backend.hpp"

#include <stdexcept>

namespace roller {

namespace {

// The increment problem's strip as Newton's objective.
class StripEnergy final : public NewtonObjective {
 public:
  explicit StripEnergy(IncrementProblem& problem) : problem_(problem) {}
  Expected<ObjectiveValue> evaluate(const VecX& x, VecX* gradient, SparseMatrix* hessian) override {
    return problem_.strip_energy(x, gradient, hessian);
  }

 private:
  IncrementProblem& problem_;
};

}  // namespace

BackendResult StripBackend::do_solve(IncrementProblem& problem, const VecX& x0) {
  if (!problem.candidates().empty())
    throw std::logic_error("newton backend: given contact candidates, which only a contact backend solves");
  StripEnergy energy(problem);
  BackendResult result;
  result.x = x0;
  const NewtonReport newton = newton_solver_.minimise(energy, result.x, newton_);
  result.status = newton.status;
  result.message = newton.message;
  result.counters = newton.counters;
  result.residual = newton.residual;
  return result;
}

}  // namespace roller
