#include "roller/contact/penalty_backend.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <fmt/format.h>

#include "roller/core/error.hpp"

namespace roller {

namespace {

using Stiffness = PenaltyBackend::Stiffness;

// Largest |r|/F accepted because the round-off floor forbids a smaller one (newton_stage).
constexpr Real kMaxRoundoffResidual = 1e-3;

// A candidate's contact as a function of its local unknowns among z = [x, w] (w: an elastic
// roller's rim displacements after the strip's free dofs): the node's free x and y, then those of
// the rim nodes it touches; -1 where there is none. The gap and the slip are linear in the rim's.
struct LocalDofs {
  std::vector<Index> index;
  VecX gap;   // d gap / d z_local
  VecX slip;  // d slip / d z_local
};

// Fills `d` (reused from candidate to candidate: no allocation once it is large enough).
void fill_local_dofs(const IncrementProblem& p, const ContactCandidate& c, const Vec2& normal, LocalDofs& d) {
  const Index n_rim = p.rim() ? static_cast<Index>(c.rim.node.size()) : 0;
  d.index.assign(2 + 2 * n_rim, -1);
  d.gap.resize(2 + 2 * n_rim);
  d.slip.resize(2 + 2 * n_rim);
  for (int a = 0; a < 2; ++a) {
    d.index[a] = c.free_dof[a];
    d.gap(a) = normal(a);
    d.slip(a) = c.tangent(a);
  }
  for (Index k = 0; k < n_rim; ++k)
    for (int a = 0; a < 2; ++a) {
      d.index[2 + 2 * k + a] = p.n_free() + 2 * c.rim.node[k] + a;
      d.gap(2 + 2 * k + a) = c.rim.gap_weight[k](a);
      d.slip(2 + 2 * k + a) = c.rim.slip_weight[k](a);
    }
}

// Contact forces of candidate c at x (the rim at the problem's rim displacements) and,
// optionally, the tangent block d(-f)/dz_local of the forces on its local unknowns (LocalDofs),
// f = F_N dgap + F_T dslip: on the node F_N n + F_T t. With `frozen`, the node keeps that status
// (and slip direction) whatever x: open nodes carry no force, closed ones a bilateral normal
// penalty (also in tension), so the system is smooth for Newton; the caller updates the statuses
// between solves.
NodeContact contact_state(const IncrementProblem& p, const ContactCandidate& c, const Stiffness& k, const VecX& x,
                          const LocalDofs& d, MatX* block, const NodeContact* frozen = nullptr) {
  NodeContact s;
  const Vec2 u = p.increment(c, x);
  s.gap = p.gap_for(c, u);
  s.slip = p.slip_for(c, u);
  if (block) block->setZero(d.gap.size(), d.gap.size());
  if (frozen ? frozen->status == ContactStatus::Open : s.gap >= 0.0) return s;  // open: no force
  s.normal_force = -k.normal * s.gap;
  const Real mu = p.roller().friction;
  if (block) {
    *block += k.normal * d.gap * d.gap.transpose();
    block->topLeftCorner<2, 2>() -= p.gap_curvature(c, u, s.normal_force);
  }
  if (mu == 0.0) {
    s.status = ContactStatus::Slip;
    return s;
  }
  const Real trial = c.tangential_force - k.tangential * s.slip;
  const Real bound = mu * s.normal_force;
  const bool stick = frozen ? frozen->status == ContactStatus::Stick : std::abs(trial) <= bound;
  if (stick) {
    s.tangential_force = trial;
    s.status = ContactStatus::Stick;
    if (block) *block += k.tangential * d.slip * d.slip.transpose();
  } else {
    const Real sign = (frozen ? frozen->tangential_force : trial) >= 0.0 ? 1.0 : -1.0;
    s.tangential_force = sign * bound;
    s.status = ContactStatus::Slip;
    if (block) *block += mu * k.normal * sign * d.slip * d.gap.transpose();  // unsymmetric
  }
  return s;
}

// Residual r = dPi/dz - (contact forces) on z = [x, w] and, when asked, its Jacobian, with the
// contact of every candidate at z; or why the strip cannot take x. The elastic roller's rim adds
// K w to its rows. The value's force scale is the larger of the strip's and the contact forces';
// its round-off floor is the residual that round-off alone produces: the gap |x - c| - R of a node
// at distance rho from the centre carries an absolute error ~ eps rho, which the penalty turns
// into a force error ~ eps rho kN. Tolerances below it cannot be met.
Expected<ObjectiveValue> evaluate(IncrementProblem& p, const std::vector<Stiffness>& k, const VecX& z, VecX& r,
                                  SparseMatrix* jacobian, std::vector<NodeContact>& contact,
                                  const std::vector<NodeContact>* frozen = nullptr) {
  const Index n = p.n_free(), n_rim = p.n_rim();
  VecX strip_part;  // the strip's free dofs of z, copied only when the rim follows them
  if (n_rim > 0) {
    strip_part = z.head(n);
    p.set_rim_displacement(z.tail(n_rim));
  }
  const VecX& x = n_rim > 0 ? strip_part : z;
  VecX strip_r;
  const Expected<ObjectiveValue> strip = p.strip_energy(x, &strip_r, jacobian);
  if (!strip) return strip;
  r.resize(n + n_rim);
  r.head(n) = strip_r;
  std::vector<Triplet> rim_entries;
  if (n_rim > 0) {
    const MatX& kr = p.rim()->stiffness;
    r.tail(n_rim) = kr * z.tail(n_rim);
    if (jacobian) {
      jacobian->conservativeResize(n + n_rim, n + n_rim);
      for (Index j = 0; j < n_rim; ++j)
        for (Index i = 0; i < n_rim; ++i) rim_entries.emplace_back(n + i, n + j, kr(i, j));
    }
  }
  contact.assign(p.candidates().size(), NodeContact{});
  ObjectiveValue value;
  // Armstrong-Frederick's consistent tangent is unsymmetric (docs/model.md, Hardening laws).
  value.symmetric = !p.strip_model().has_recovery();
  Real contact_norm2 = 0.0, floor2 = 0.0;
  MatX block;
  LocalDofs d;
  for (std::size_t i = 0; i < p.candidates().size(); ++i) {
    const ContactCandidate& c = p.candidates()[i];
    fill_local_dofs(p, c, p.normal(c, x), d);
    NodeContact& s = contact[i];
    s = contact_state(p, c, k[i], x, d, jacobian ? &block : nullptr, frozen ? &(*frozen)[i] : nullptr);
    const bool rim = d.index.size() > 2;
    if (s.status == ContactStatus::Open && !rim) continue;
    // A rim's entries stay in the pattern while open (as zeros): Newton's pattern is fixed within a solve.
    const int n_local = static_cast<int>(d.index.size());
    for (int a = 0; a < n_local; ++a) {
      if (d.index[a] < 0) continue;
      r(d.index[a]) -= s.normal_force * d.gap(a) + s.tangential_force * d.slip(a);
      if (!jacobian) continue;
      for (int b = 0; b < n_local; ++b) {
        if (d.index[b] < 0) continue;
        if (a < 2 && b < 2)
          jacobian->coeffRef(d.index[a], d.index[b]) += block(a, b);
        else
          rim_entries.emplace_back(d.index[a], d.index[b], block(a, b));
      }
    }
    if (s.status == ContactStatus::Open) continue;
    const Real floor_i =
        10.0 * std::numeric_limits<Real>::epsilon() * k[i].normal * (p.position(c, x) - p.roller().end.centre).norm();
    floor2 += floor_i * floor_i;
    contact_norm2 += (s.normal_force * d.gap.head(2) + s.tangential_force * d.slip.head(2)).squaredNorm();
    if (s.status == ContactStatus::Slip && p.roller().friction > 0.0) value.symmetric = false;
  }
  if (jacobian && !rim_entries.empty()) {
    SparseMatrix extra(n + n_rim, n + n_rim);
    extra.setFromTriplets(rim_entries.begin(), rim_entries.end());
    *jacobian += extra;
  }
  value.force_scale = std::max(strip->force_scale, std::sqrt(contact_norm2));
  value.roundoff_floor = std::sqrt(floor2);
  return value;
}

// The penalty equations at fixed stiffnesses (and, with `frozen`, fixed statuses) as Newton sees
// them. Newton evaluates the Jacobian at every iterate it accepts, so the contact kept from the
// last such evaluation is the contact at Newton's last iterate.
class PenaltyEquations final : public NewtonObjective {
 public:
  PenaltyEquations(IncrementProblem& problem, const std::vector<Stiffness>& k, const std::vector<NodeContact>* frozen)
      : problem_(problem), k_(k), frozen_(frozen) {}
  Expected<ObjectiveValue> evaluate(const VecX& x, VecX* r, SparseMatrix* jacobian) override {
    if (!jacobian) return roller::evaluate(problem_, k_, x, *r, nullptr, trial_contact_, frozen_);
    return roller::evaluate(problem_, k_, x, *r, jacobian, contact_, frozen_);
  }
  std::vector<NodeContact> take_contact() { return std::move(contact_); }

