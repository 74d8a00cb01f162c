#include "roller/contact/contact_session.hpp"

#include <utility>

#include "increment_solve.hpp"
#include "roller_couplings.hpp"

namespace roller {

ContactSession::ContactSession(ContactSessionSettings settings, ContactBackend& backend,
                               std::vector<Index> candidate_nodes)
    : settings_(std::move(settings)), backend_(backend), candidate_nodes_(std::move(candidate_nodes)) {}

IncrementSolution ContactSession::solve(IncrementEnergy& energy, const VecX& prescribed, const VecX& predictor,
                                        IncrementStart& start, IncrementReport& report) {
  if (!settings_.roller) return solve_strip(energy, predictor, start, report);
  IncrementSolve solve(settings_, backend_, candidate_nodes_, energy, prescribed, predictor, start, report);
  if (start.suspension)
    couple_suspended(solve);
  else if (start.force.any())
    couple_loaded(solve);
  else
    couple_placed(solve);
  return solve.finish();
}

IncrementSolution ContactSession::solve_strip(IncrementEnergy& energy, const VecX& predictor,
                                              const IncrementStart& start, IncrementReport& report) {
  IncrementProblem problem(energy, {}, start.motion, settings_.surface_youngs_modulus, settings_.surface_poisson_ratio);
  const BackendResult result = backend_.solve(problem, energy.model().dof_map().restrict_to_free(predictor));
  add_solve(report, result);
  IncrementSolution solution;
  solution.load_offset = start.load_offset;
  solution.load_stiffness = start.load_stiffness;
  solution.u = energy.full_increment(result.x);
  solution.contact = result;
  return solution;
}

}  // namespace roller
