#include "roller/driver/increment_solver.hpp"

#include "increment_solve.hpp"
#include "roller/assembly/recovery_iteration.hpp"
#include "roller_couplings.hpp"

namespace roller {

IncrementSolver::IncrementSolver(const Scene& scene, ContactBackend* backend, const std::vector<Index>& candidate_nodes)
    : scene_(scene), backend_(backend), candidate_nodes_(candidate_nodes) {}

IncrementSolution IncrementSolver::solve(IncrementEnergy& energy, const VecX& prescribed, const VecX& predictor,
                                         IncrementStart& start, IncrementReport& report) {
  if (!backend_) {
    // The strip alone: Newton on its incremental potential.
    VecX x = energy.model().dof_map().restrict_to_free(predictor);
    IncrementSolution solution;
    solution.load_offset = start.load_offset;
    solution.load_stiffness = start.load_stiffness;
    // Armstrong-Frederick's recovery has no potential: Newton minimises with it frozen, until the
    // frozen multipliers are the solution's (docs/model.md, Hardening laws).
    RecoveryIteration recovery(energy.model(), scene_.newton.residual_tolerance);
    const Termination end = recovery.iterate([&]() -> std::optional<VecX> {
      const NewtonReport newton = newton_.minimise(energy, x, scene_.newton);
      add_solve(report, newton);
      if (!newton.converged()) return std::nullopt;
      return energy.full_increment(x);
    });
    if (end == Termination::LimitReached) {
      report.status = end;
      report.message = recovery.failure();
    }
    solution.u = energy.full_increment(x);
    return solution;
  }
  IncrementSolve solve(scene_, *backend_, candidate_nodes_, energy, prescribed, predictor, start, report);
  if (start.suspension)
    couple_suspended(solve);
  else if (start.force.any())
    couple_loaded(solve);
  else
    couple_placed(solve);
  return solve.finish();
}

}  // namespace roller
