#include "roller/driver/increment_solver.hpp"

#include "increment_solve.hpp"
#include "roller_couplings.hpp"

namespace roller {

IncrementSolver::IncrementSolver(const Scene& scene, ContactBackend& backend, const std::vector<Index>& candidate_nodes)
    : scene_(scene), backend_(backend), candidate_nodes_(candidate_nodes) {}

IncrementSolution IncrementSolver::solve(IncrementEnergy& energy, const VecX& prescribed, const VecX& predictor,
                                         IncrementStart& start, IncrementReport& report) {
  if (!scene_.roller) return solve_strip(energy, predictor, start, report);
  IncrementSolve solve(scene_, backend_, candidate_nodes_, energy, prescribed, predictor, start, report);
  if (start.suspension)
    couple_suspended(solve);
  else if (start.force.any())
    couple_loaded(solve);
  else
    couple_placed(solve);
  return solve.finish();
}

IncrementSolution IncrementSolver::solve_strip(IncrementEnergy& energy, const VecX& predictor,
                                               const IncrementStart& start, IncrementReport& report) {
  const MaterialParams m = scene_.strip_material().surface();
  IncrementProblem problem(energy, {}, start.motion, m.youngs_modulus, m.poisson_ratio);
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
