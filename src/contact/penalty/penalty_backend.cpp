#include "roller/contact/penalty_backend.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <fmt/format.h>

#include "roller/core/error.hpp"
#include "roller/solver/sparse_solver.hpp"

namespace roller {

namespace {

using Stiffness = PenaltyBackend::Stiffness;

// Largest |r|/F accepted because the round-off floor forbids a smaller one (newton_stage).
constexpr Real kMaxRoundoffResidual = 1e-3;

// Contact forces of candidate c at x and, optionally, the 2x2 tangent block d(-f)/du of the
// force f = F_N n + F_T t acting on the node. With `frozen`, the node keeps that status (and slip
// direction) whatever x: open nodes carry no force, closed ones a bilateral normal penalty (also
// in tension), so the system is smooth for Newton; the caller updates the statuses between solves.
NodeContact contact_state(const IncrementProblem& p, const ContactCandidate& c, const Stiffness& k, const VecX& x,
                          Mat2* block, const NodeContact* frozen = nullptr) {
  NodeContact s;
  const Vec2 u = p.increment(c, x);
  const Vec2 d = p.from_centre(c, u);
  const Real rho = d.norm();
  const Vec2 n = d / rho;
  s.gap = rho - p.roller().radius;
  s.slip = p.slip_for(c, u);
  if (block) block->setZero();
  if (frozen ? frozen->status == ContactStatus::Open : s.gap >= 0.0) return s;  // open: no force
  s.normal_force = -k.normal * s.gap;
  const Real mu = p.roller().friction;
  const Vec2& t = c.tangent;
  if (block) *block += k.normal * n * n.transpose() - s.normal_force * (Mat2::Identity() - n * n.transpose()) / rho;
  if (mu == 0.0) {
    s.status = ContactStatus::Slip;
    return s;
  }
  const Real trial = c.tangential_force - k.tangential * s.slip;
  const Real bound = mu * s.normal_force;
  if (frozen) {
    if (frozen->status == ContactStatus::Stick) {
      s.tangential_force = trial;
      s.status = ContactStatus::Stick;
      if (block) *block += k.tangential * t * t.transpose();
    } else {
      const Real sign = frozen->tangential_force >= 0.0 ? 1.0 : -1.0;
      s.tangential_force = sign * bound;
      s.status = ContactStatus::Slip;
      if (block) *block += mu * k.normal * sign * t * n.transpose();
    }
    return s;
  }
  if (std::abs(trial) <= bound) {
    s.tangential_force = trial;
    s.status = ContactStatus::Stick;
    if (block) *block += k.tangential * t * t.transpose();
  } else {
    const Real sign = trial > 0.0 ? 1.0 : -1.0;
    s.tangential_force = sign * bound;
    s.status = ContactStatus::Slip;
    if (block) *block += mu * k.normal * sign * t * n.transpose();  // unsymmetric
  }
  return s;
}

struct Evaluation {
  VecX residual;
  SparseMatrix jacobian;
  std::vector<NodeContact> contact;
  Real scale = 0.0;
  // Residual that round-off alone produces: the gap |x - c| - R of a node at distance rho from
  // the centre carries an absolute error ~ eps rho, which the penalty turns into a force
  // error ~ eps rho kN. Tolerances below it cannot be met.
  Real roundoff_floor = 0.0;
  bool symmetric = true;
};

// Residual r = dPi/dx - (contact forces) on the free dofs, and its Jacobian when asked, into `e`;
// false, with the strip's reason in `why`, when the strip cannot take x.
bool evaluate(IncrementProblem& p, const std::vector<Stiffness>& k, const VecX& x, bool want_jacobian, Evaluation& e,
              const std::vector<NodeContact>* frozen = nullptr, std::string* why = nullptr) {
  const Expected<ObjectiveValue> strip = p.strip_energy(x, &e.residual, want_jacobian ? &e.jacobian : nullptr);
  if (!strip) {
    if (why) *why = strip.error();
    return false;
  }
  const Real strip_scale = strip->force_scale;
  e.contact.assign(p.candidates().size(), NodeContact{});
  // Armstrong-Frederick's consistent tangent is unsymmetric (docs/model.md, Hardening laws).
  e.symmetric = !p.strip_model().has_recovery();
  Real contact_norm2 = 0.0, floor2 = 0.0;
  Mat2 block;
  for (std::size_t i = 0; i < p.candidates().size(); ++i) {
    const ContactCandidate& c = p.candidates()[i];
    NodeContact& s = e.contact[i];
    s = contact_state(p, c, k[i], x, want_jacobian ? &block : nullptr, frozen ? &(*frozen)[i] : nullptr);
    if (s.status == ContactStatus::Open) continue;
    const Real floor_i =
        10.0 * std::numeric_limits<Real>::epsilon() * k[i].normal * (p.position(c, x) - p.roller().end.centre).norm();
    floor2 += floor_i * floor_i;
    const Vec2 f = contact_force(s.normal_force, s.tangential_force, p.normal(c, x), c.tangent);
    contact_norm2 += f.squaredNorm();
    if (s.status == ContactStatus::Slip && p.roller().friction > 0.0) e.symmetric = false;
    for (int a = 0; a < 2; ++a) {
      if (c.free_dof[a] < 0) continue;
      e.residual(c.free_dof[a]) -= f(a);
      if (!want_jacobian) continue;
      for (int b = 0; b < 2; ++b)
        if (c.free_dof[b] >= 0) e.jacobian.coeffRef(c.free_dof[a], c.free_dof[b]) += block(a, b);
    }
  }
  e.scale = std::max(strip_scale, std::sqrt(contact_norm2));
  e.roundoff_floor = std::sqrt(floor2);
  return true;
}

// evaluate() where no step can be shortened (the start, a Newton solve's solution): a strip that
// cannot take x ends the solve with its NumericalError (the driver cuts the step).
void evaluate_or_throw(IncrementProblem& p, const std::vector<Stiffness>& k, const VecX& x, Evaluation& e) {
  std::string why;
  if (!evaluate(p, k, x, false, e, nullptr, &why)) throw NumericalError(why);
}

// The documented penalty rule: kN = factor E* l_i / h_i per candidate, kT = tangential_factor kN.
std::vector<Stiffness> penalty_stiffnesses(const IncrementProblem& p, Real factor, Real tangential_factor) {
  std::vector<Stiffness> k;
  for (const auto& c : p.candidates()) {
    const Real kn = factor * p.plane_strain_modulus() * c.tributary_length / c.element_size;
    k.push_back({kn, tangential_factor * kn});
  }
  return k;
}

// LDL^T for the symmetric Jacobian (no friction, or stick), LU for the unsymmetric one of
// sliding friction, and LU as the fallback when LDL^T fails (solver/sparse_solver.hpp).
// The solvers are the backend's, kept between calls so that MUMPS's symbolic analysis is redone
// only when the Jacobian's pattern changes (it is fixed within an increment).
bool solve_linear(const Evaluation& e, const LinearSolverOptions& linear, SparseSolver& ldlt, SparseSolver& lu,
                  VecX& d) {
  ldlt.configure(linear);
  lu.configure(linear);
  if (e.symmetric) {
    if (ldlt.factorize(e.jacobian)) {
      d = ldlt.solve(-e.residual);
      if (d.allFinite()) return true;
    }
  }
  if (!lu.factorize(e.jacobian)) return false;
  d = lu.solve(-e.residual);
  return d.allFinite();
}

}  // namespace

PenaltyBackend::PenaltyBackend(ContactOptions options, NewtonOptions newton)
    : options_(std::move(options)), newton_(newton) {}

void PenaltyBackend::residual(IncrementProblem& problem, const VecX& x, VecX& r, SparseMatrix* jacobian) const {
  const auto k = penalty_stiffnesses(problem, options_.penalty.factor, options_.penalty.tangential_factor);
  Evaluation e;
  std::string why;
  if (!evaluate(problem, k, x, jacobian != nullptr, e, nullptr, &why)) throw NumericalError(why);
  r = e.residual;
  if (jacobian) *jacobian = e.jacobian;
}

// One Newton solve at fixed penalty stiffnesses, from x (updated in place).
BackendResult PenaltyBackend::newton_stage(IncrementProblem& problem, const std::vector<Stiffness>& k, VecX& x,
                                           Real tolerance, const std::vector<NodeContact>* frozen) {
  BackendResult result;
  VecX d, x_trial;
  Evaluation e, trial;
  int full_steps = 0;  // consecutive full steps taken without a residual decrease
  constexpr int kMaxFullSteps = 5;
  std::string why;
  if (!evaluate(problem, k, x, true, e, frozen, &why)) {
    result.message = fmt::format("cannot evaluate the start of the increment: {}", why);
    return result;
  }
  for (int it = 0;; ++it) {
    const Real rnorm = e.residual.norm();
    result.counters.iterations = it;
    result.residual = rnorm / std::max(e.scale, 1e-300);
    if (!std::isfinite(rnorm)) {
      result.message =
          "the residual is not finite: the increment diverged; use smaller steps (a larger steps.count, or "
          "steps.max_cuts)";
      return result;
    }
    if (result.residual <= tolerance || rnorm <= e.roundoff_floor) {
      // Below the round-off floor no iteration reduces the residual further, but the floor grows
      // with the penalty (eps |x - c| kN per node). Above kMaxRoundoffResidual of the force scale
      // the penalty is too stiff for double precision and the contact forces are round-off
      // noise (measured, docs/stability.md: Z1 at factor 1e12 was accepted at |r|/F ~ 1.8 with
      // the roller force 28 % off): stop with the cause instead of accepting the increment.
      if (result.residual > tolerance && result.residual > kMaxRoundoffResidual) {
        result.status = Termination::LimitReached;
        result.message = fmt::format(
            "penalty Newton: the penalty is too stiff for double precision: round-off in the gaps "
            "alone leaves |r|/F = {:.2e} (> {:.0e}), the contact forces are not resolved; use a "
            "smaller contact.penalty.factor (now {:.3g}) or the ipopt backend",
            result.residual, kMaxRoundoffResidual, options_.penalty.factor);
        break;
      }
      result.status = Termination::Converged;
      break;
    }
    if (it >= newton_.max_iterations) {
      result.status = Termination::LimitReached;
      result.message = fmt::format(
          "penalty Newton: no convergence in {} iterations (|r|/F = {:.2e}); use smaller steps (a larger steps.count, "
          "or steps.max_cuts), "
          "a smaller contact.penalty.factor, or the ipopt backend",
          it, result.residual);
      break;
    }
    ++result.counters.factorizations;
    if (!solve_linear(e, newton_.linear, ldlt_, lu_, d)) {
      result.message =
          "penalty Newton: the tangent matrix is singular (missing supports, or a "
          "mechanism); check the boundary conditions";
      return result;
    }
    // Backtracking on ||r||: once friction slips no energy exists to backtrack on.
    Real alpha = 1.0;
    bool accepted = false;
    for (int ls = 0; ls < 20 && !accepted; ++ls, alpha *= 0.5) {
      x_trial = x + alpha * d;
      if (!evaluate(problem, k, x_trial, false, trial, frozen)) continue;
      accepted = !newton_.line_search || trial.residual.norm() <= (1.0 - 1e-4 * alpha) * rnorm;
    }
    if (!accepted) {
      // No decrease of ||r|| along d: the contact/stick/slip state changes along the step and
      // ||r|| is not a reliable merit there. Take the full Newton step (a semismooth Newton
      // step), at most a few times in a row; the iteration limit bounds the rest.
      if (++full_steps > kMaxFullSteps) {
        result.status = Termination::LimitReached;
        result.message = fmt::format(
            "penalty Newton: the line search found no decrease of the residual (|r|/F = {:.2e}); "
            "use smaller steps (a larger steps.count, or steps.max_cuts), a smaller contact.penalty.factor, or the "
            "ipopt backend",
            result.residual);
        break;
      }
      x_trial = x + d;
    } else {
      full_steps = 0;
    }
    x = x_trial;
    if (!evaluate(problem, k, x, true, e, frozen, &why)) {
      result.message = why;
      return result;
    }
  }
  result.x = x;
  result.contact = e.contact;
  return result;
}

BackendResult PenaltyBackend::do_solve(IncrementProblem& problem, const VecX& x0) {
  // First a Newton at the target penalty from the predictor: the previous increment ended in
  // equilibrium at this penalty, so on a smooth path this converges at once. If it fails,
  // penalty staging (measured: a Newton at a high penalty chatters between contact/stick/slip
  // states when the contact set changes much): solve at a soft penalty first and raise it by
  // 100 per stage up to the target, each stage starting from the previous solution.
  // Intermediate stages stop at a looser tolerance.
  const Real target = options_.penalty.factor;
  const auto k_target = penalty_stiffnesses(problem, target, options_.penalty.tangential_factor);
  SolveCounters spent;
  {
    // Active-set passes: Newton on the smooth system with every node's status (open, stick,
    // slip and its direction) frozen, then the statuses are updated from the converged state;
    // done when no status changes (then the frozen and the true Coulomb residuals coincide).
    VecX x = x0;
    Evaluation natural;
    evaluate_or_throw(problem, k_target, x, natural);
    std::vector<NodeContact> status = natural.contact;
    for (int pass = 1; pass <= kMaxActiveSetPasses; ++pass) {
      BackendResult r = newton_stage(problem, k_target, x, newton_.residual_tolerance, &status);
      spent += r.counters;
      if (!r.converged()) break;
      evaluate_or_throw(problem, k_target, x, natural);
      bool same = true;
      for (std::size_t i = 0; i < status.size() && same; ++i)
        same = natural.contact[i].status == status[i].status &&
               (natural.contact[i].status != ContactStatus::Slip ||
                (natural.contact[i].tangential_force >= 0.0) == (status[i].tangential_force >= 0.0));
      if (same) {
        r.counters = spent;
        r.contact = natural.contact;
        r.residual = natural.residual.norm() / std::max(natural.scale, 1e-300);
        r.details.fill<PenaltyDetails>().active_set_passes = pass;
        return r;
      }
      // Update; a slip that reverses its direction goes through stick first (otherwise two
      // nodes near the no-slip point can flip back and forth for ever).
      for (std::size_t i = 0; i < status.size(); ++i) {
        const bool reversed = status[i].status == ContactStatus::Slip &&
                              natural.contact[i].status == ContactStatus::Slip && problem.roller().friction > 0.0 &&
                              (natural.contact[i].tangential_force >= 0.0) != (status[i].tangential_force >= 0.0);
        status[i] = natural.contact[i];
        if (reversed) status[i].status = ContactStatus::Stick;
      }
    }
  }
  {
    VecX x = x0;
    BackendResult direct = newton_stage(problem, k_target, x, newton_.residual_tolerance);
    direct.counters += spent;
    direct.details.fill<PenaltyDetails>().penalty_stages = 1;
    if (direct.converged() || target <= 10.0 * kFirstStageFactor) return direct;
    spent = direct.counters;
  }
  std::vector<Real> factors{target};
  while (factors.back() > 10.0 * kFirstStageFactor) factors.push_back(factors.back() / 100.0);
  std::reverse(factors.begin(), factors.end());

  VecX x = x0;
  BackendResult total;
  total.counters = spent;
  for (std::size_t stage = 0; stage < factors.size(); ++stage) {
    const auto k = penalty_stiffnesses(problem, factors[stage], options_.penalty.tangential_factor);
    const bool last = stage + 1 == factors.size();
    BackendResult r =
        newton_stage(problem, k, x, last ? newton_.residual_tolerance : std::max(1e-6, newton_.residual_tolerance));
    r.counters += total.counters;
    r.details.fill<PenaltyDetails>().penalty_stages = stage + 1;
    total = std::move(r);
    if (!total.converged()) {
      total.message = fmt::format("stage {} of {} (penalty factor {:.3g}): {}", stage + 1, factors.size(),
                                  factors[stage], total.message);
      return total;
    }
  }
  return total;
}

}  // namespace roller
