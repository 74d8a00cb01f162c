// The condensed formulation of the interior-point backend (contact.ipopt.formulation =
// "condensed", the default).
//
// Why. Only the contact candidates carry constraints; every other dof of the strip enters the
// increment through its (quadratic) strain energy alone. The "full" formulation still gives Ipopt
// every free dof, so each interior-point iteration factorises the whole KKT matrix (Hertz: 9-15
// of them per increment, Z1's rolling increment 55-170 with the friction fixed point). Here the
// strip is condensed onto the contact dofs once per linearisation, and Ipopt solves a dense NLP of
// a few hundred unknowns: an increment costs one sparse factorisation per linearisation.
//
// Outer loop (sequential quadratic programming on the strip, exact constraints): at x_k, with
// g = grad Pi(x_k) and K = Hess Pi(x_k) (the consistent tangent K_eff with the geometric and
// Houbolt mass terms), the strip's energy change is the quadratic model q(d) = g.d + d.K.d/2.
// Split d = (d_I, d_C), C = the free dofs of the working candidates. For given d_C the model's
// minimum over d_I is d_I = -K_II^-1 (g_I + K_IC d_C), which leaves
//   q_C(d_C) = gc.d_C + d_C.S.d_C/2,   S = K_CC - K_CI K_II^-1 K_IC,   gc = g_C - K_CI K_II^-1 g_I,
// S from one MUMPS factorisation with a Schur complement (solver/mumps_factorization.hpp), gc
// from one interior solve. Ipopt then solves, with the friction fixed point around it
// (friction_passes.hpp),
//   min q_C(d_C) + friction   s.t.  |x_i^n + u_i(x_k + d) - c| - R >= 0   (exact circle)
// with the contact rows of the full formulation (nlp_contact_rows.hpp: the node increment of a
// working candidate is its increment at x_k plus its entries of d_C), the same scaling and
// options, and a dense Hessian S + sum lambda_i (I - n n^T)/rho. A second interior solve gives d_I. Because the gap of
// a node depends on that node's dofs only, the condensation is exact: for an elastic strip with small kinematics
// (Hertz) one linearisation solves the increment.
//
// Step and convergence. x_{k+1} = x_k + alpha d, alpha from backtracking on the l1 merit
// Pi + friction + nu sum max(0, -g_i) (nu = 2 max F_N), alpha = 1 whenever the predicted decrease
// is at round-off level. The increment has converged when a full step was taken, the friction
// fixed point converged on that linearisation, and the model was exact to tol:
//   |grad Pi(x_{k+1}) - g - K d|_inf <= tol F_ref
// (the inner NLP holds grad q = contact forces to Ipopt's tol, so grad Pi(x_{k+1}) = contact
// forces to tol as well: the full problem's KKT conditions).
// The full step's trial point is evaluated with its tangent (a strip whose tangent changes): when
// it is taken and the increment goes on, that is the next linearisation, and the strip is not
// evaluated twice at one point.
//
// Free roller height (IncrementProblem::free_roller: a suspended or force-loaded roller). The
// roller's vertical offset w is one more unknown: the NLP gets its step dw as a last variable (the contact rows see the
// node's increment relative to the roller, u - dw e_y) and the model its spring P(w + dw) - P(w), which is exact, so
// the model error stays the strip's. The line search moves (x, w) together. One solve then finds the strip, the contact
// and the suspension in equilibrium, where the driver's coupling loop (dynamics/suspension.hpp) needs three or four
// contact solves.
//
// Working set. Candidates with a free dof whose gap at the start vector is within kReach l_step
// (l_step the increment's length scale, ipopt_common.hpp), or that carried a normal force in the
// previous increment. After each step every other candidate's gap is checked; a penetrating one
// joins the set (with every candidate within kReach l_step of the roller then) and the increment
// goes on with a new linearisation. So the constraint set of the solution is the full one.
//
// Constant tangent (a linear elastic strip with small kinematics, StripModel::tangent_is_constant).
// K is then the same matrix at every linearisation of every increment, so it is factorised once
// with its Schur complement on every candidate's free dofs and the factors stay in the backend;
// each working set is reduced from that Schur complement (solver/schur_condenser.hpp), and an
// increment costs no factorisation at all. Hertz at 2.9e5 dofs: 0.9 s a step instead of 2.4 s.
//
// Failure of the formulation (singular K_II, no descent, linearisations ran out) is reported as
// CondensedOutcome::formulation_failed; IpoptBackend then solves the increment with the full
// formulation.
#include "ipopt_condensed.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <IpIpoptApplication.hpp>

#include "friction_passes.hpp"
#include "ipopt_common.hpp"
#include "roller/core/error.hpp"

