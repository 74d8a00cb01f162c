#pragma once
// The backend of a strip without a roller: its increment problem has no contact candidates, and
// Newton minimises the strip's incremental potential (solver/newton.hpp, energy merit). Through
// the same interface as the contact backends, so that an increment is solved one way whatever
// touches the strip.
#include "roller/contact/backend.hpp"
#include "roller/solver/newton.hpp"

namespace roller {

class StripBackend : public ContactBackend {
 public:
  explicit StripBackend(NewtonOptions newton) : newton_(newton) {}
  std::string name() const override { return "newton"; }

 private:
  BackendResult do_solve(IncrementProblem& problem, const VecX& x0) override;
  // Armstrong-Frederick's frozen recovery settles to Newton's own accuracy.
  Real recovery_tolerance() const override { return newton_.residual_tolerance; }
  NewtonOptions newton_;
  NewtonMinimiser newton_solver_;  // kept over the run's increments, with its linear solver
};

}  // namespace roller
