#pragma once
// One increment of the strip, with the roller coupled as the scene asks (docs/model.md, Roller
// couplings): placed (its motion prescribed), on its suspension (the deflection converged with
// the contact) or under prescribed forces (the centre's offset that carries them). Pure in the run
// state: the caller commits the solution it returns.
#include <vector>

#include "roller/assembly/increment_energy.hpp"
#include "roller/contact/backend.hpp"
#include "roller/driver/increment_types.hpp"
#include "roller/io/scene.hpp"

namespace roller {

class IncrementSolver {
 public:
  // `backend` solves the scene's increments (backend_factory.hpp: the strip's own without a
  // roller); `candidate_nodes` are empty without a roller. All outlive the solver.
  IncrementSolver(const Scene& scene, ContactBackend& backend, const std::vector<Index>& candidate_nodes);

  // Solves the increment of `energy` from `predictor` (all dofs): the solution when report.converged.
  // `motion` ends where the couplings put the roller.
  IncrementSolution solve(IncrementEnergy& energy, const VecX& prescribed, const VecX& predictor, IncrementStart& start,
                          IncrementReport& report);

 private:
  // The strip without a roller: one solve of a problem without contact candidates.
  IncrementSolution solve_strip(IncrementEnergy& energy, const VecX& predictor, const IncrementStart& start,
                                IncrementReport& report);
  const Scene& scene_;
  ContactBackend& backend_;
  const std::vector<Index>& candidate_nodes_;
};

}  // namespace roller
