#pragma once
// One increment's contact solves in progress (a ContactSession's), shared by the roller couplings
// (roller_couplings.hpp): the increment's energy and prescribed motion, the roller's motion as the
// coupling moves it, the free dofs the next solve starts from, the solution so far and the work
// done. A coupling places the roller and calls solve_contact() until the roller is in balance.
#include <optional>
#include <vector>

#include "roller/assembly/increment_energy.hpp"
#include "roller/contact/contact_session.hpp"
#include "roller/contact/increment_types.hpp"

namespace roller {

class IncrementSolve {
 public:
  IncrementSolve(const ContactSessionSettings& settings, ContactBackend& backend,
                 const std::vector<Index>& candidate_nodes, IncrementEnergy& energy, const VecX& prescribed,
                 const VecX& predictor, IncrementStart& start, IncrementReport& report);

  // One contact solve with the roller at `motion()`: the candidates and the backend's result
  // replace the solution's (which, when converged, is the last pass's and seeds this one). With
  // `potential` the roller's vertical offset from there is an unknown of the solve
  // (IncrementProblem::free_roller), and the motion ends where the solve put the roller.
  // Returns whether it converged; the work is added to the report.
  bool solve_contact(const std::optional<RollerPotential>& potential = std::nullopt);
  // Whether a roller whose height is not prescribed is solved with the strip (contact.roller_coupling
  // and a backend that can) rather than by passes.
  bool joint_height() const;
  // solve_contact with the roller's height an unknown carrying `potential`: the offset the solve
  // moved the roller by, or nullopt, with the free dofs, the solution and the centre as they were,
  // when it did not converge or moved it by more than `max_offset` (the caller then couples by passes).
  std::optional<Real> solve_height_jointly(const RollerPotential& potential, Real max_offset);
  // The force of the strip on the roller in the last contact solution.
  Vec2 strip_force() const;

  const ContactSessionSettings& settings() const { return settings_; }
  const IncrementStart& start() const { return start_; }
  RollerMotion& motion() { return start_.motion; }
  IncrementSolution& solution() { return solution_; }
  IncrementReport& report() { return report_; }
  // The solution, its increment of all dofs filled when the report says converged.
  IncrementSolution finish();

 private:
  const ContactSessionSettings& settings_;
  ContactBackend& backend_;
  const std::vector<Index>& candidate_nodes_;
  IncrementEnergy& energy_;
  const VecX& prescribed_;
  const VecX& predictor_;
  IncrementStart& start_;
  IncrementReport& report_;
  VecX x_;  // free dofs: where the next solve starts
  IncrementSolution solution_;
};

// One solve of an increment (Newton or contact) into its report: the outcome of the last solve,
// the work of all of them.
template <class Result>
void add_solve(IncrementReport& report, const Result& r) {
  report.status = r.status;
  report.counters += r.counters;
  report.residual = r.residual;
  report.message = r.message;
}
// A contact solve also adds its backend's work counters (solver.csv).
inline void add_solve(IncrementReport& report, const BackendResult& r) {
  add_solve<BackendResult>(report, r);
  report.details.add(r.details);
}

}  // namespace roller