namespace roller::ipopt_detail {

namespace {

constexpr int kMaxLinearisations = 30;
constexpr int kMaxBacktracks = 12;
// Working-set reach in units of l_step (see the header comment). The dense NLP costs ~m^3 per
// interior-point iteration: with 2 l_step Z1's first rolling increment (a 600 mm roller moving
// 4 mm over a nearly flat strip) took 571 candidates into the set for 47 in contact and spent
// most of its time in Ipopt; with 0.25 l_step 236 candidates; with 0.05 l_step the condensed
// dofs of Z1's rolling increments fall by a third more (944 -> 634 at 4.4e5 dofs, its Ipopt time
// 7.7 -> 2.9 s) and no scene needed a linearisation more for a candidate found penetrating
// outside the set (docs/benchmarks-log.md, "A smaller working set for the contact NLP").
constexpr Real kReach = 0.05;

// Candidates in the working set: a free dof and (gap at x within `reach`, or a normal force in
// the previous increment, or already in).
std::vector<int> working_set(const IncrementProblem& problem, const VecX& x, Real reach, const std::vector<int>& old) {
  const auto& cands = problem.candidates();
  std::vector<char> in(cands.size(), 0);
  for (const int i : old) in[i] = 1;
  std::vector<int> out;
  for (std::size_t i = 0; i < cands.size(); ++i) {
    const ContactCandidate& c = cands[i];
    if (c.free_dof[0] < 0 && c.free_dof[1] < 0) continue;
    if (in[i] || c.normal_force_guess > 0.0 || problem.gap(c, x) <= reach) out.push_back(static_cast<int>(i));
  }
  return out;
}

// Merit of a point: strip energy + friction (with the pass's weights) + nu * penetration.
Real merit(const IncrementProblem& problem, const std::vector<RowMap>& rows, const FrictionTerms& friction, Real energy,
           const VecX& x, Real nu) {
  Real m = energy;
  const auto& cands = problem.candidates();
  for (std::size_t j = 0; j < friction.rows.size(); ++j) {
    const Real s = problem.slip(cands[rows[friction.rows[j]].candidate], x);
    m += friction.weight[j] * (friction.split() ? std::abs(s) : std::sqrt(s * s + friction.eps * friction.eps));
  }
  for (const auto& c : cands)
    if (c.free_dof[0] >= 0 || c.free_dof[1] >= 0) m += nu * std::max(0.0, -problem.gap(c, x));
  return m;
}

CondensedOutcome formulation_failed(BackendResult result, ContactTermination status, std::string message) {
  result.status = status;
  result.message = std::move(message);
  return {std::move(result), true};
}

}  // namespace

bool QuadraticModel::value(const Real* d, Real& f) {
  const auto m = static_cast<Index>(c_.gradient.size());
  const Eigen::Map<const VecX> dv(d, m);
  f = c_.gradient.dot(dv) + 0.5 * dv.dot(c_.schur * dv);
  if (roller_) f += roller_gradient_ * d[m] + 0.5 * roller_->stiffness * d[m] * d[m];
  return true;
}

bool QuadraticModel::gradient(const Real* d, Real* g) {
  const auto m = static_cast<Index>(c_.gradient.size());
  Eigen::Map<VecX>(g, m) = c_.gradient + c_.schur * Eigen::Map<const VecX>(d, m);
  if (roller_) g[m] = roller_gradient_ + roller_->stiffness * d[m];
  return true;
}

void QuadraticModel::hessian_structure(int* row, int* col) const {
  int e = 0;
  for (int r = 0; r < n(); ++r)
    for (int c = 0; c <= r; ++c, ++e) {
      row[e] = r;
      col[e] = c;
    }
}

bool QuadraticModel::hessian_values(const Real* /*d*/, Real obj_factor, Real* values) {
  const auto m = static_cast<int>(c_.gradient.size());
  int e = 0;
  for (int r = 0; r < m; ++r)
    for (int c = 0; c <= r; ++c, ++e) values[e] = obj_factor * c_.schur(r, c);
  if (roller_) {  // the roller's row: no strip coupling, its spring on the diagonal
    for (int c = 0; c < m; ++c, ++e) values[e] = 0.0;
    values[e] = obj_factor * roller_->stiffness;
  }
  return true;
}

std::vector<int> initial_working_set(const IncrementProblem& problem, const VecX& x0, Real length_scale) {
  return working_set(problem, x0, kReach * length_scale, {});
}

SchurCondenser::Outcome condense(const IncrementProblem& problem, const std::vector<int>& working, const VecX& x,
                                 const VecX& g, const SparseMatrix& k, SchurCondenser& condenser, Condensation* out) {
  // The working candidates as NLP rows: their free dofs numbered in order (d_C), their increment at x.
  out->rows.clear();
  out->dofs.clear();
  for (const int i : working) {
    const ContactCandidate& c = problem.candidates()[i];
    RowMap r;
    r.candidate = i;
    r.base = problem.increment(c, x);
    for (int a = 0; a < 2; ++a)
      if (c.free_dof[a] >= 0) {
        r.slot[a] = static_cast<int>(out->dofs.size());
        out->dofs.push_back(c.free_dof[a]);
      }
    out->rows.push_back(r);
  }
  // A constant tangent is factorised once for every candidate's dofs (the working sets to come).
  std::vector<Index> superset = out->dofs;
  if (problem.strip_tangent_is_constant()) {
    superset.clear();
    for (const ContactCandidate& c : problem.candidates())
      for (const Index dof : c.free_dof)
        if (dof >= 0) superset.push_back(dof);
  }
  const SchurCondenser::Outcome outcome = condenser.condense(k, out->dofs, superset, &out->schur);
  if (outcome == SchurCondenser::Outcome::Failed) return outcome;
  const VecX y = condenser.solve_interior(-g);
  const VecX ky = k * y;
  const auto m = static_cast<Index>(out->dofs.size());
  out->gradient.resize(m);
  for (Index s = 0; s < m; ++s) out->gradient(s) = g(out->dofs[s]) + ky(out->dofs[s]);
  return outcome;
}

CondensedOutcome solve_condensed(IncrementProblem& problem, const VecX& x0, const ContactOptions& options,
                                 SchurCondenser& condenser) {
  const IpoptOptions& o = options.ipopt;
  const auto& cands = problem.candidates();
  const std::size_t n_c = cands.size();
  BackendResult result;
  result.x = x0;
  result.contact.assign(n_c, NodeContact{});

  Scales scales;
  VecX x = x0, g;
  SparseMatrix k_eff;
  Real energy = 0.0;
  try {
    const ObjectiveValue start = problem.strip_energy(x, &g, &k_eff);
    energy = start.value;
    scales = increment_scales(problem, x0, start.force_scale);
  } catch (const NumericalError& error) {
    return formulation_failed(result, ContactTermination::Failed,
                              fmt::format("ipopt backend: the strip cannot be evaluated at the start vector ({}); "
                                          "use smaller steps (a larger steps.count, or steps.max_cuts)",
                                          error.what()));
  }
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = make_application(o, scales);
  if (app->Initialize("") != Ipopt::Solve_Succeeded)
    return formulation_failed(result, ContactTermination::Failed, "ipopt backend: Ipopt failed to initialise");

  const Real reach = kReach * scales.length;
  NormalForceFixedPoint fixed_point(problem, o, scales.force);
  // Per candidate, from the last solved pass.
  std::vector<Real> normal(n_c, 0.0), tangential(n_c, 0.0), fbar_used = fixed_point.fbar();
  std::vector<bool> has_friction(n_c, false);
  for (std::size_t i = 0; i < n_c; ++i) {
    normal[i] = std::max(cands[i].normal_force_guess, 0.0);
    tangential[i] = cands[i].tangential_force;
  }
  std::vector<int> working = initial_working_set(problem, x, scales.length);
  // A free roller height: its offset w is the last unknown (header comment, "Free roller height").
  const std::optional<RollerPotential> spring = problem.roller_potential();
  auto roller_energy = [&spring](Real w) { return spring ? spring->energy(w) : 0.0; };
  Condensation cond;
  const int max_passes = fixed_point.iterated() ? o.fixed_point_max : 1;
  // A constant tangent needs no new one at the full step (its increments take one linearisation).
  const bool tangent_changes = !problem.strip_tangent_is_constant();
  int linearisations = 0, passes_last = 0;
  bool converged = false, fixed_point_converged = false;
  Real model_error = 0.0;

  for (int outer = 1; outer <= kMaxLinearisations && !converged; ++outer) {
    linearisations = outer;
    // Condensation of K onto the working candidates' free dofs.
    const SchurCondenser::Outcome condensed = condense(problem, working, x, g, k_eff, condenser, &cond);
    if (condensed == SchurCondenser::Outcome::Failed)
      return formulation_failed(
          result, ContactTermination::Failed,
          fmt::format("ipopt backend (condensed): the strip tangent cannot be factorised on its interior dofs ({}): "
                      "the strip is held against rigid-body motion only through contact",
                      condenser.message()));
    if (condensed == SchurCondenser::Outcome::Factorised) ++result.factorizations;
    const std::vector<RowMap>& rows = cond.rows;
    const std::vector<Index>& dofs = cond.dofs;
    const auto m = static_cast<Index>(dofs.size());

    // Friction fixed point on this linearisation (Tresca passes on the dense NLP). Far from
    // convergence one pass per linearisation suffices (Fbar follows the linearisations); the
    // fixed point is converged once the model is close (model error <= 1e-3).
    fixed_point.restart();
    VecX d_c = VecX::Zero(m);
    FrictionTerms friction;
    Real dw = 0.0;  // the suspended roller's step
    if (m == 0) {   // no working candidate: the strip alone (and the roller hangs free)
      if (spring && !(spring->stiffness > 0.0))
        return formulation_failed(result, ContactTermination::Failed,
                                  "ipopt backend (condensed): the roller carries a prescribed force but touches no "
                                  "candidate: nothing holds it");
      if (spring) dw = -spring->derivative(problem.roller_offset()) / spring->stiffness;
      fixed_point_converged = true;
      std::fill(normal.begin(), normal.end(), 0.0);
      std::fill(tangential.begin(), tangential.end(), 0.0);
      std::fill(has_friction.begin(), has_friction.end(), false);
      result.stats.nlp_variables = 0;
      result.stats.nlp_constraints = 0;
    } else {
      NlpStart start;
      for (const RowMap& r : rows) {
        start.guess.normal.push_back(normal[r.candidate]);
        start.guess.tangential.push_back(tangential[r.candidate]);
      }
      QuadraticModel model = spring ? QuadraticModel(cond, *spring, problem.roller_offset()) : QuadraticModel(cond);
      start.primal = VecX::Zero(model.n());
      const int passes_here = outer > 1 && model_error <= 1e-3 ? max_passes : 1;
      const FrictionPasses passes = solve_friction_passes(*app, model, problem, rows, fixed_point, std::move(start),
                                                          passes_here, o.warm_start, o);
      result.iterations += passes.iterations;
      result.stats.nlp_solves += passes.nlp_solves;
      result.stats.cold_restarts += passes.cold_restarts;
      result.stats.ipopt_time_s += passes.ipopt_time_s;
      result.stats.acceptable_level = result.stats.acceptable_level || passes.acceptable_level;
      if (passes.status != ContactTermination::Converged) {
        // Ipopt's own failure on the small NLP: reported as such (the driver cuts the step), no
        // fall-back to the full formulation, which would meet the same NLP.
        result.status = passes.status;
        result.message =
            fmt::format("{} (condensed NLP, linearisation {}, friction pass {})", passes.message, outer, passes.passes);
        return {std::move(result), false};
      }
      passes_last = passes.passes;
      fixed_point_converged = passes.fixed_point_converged;
      normal = passes.normal;
      tangential = passes.tangential;
      has_friction = passes.has_friction;
      fbar_used = passes.fbar;
      friction = passes.friction;
      d_c = passes.last.z.head(m);
      if (spring) dw = passes.last.z(m);
      result.stats.nlp_variables = passes.nlp_variables;
      result.stats.nlp_constraints = passes.nlp_constraints;
    }
    Real fn_max = 0.0;
    for (const Real f : normal) fn_max = std::max(fn_max, f);

    // The whole step: d_C from Ipopt, d_I from the interior solve.
    VecX e = VecX::Zero(x.size());
    for (Index s = 0; s < m; ++s) e(dofs[s]) = d_c(s);
    const VecX ke = k_eff * e;
    VecX d = condenser.solve_interior(-g - ke) + e;
    const VecX kd = k_eff * d;
    k_eff = SparseMatrix();  // the next tangent comes with the full step or anew: one K in memory
    const Real w0 = problem.roller_offset();
    const Real model_change = g.dot(d) + 0.5 * d.dot(kd) + roller_energy(w0 + dw) - roller_energy(w0);

    // Backtracking on the merit function.
    const Real nu = 2.0 * std::max(fn_max, 1e-6 * scales.force);
    const Real phi0 = merit(problem, rows, friction, energy + roller_energy(w0), x, nu);
    Real pred = -model_change;
    {
      VecX x1 = x + d;
      pred += merit(problem, rows, friction, 0.0, x, nu);
      problem.move_roller(w0 + dw);
      pred -= merit(problem, rows, friction, 0.0, x1, nu);
      problem.move_roller(w0);
    }
    const Real roundoff = 1e-10 * (std::abs(energy) + scales.force * scales.length);
    Real alpha = 1.0;
    VecX x_new, g_new;
    SparseMatrix k_full_step;  // the tangent at the full step, the next linearisation's if it is taken
    Real energy_new = 0.0;
    bool accepted = false;
    std::string evaluation_error;
    Real next_alpha = 0.5;
    for (int b = 0; b <= kMaxBacktracks && !accepted; ++b, alpha = next_alpha) {
      next_alpha = 0.5 * alpha;
      x_new = x + alpha * d;
      try {
        energy_new =
            problem.strip_energy(x_new, &g_new, alpha == 1.0 && tangent_changes ? &k_full_step : nullptr).value;
      } catch (const NumericalError& error) {
        evaluation_error = error.what();
        continue;
      }
      problem.move_roller(w0 + alpha * dw);
      const Real phi = merit(problem, rows, friction, energy_new + roller_energy(w0 + alpha * dw), x_new, nu);
      accepted = std::isfinite(phi) &&
                 (pred <= roundoff || phi <= phi0 - 1e-4 * alpha * pred || (alpha == 1.0 && phi <= phi0 + roundoff));
      // Minimiser of the parabola through phi0 (slope -pred) and phi(alpha), kept in [0.1, 0.9] alpha.
      if (!accepted && std::isfinite(phi) && pred > 0.0) {
        const Real curvature = phi - phi0 + alpha * pred;
        if (curvature > 0.0) next_alpha = std::clamp(0.5 * pred * alpha * alpha / curvature, 0.1 * alpha, 0.9 * alpha);
      }
      if (accepted) break;
    }
    if (!accepted) {
      problem.move_roller(w0);
      return formulation_failed(result, ContactTermination::LimitReached,
                                fmt::format("ipopt backend (condensed): no descent along the step of linearisation "
                                            "{}{}; use smaller steps (a larger steps.count, or steps.max_cuts)",
                                            outer, evaluation_error.empty() ? "" : " (" + evaluation_error + ")"));
    }
    model_error = (g_new - g - alpha * kd).lpNorm<Eigen::Infinity>() / scales.force;
    x = x_new;
    g = g_new;
    energy = energy_new;

    // Candidates outside the working set must not penetrate.
    bool grew = false;
    {
      std::vector<char> in(n_c, 0);
      for (const int i : working) in[i] = 1;
      for (std::size_t i = 0; i < n_c && !grew; ++i)
        if (!in[i] && (cands[i].free_dof[0] >= 0 || cands[i].free_dof[1] >= 0) && problem.gap(cands[i], x) < 0.0)
          grew = true;
      if (grew) working = working_set(problem, x, reach, working);
    }
    converged = alpha == 1.0 && !grew && fixed_point_converged && model_error <= o.tol;
    if (!converged && alpha == 1.0 && k_full_step.size() > 0) {
      k_eff = std::move(k_full_step);  // evaluated with the full step: energy and g are x's already
    } else if (!converged) {
      try {
        energy = problem.strip_energy(x, &g, &k_eff).value;
      } catch (const NumericalError& error) {
        return formulation_failed(result, ContactTermination::Failed,
                                  fmt::format("ipopt backend (condensed): the strip tangent cannot be evaluated ({}); "
                                              "use smaller steps (a larger steps.count, or steps.max_cuts)",
                                              error.what()));
      }
    }
  }
  result.x = x;
  if (spring) result.roller_offset = problem.roller_offset();
  result.stats.fixed_point_iterations = passes_last;  // Coulomb passes on the last linearisation
  result.stats.linearisations = linearisations;
  result.stats.condensed_dofs = static_cast<int>(cond.dofs.size());
  if (!report_increment(problem, x, normal, tangential, fbar_used, has_friction, scales, &result))
    return {std::move(result), true};
  if (!converged) {
    if (!fixed_point_converged) {
      result.status = ContactTermination::LimitReached;
      result.message = fixed_point.failure_message(result.stats.nlp_solves);
      return {std::move(result), false};
    }
    return formulation_failed(result, ContactTermination::LimitReached,
                              fmt::format("ipopt backend (condensed): {} linearisations without convergence (model "
                                          "error {:.3g} against contact.ipopt.tol = {:g}); use smaller steps (a larger "
                                          "steps.count, or steps.max_cuts)",
                                          kMaxLinearisations, model_error, o.tol));
  }
  result.status = ContactTermination::Converged;
  const int nlp_solves = result.stats.nlp_solves;
  result.message =
      fmt::format("Ipopt converged: {} linearisation{}, {} interior-point iterations ({} pass{})", linearisations,
                  linearisations == 1 ? "" : "s", result.iterations, nlp_solves, nlp_solves == 1 ? "" : "es");
  return {std::move(result), false};
}

}  // namespace roller::ipopt_detail
