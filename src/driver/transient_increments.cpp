#include "transient_increments.hpp"

#include <fmt/format.h>

#include "roller/assembly/increment_energy.hpp"
#include "roller/contact/increment_predictor.hpp"
#include "roller/core/error.hpp"
#include "roller/io/contact_settings.hpp"
#include "roller/io/scene_strip.hpp"

namespace roller {

TransientIncrements::TransientIncrements(RunModel& run)
    : run_(run),
      loads_(run.scene, run.strip->mesh()),
      session_(contact_session_settings(run.scene, run.strip->mesh()), *run.backend,
               contact_candidate_nodes(run.scene, run.strip->mesh())) {
  run.strip->set_dof_map(loads_.dof_map());
}

IncrementStart TransientIncrements::increment_start(Real s_to) const {
  IncrementStart start;
  start.friction = &run_.state.friction;
  if (run_.state.rim.size() > 0) start.rim = &run_.state.rim;
  start.suspension = run_.dynamics.suspension();
  start.load_offset = run_.state.load_offset;
  start.load_stiffness = run_.state.load_stiffness;
  if (!run_.scene.roller) return start;
  RollerMotion& motion = start.motion;
  motion.radius = run_.scene.roller->radius;
  motion.start = run_.state.pose;
  motion.end = run_.program.pose(s_to);
  motion.end.centre += run_.state.load_offset;
  motion.friction = run_.program.friction(s_to, run_.scene.contact.friction);
  start.force = run_.program.force(s_to);
  start.roller_force = run_.roller_force();
  return start;
}

IncrementReport TransientIncrements::advance(Real s_from, Real s_to) {
  IncrementReport inc;
  // Prescribed increments: target total minus what the dof already has, so sub-increments
  // never accumulate drift.
  const VecX prescribed = loads_.prescribed_displacement(s_to) - run_.strip->total_displacement();
  IncrementEnergy energy(*run_.strip, prescribed, loads_.external_force(s_to),
                         run_.dynamics.begin_increment((s_to - s_from) * run_.scene.steps.dt));
  IncrementStart start = increment_start(s_to);
  const IncrementSolution solution = session_.solve(
      energy, prescribed,
      increment_predictor(*run_.strip, session_.candidate_nodes(), run_.state.last_increment, run_.state.last_length,
                          s_to - s_from, run_.scene.roller ? &start.motion : nullptr, run_.scene.contact.predictor),
      start, inc);
  if (inc.converged()) commit(solution, start.motion, s_from, s_to, inc);
  return inc;
}

void TransientIncrements::commit(const IncrementSolution& solution, const RollerMotion& motion, Real s_from, Real s_to,
                                 IncrementReport& inc) {
  ROLLER_ASSERT(inc.converged() && solution.u.size() == run_.strip->n_dofs(), "a converged increment of all dofs");
  ROLLER_ASSERT(s_to > s_from, "an increment moves forward in steps");
  try {
    inc.n_yielded = run_.strip->commit(solution.u);
  } catch (const NumericalError& e) {
    // A solver reported success at a state the strip cannot take (e.g. an inverted element):
    // treat it as a failed increment so the step is cut; nothing was committed.
    inc.status = Termination::Failed;
    inc.message = fmt::format("the increment's solution is not admissible: {}", e.what());
    return;
  }
  run_.state.last_increment = solution.u;
  run_.state.last_length = s_to - s_from;
  run_.state.load_offset = solution.load_offset;
  run_.state.load_stiffness = solution.load_stiffness;
  run_.dynamics.commit_increment(run_.strip->total_displacement(), solution.deflection);
  if (run_.scene.roller) {
    run_.state.pose = motion.end;
    run_.state.contact = contact_records(solution, run_.state.pose.centre);
    run_.state.friction.record(solution.candidates, solution.contact.contact);
    if (solution.contact.rim.size() > 0) run_.state.rim = solution.contact.rim;
  }
}

}  // namespace roller
