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
// Elastic roller (IncrementProblem::rim). Its rim displacements w follow the condensed variables in
// the NLP (RimObjective: 1/2 w^T K w, exactly quadratic, so w itself and not a step), and the line
// search moves them with the strip (docs/model.md, Elastic roller).
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
//
// This file: the quadratic model, the condensation and the working set; the outer loop is
// CondensedSolve (condensed_solve.cpp).
#include "ipopt_condensed.hpp"

#include <cmath>
#include <vector>

namespace roller::ipopt_detail {

namespace {

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

std::vector<int> grown_working_set(const IncrementProblem& problem, const VecX& x, Real length_scale,
                                   const std::vector<int>& old) {
  return working_set(problem, x, kReach * length_scale, old);
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

}  // namespace roller::ipopt_detail
