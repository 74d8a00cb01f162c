#include "increment_solve.hpp"

#include <cmath>

#include "roller/contact/contact_set.hpp"
#include "roller/core/error.hpp"

namespace roller {

IncrementSolve::IncrementSolve(const ContactSessionSettings& settings, ContactBackend& backend,
                               const std::vector<Index>& candidate_nodes, IncrementEnergy& energy,
                               const VecX& prescribed, const VecX& predictor, IncrementStart& start,
                               IncrementReport& report)
    : settings_(settings),
      backend_(backend),
      candidate_nodes_(candidate_nodes),
      energy_(energy),
      prescribed_(prescribed),
      predictor_(predictor),
      start_(start),
      report_(report),
      x_(energy.model().dof_map().restrict_to_free(predictor)) {
  solution_.load_offset = start.load_offset;
  solution_.load_stiffness = start.load_stiffness;
}

bool IncrementSolve::solve_contact(const std::optional<RollerPotential>& potential) {
  RollerMotion& motion = start_.motion;
  // Nodes farther from the roller than it can travel within the increment cannot touch it.
  const Real reach = 0.05 * motion.radius + 4.0 * motion.dc().norm() + 4.0 * predictor_.cwiseAbs().maxCoeff();
  std::vector<ContactCandidate> candidates = make_contact_candidates(
      energy_.model(), candidate_nodes_, prescribed_, predictor_, motion.end.centre, motion.radius, reach);
  start_.friction->seed(candidates);
  // A later pass of the same increment (the suspension's or the load's coupling) moved the roller
  // only a little: its friction fixed point starts from the last pass's normal forces, not from
  // the previous increment's, and so needs no more linearisations than the move itself.
  if (solution_.contact.converged()) seed_normal_forces(candidates, solution_.candidates, solution_.contact.contact);
  IncrementProblem problem(energy_, candidates, motion, settings_.surface_youngs_modulus,
                           settings_.surface_poisson_ratio);
  if (potential) problem.free_roller(*potential, 0.0);  // w measured from where `motion` puts the centre
  if (settings_.rim) {
    problem.attach_rim(*settings_.rim, start_.rim);
    candidates = problem.candidates();  // with their rim samples
  }
  BackendResult result = backend_.solve(problem, x_);
  // The extrapolated predictor misleads when the roller path turns (press -> roll, the
  // harmonic's crests): retry once from the start-of-step configuration before giving up.
  if (!result.converged() && x_.squaredNorm() > 0.0) {
    const int spent = result.counters.iterations;
    problem.move_roller(0.0);
    result = backend_.solve(problem, VecX::Zero(x_.size()));
    result.counters.iterations += spent;  // the first attempt's factorisations are not counted
  }
  if (result.converged()) x_ = result.x;
  if (result.converged() && potential) motion.end.centre.y() += result.roller_offset.value_or(0.0);
  solution_.candidates = std::move(candidates);
  solution_.contact = std::move(result);
  add_solve(report_, solution_.contact);
  return solution_.contact.converged();
}

bool IncrementSolve::joint_height() const {
  return settings_.roller_coupling == RollerCoupling::Joint && backend_.solves_roller_height();
}

std::optional<Real> IncrementSolve::solve_height_jointly(const RollerPotential& potential, Real max_offset) {
  const VecX x0 = x_;
  const Real y0 = start_.motion.end.centre.y();
  solve_contact(potential);
  const Real offset = start_.motion.end.centre.y() - y0;
  if (solution_.contact.converged() && solution_.contact.roller_offset && std::abs(offset) <= max_offset) return offset;
  // Not solved jointly (the condensed formulation failed): everything as it was, for the passes.
  x_ = x0;
  solution_.contact = BackendResult{};
  start_.motion.end.centre.y() = y0;
  return std::nullopt;
}

Vec2 IncrementSolve::strip_force() const {
  const BackendResult& r = solution_.contact;
  ROLLER_ASSERT(r.converged() && r.contact.size() == solution_.candidates.size(),
                "the strip's force is read from a converged solve, one result per candidate");
  const VecX u = energy_.full_increment(r.x);
  Vec2 f = Vec2::Zero();
  for (std::size_t i = 0; i < solution_.candidates.size(); ++i) {
    const ContactCandidate& c = solution_.candidates[i];
    const Vec2 xi = c.position + Vec2(u(2 * c.node), u(2 * c.node + 1));
    const Vec2 n = (xi - start_.motion.end.centre).normalized();
    f -= contact_force(r.contact[i].normal_force, r.contact[i].tangential_force, n, c.tangent);
  }
  return f;
}

IncrementSolution IncrementSolve::finish() {
  report_.max_penetration = solution_.contact.max_penetration;
  if (report_.converged()) solution_.u = energy_.full_increment(solution_.contact.x);
  return std::move(solution_);
}

}  // namespace roller