 private:
  IncrementProblem& problem_;
  const std::vector<Stiffness>& k_;
  const std::vector<NodeContact>* frozen_;
  std::vector<NodeContact> contact_, trial_contact_;
};

// The residual and the contact at x, where no step can be shortened (the start, a Newton solve's
// solution): a strip that cannot take x ends the solve with its NumericalError (the driver cuts
// the step).
ObjectiveValue evaluate_or_throw(IncrementProblem& p, const std::vector<Stiffness>& k, const VecX& x, VecX& r,
                                 std::vector<NodeContact>& contact) {
  const Expected<ObjectiveValue> value = evaluate(p, k, x, r, nullptr, contact);
  if (!value) throw NumericalError(value.error());
  return *value;
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

}  // namespace

PenaltyBackend::PenaltyBackend(ContactOptions options, NewtonOptions newton)
    : options_(std::move(options)), newton_(newton) {}

void PenaltyBackend::residual(IncrementProblem& problem, const VecX& x, VecX& r, SparseMatrix* jacobian) const {
  const auto k = penalty_stiffnesses(problem, options_.penalty.factor, options_.penalty.tangential_factor);
  std::vector<NodeContact> contact;
  const Expected<ObjectiveValue> value = evaluate(problem, k, x, r, jacobian, contact);
  if (!value) throw NumericalError(value.error());
}

// One Newton solve at fixed penalty stiffnesses, from x (updated in place): Newton on the
// equilibrium equations with a residual merit (once friction slips no energy exists to backtrack on).
BackendResult PenaltyBackend::newton_stage(IncrementProblem& problem, const std::vector<Stiffness>& k, VecX& x,
                                           Real tolerance, const std::vector<NodeContact>* frozen) {
  NewtonOptions options = newton_;
  options.residual_tolerance = tolerance;
  PenaltyEquations equations(problem, k, frozen);
  const NewtonReport newton = newton_solver_.minimise(equations, x, options, NewtonMerit::Residual);
  BackendResult result = BackendResult::of(newton, x);
  result.contact = equations.take_contact();
  if (!newton.converged()) {
    result.message =
        fmt::format("penalty Newton: {}; or a smaller contact.penalty.factor, or the ipopt backend", newton.message);
  } else if (newton.at_roundoff_floor && newton.residual > kMaxRoundoffResidual) {
    // The round-off floor grows with the penalty (eps |x - c| kN per node). Above
    // kMaxRoundoffResidual of the force scale the penalty is too stiff for double precision and
    // the contact forces are round-off noise (measured, docs/stability.md: Z1 at factor 1e12 was
    // accepted at |r|/F ~ 1.8 with the roller force 28 % off): stop with the cause instead of
    // accepting the increment.
    result.status = Termination::LimitReached;
    result.message = fmt::format(
        "penalty Newton: the penalty is too stiff for double precision: round-off in the gaps "
        "alone leaves |r|/F = {:.2e} (> {:.0e}), the contact forces are not resolved; use a "
        "smaller contact.penalty.factor (now {:.3g}) or the ipopt backend",
        newton.residual, kMaxRoundoffResidual, options_.penalty.factor);
  }
  return result;
}

BackendResult PenaltyBackend::do_solve(IncrementProblem& problem, const VecX& x0) {
  // An elastic roller's rim displacements are unknowns after the strip's, from the start's.
  const Index n = problem.n_free(), n_rim = problem.n_rim();
  VecX z0(n + n_rim);
  z0 << x0, problem.rim_start();
  BackendResult result = solve_unknowns(problem, z0);
  if (n_rim == 0) return result;
  result.rim = result.x.tail(n_rim);
  result.x.conservativeResize(n);
  problem.set_rim_displacement(result.rim);
  return result;
}

BackendResult PenaltyBackend::solve_unknowns(IncrementProblem& problem, const VecX& x0) {
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
    VecX residual;
    std::vector<NodeContact> natural;
    evaluate_or_throw(problem, k_target, x, residual, natural);
    std::vector<NodeContact> status = natural;
    for (int pass = 1; pass <= kMaxActiveSetPasses; ++pass) {
      BackendResult r = newton_stage(problem, k_target, x, newton_.residual_tolerance, &status);
      spent += r.counters;
      if (!r.converged()) break;
      const ObjectiveValue at_x = evaluate_or_throw(problem, k_target, x, residual, natural);
      bool same = true;
      for (std::size_t i = 0; i < status.size() && same; ++i)
        same = natural[i].status == status[i].status &&
               (natural[i].status != ContactStatus::Slip ||
                (natural[i].tangential_force >= 0.0) == (status[i].tangential_force >= 0.0));
      if (same) {
        r.counters = spent;
        r.contact = natural;
        r.residual = residual.norm() / std::max(at_x.force_scale, 1e-300);
        r.details.fill<PenaltyDetails>().active_set_passes = pass;
        return r;
      }
      // Update; a slip that reverses its direction goes through stick first (otherwise two
      // nodes near the no-slip point can flip back and forth for ever).
      for (std::size_t i = 0; i < status.size(); ++i) {
        const bool reversed = status[i].status == ContactStatus::Slip && natural[i].status == ContactStatus::Slip &&
                              problem.roller().friction > 0.0 &&
                              (natural[i].tangential_force >= 0.0) != (status[i].tangential_force >= 0.0);
        status[i] = natural[i];
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
