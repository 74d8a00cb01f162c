#pragma once
// One increment of the transient method: the scene's prescribed displacements and loads at a
// (fractional) step, what the roller starts from (its pose, motion and forces, the friction
// history), the contact session's solve, and the commit of a converged increment into the run's
// pieces (transactional: a throw of the strip's commit changes nothing).
#include <vector>

#include "roller/contact/contact_session.hpp"
#include "roller/io/load_program.hpp"
#include "run_model.hpp"

namespace roller {

class TransientIncrements {
 public:
  // Resolves the scene's conditions against the strip (its dof map is set here) and its contact
  // candidates. InputError for a condition that does not fit the mesh.
  explicit TransientIncrements(RunModel& run);

  // Advances the run from s_from to s_to (scene steps, fractional) with one increment; commits on
  // success (converged = true) and leaves the run untouched on failure.
  IncrementReport advance(Real s_from, Real s_to);
  const std::vector<Index>& candidate_nodes() const { return session_.candidate_nodes(); }

 private:
  // What the increment to s_to starts from besides the strip (the roller's motion, forces, ...).
  IncrementStart increment_start(Real s_to) const;
  void commit(const IncrementSolution& solution, const RollerMotion& motion, Real s_from, Real s_to,
              IncrementReport& inc);

  RunModel& run_;
  LoadProgram loads_;
  ContactSession session_;
};

}  // namespace roller
