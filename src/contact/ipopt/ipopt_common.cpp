#include "ipopt_common.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "roller/core/error.hpp"
#include "roller/solver/dense_kkt_solver.hpp"

namespace roller::ipopt_detail {

void set(Ipopt::IpoptApplication& app, const std::string& name, const std::string& value) {
  if (!app.Options()->SetStringValue(name, value))
    throw std::logic_error(fmt::format("ipopt backend: Ipopt rejected option {} = {}", name, value));
}
void set(Ipopt::IpoptApplication& app, const std::string& name, Real value) {
  if (!app.Options()->SetNumericValue(name, value))
    throw std::logic_error(fmt::format("ipopt backend: Ipopt rejected option {} = {}", name, value));
}
void set(Ipopt::IpoptApplication& app, const std::string& name, int value) {
  if (!app.Options()->SetIntegerValue(name, value))
    throw std::logic_error(fmt::format("ipopt backend: Ipopt rejected option {} = {}", name, value));
}

void apply_raw_options(Ipopt::IpoptApplication& app, const std::vector<RawIpoptOption>& raw) {
  for (const RawIpoptOption& r : raw) {
    bool ok = false;
    switch (r.kind) {
      case RawIpoptOption::Kind::Integer: ok = app.Options()->SetIntegerValue(r.name, std::stoi(r.text)); break;
      case RawIpoptOption::Kind::Number: ok = app.Options()->SetNumericValue(r.name, std::stod(r.text)); break;
      case RawIpoptOption::Kind::String: ok = app.Options()->SetStringValue(r.name, r.text); break;
    }
    if (!ok)
      throw InputError(
          fmt::format("contact.ipopt.options.{} = {}: Ipopt rejects it (unknown option, wrong type "
                      "or value out of range; see Ipopt's option list)",
                      r.name, r.text));
  }
}

void set_warm_start(Ipopt::IpoptApplication& app, bool on) {
  set(app, "warm_start_init_point", std::string(on ? "yes" : "no"));
  set(app, "mu_init", on ? 1e-6 : 0.1);
  for (const char* name : {"warm_start_bound_push", "warm_start_bound_frac", "warm_start_slack_bound_push",
                           "warm_start_slack_bound_frac", "warm_start_mult_bound_push"})
    set(app, name, on ? 1e-6 : 1e-3);
}

Scales increment_scales(const IncrementProblem& problem, const VecX& x0, Real strip_force_scale) {
  const RollerMotion& r = problem.roller();
  Real l = std::max(r.dc().norm(), r.radius * std::abs(r.dphi()));
  const VecX u = problem.full_increment(x0);
  if (u.size() > 0) l = std::max(l, u.lpNorm<Eigen::Infinity>());
  for (const auto& c : problem.candidates()) l = std::max(l, -problem.gap(c, x0));
  Scales s;
  s.length = std::max(l, 1e-9 * r.radius);
  s.force = std::max(strip_force_scale, problem.plane_strain_modulus() * s.length);
  return s;
}

Ipopt::SmartPtr<Ipopt::IpoptApplication> make_application(const IpoptOptions& o, const Scales& scales) {
  dense_kkt::register_dense_kkt_solver();
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  app->RethrowNonIpoptException(true);
  set(*app, "sb", std::string("yes"));
  set(*app, "print_level", o.print_level);
  set(*app, "linear_solver", std::string("mumps"));
  set(*app, "hessian_approximation", std::string("exact"));
  set(*app, "tol", o.tol);
  set(*app, "max_iter", o.max_iter);
  set(*app, "mu_strategy", std::string(enum_name(o.mu_strategy)));
  // Small NLPs (a few to a few hundred variables, solved hundreds of times per run) pay per
  // linear solve: Debian's MUMPS 5.5 walks its whole structure on every call. The probing
  // (Mehrotra) barrier oracle needs one extra solve per iteration where the quality function
  // needs several, and no forced refinement step saves a solve whenever the first is accurate
  // (Ipopt still refines when the residual asks for it). Measured: docs/benchmarks-log.md, "The
  // thesis scenes at refine 1".
  set(*app, "mu_oracle", std::string("probing"));
  set(*app, "min_refinement_steps", 0);
  set(*app, "obj_scaling_factor", 1.0 / scales.force);
  // The unscaled dual safety tolerance (default 1 N/mm) must not be stricter than tol on the
  // scaled problem for large force scales. The unscaled complementarity max F_N g [N mm] is held
  // to tol F_ref, so that the reported complementarity (max F_N g / F_ref) ends below tol.
  set(*app, "dual_inf_tol", std::max(1.0, 100.0 * o.tol * scales.force));
  set(*app, "compl_inf_tol", o.tol * scales.force);
  set(*app, "bound_relax_factor", 0.0);
  set(*app, "honor_original_bounds", std::string("yes"));
  set(*app, "line_search_method", std::string("penalty"));  // docs/model.md, the NLP in detail
  apply_raw_options(*app, o.raw);
  return app;
}

// Auto: the dense solver up to this bound on Ipopt's KKT dimension (n + 2m: the variables, the
// constraints' multipliers and the inequalities' slacks). Measured on Z1 at refine 2-8, the
// same Ipopt iterations with either solver: dense took 0.47 of MUMPS's time inside Ipopt at
// ~25 condensed dofs, 0.7 at ~55, 1.0 at ~80 and 1.4 at ~110 (docs/benchmarks-log.md, "A dense
// solver for Ipopt's small KKT systems").
constexpr int kDenseKktMax = 200;

std::string kkt_linear_solver(KktSolver choice, int n, int m) {
  const bool dense = choice == KktSolver::Dense || (choice == KktSolver::Auto && n + 2 * m <= kDenseKktMax);
  return dense ? "ma27" : "mumps";
}

StatusText map_status(Ipopt::ApplicationReturnStatus s, int iterations, const IpoptOptions& o,
                      const std::string& evaluation_error) {
  using S = Termination;
  const std::string cause =
      evaluation_error.empty() ? "" : fmt::format(" (last evaluation error: {})", evaluation_error);
  switch (s) {
    case Ipopt::Solve_Succeeded:
    case Ipopt::Solved_To_Acceptable_Level: return {S::Converged, ""};
    case Ipopt::Maximum_Iterations_Exceeded:
      return {S::LimitReached,
              fmt::format("Ipopt stopped after {} iterations without reaching contact.ipopt.tol = {:g} "
                          "(contact.ipopt.max_iter = {}); use smaller steps (a larger steps.count, or steps.max_cuts) "
                          "or raise contact.ipopt.max_iter",
                          iterations, o.tol, o.max_iter)};
    case Ipopt::Maximum_CpuTime_Exceeded:
      return {S::LimitReached,
              "Ipopt exceeded its CPU time limit; use smaller steps (a larger steps.count, or steps.max_cuts)"};
    case Ipopt::Restoration_Failed:
      return {S::LimitReached,
              fmt::format("Ipopt's feasibility restoration failed after {} iterations: the roller cannot be "
                          "placed without penetration from this start (or the strip cannot follow it){}; "
                          "use smaller steps (a larger steps.count, or steps.max_cuts)",
                          iterations, cause)};
    case Ipopt::Infeasible_Problem_Detected:
      return {S::LimitReached,
              "Ipopt found the increment locally infeasible: the roller cannot be placed without "
              "penetration (e.g. it presses a node whose dofs are prescribed, or the step is too large "
              "for the curved gap); use smaller steps (a larger steps.count, or steps.max_cuts)"};
    case Ipopt::Search_Direction_Becomes_Too_Small:
      return {S::LimitReached,
              fmt::format("Ipopt's search direction became too small before reaching contact.ipopt.tol = {:g}: "
                          "the tolerance is below what round-off allows for this problem; raise "
                          "contact.ipopt.tol or use smaller steps (a larger steps.count, or steps.max_cuts)",
                          o.tol)};
    case Ipopt::Feasible_Point_Found:
      return {S::LimitReached,
              "Ipopt found a feasible point but not an optimum; use smaller steps (a larger steps.count, or "
              "steps.max_cuts)"};
    case Ipopt::Diverging_Iterates:
      return {S::Failed,
              "Ipopt's iterates diverged (|x| > 1e20): the strip is not held against rigid-body motion "
              "(check the boundary conditions) or the step is far too large"};
    case Ipopt::Error_In_Step_Computation:
      return {S::Failed,
              fmt::format("Ipopt could not solve its Newton system (singular KKT matrix after regularisation){}; "
                          "check the boundary conditions (rigid-body modes) or use smaller steps (a larger "
                          "steps.count, or steps.max_cuts)",
                          cause)};
    case Ipopt::Invalid_Number_Detected:
      return {S::Failed,
              fmt::format("the strip's energy or its derivatives could not be evaluated at an Ipopt iterate{}; "
                          "use smaller steps (a larger steps.count, or steps.max_cuts)",
                          cause)};
    case Ipopt::Not_Enough_Degrees_Of_Freedom:
      return {S::Failed, "Ipopt: more equality constraints than free variables (internal error; please report)"};
    case Ipopt::Invalid_Problem_Definition:
    case Ipopt::Invalid_Option:
      return {S::Failed, "Ipopt rejected the problem definition or an option (internal error; please report)"};
    case Ipopt::Insufficient_Memory: return {S::Failed, "Ipopt/MUMPS ran out of memory; use a coarser mesh"};
    case Ipopt::User_Requested_Stop: return {S::Failed, "Ipopt stopped on request"};
    case Ipopt::Unrecoverable_Exception:
    case Ipopt::NonIpopt_Exception_Thrown:
    case Ipopt::Internal_Error: break;
  }
  return {S::Failed,
          fmt::format("Ipopt failed with an internal error (return status {}){}", static_cast<int>(s), cause)};
}

ContactStatus contact_status(const NodeContact& c, Real open_force, Real bound, Real length) {
  if (c.normal_force <= open_force && c.gap > 0.0) return ContactStatus::Open;
  const Real slip = std::abs(c.slip);
  const bool moves = slip > kNoSlip * length;
  if (bound <= 0.0) return moves ? ContactStatus::Slip : ContactStatus::Stick;
  const bool on_cone = std::abs(c.tangential_force) >= (1.0 - kConeTolerance) * bound;
  return slip > kSlipFraction * length || (on_cone && moves) ? ContactStatus::Slip : ContactStatus::Stick;
}

bool report_increment(IncrementProblem& problem, const VecX& x, const std::vector<Real>& normal,
                      const std::vector<Real>& tangential, const std::vector<Real>& fbar,
                      const std::vector<bool>& has_friction, const Scales& scales, BackendResult* result) {
  const auto& cands = problem.candidates();
  const std::size_t n_c = cands.size();
  const Real mu = problem.roller().friction;
  VecX gradient;
  const Expected<ObjectiveValue> strip = problem.strip_energy(x, &gradient, nullptr);
  if (!strip) {
    result->status = Termination::Failed;
    result->message =
        fmt::format("ipopt backend: the strip cannot be evaluated at Ipopt's solution ({})", strip.error());
    return false;
  }
  const Real force_scale = std::max(strip->force_scale, scales.force);
  Real fn_max = 0.0;
  for (std::size_t i = 0; i < n_c; ++i) fn_max = std::max(fn_max, normal[i]);
  const Real no_force = open_force(fn_max, scales.force);
  Real complementarity = 0.0, violation = 0.0;
  VecX r = gradient;
  result->contact.assign(n_c, NodeContact{});
  for (std::size_t i = 0; i < n_c; ++i) {
    const ContactCandidate& c = cands[i];
    NodeContact& nc = result->contact[i];
    nc.normal_force = std::max(normal[i], 0.0);
    nc.tangential_force = tangential[i];
    nc.gap = problem.gap(c, x);
    nc.slip = problem.slip(c, x);
    nc.status = contact_status(nc, no_force, has_friction[i] ? mu * fbar[i] : 0.0, scales.length);
    const Vec2 f = contact_force(nc.normal_force, nc.tangential_force, problem.normal(c, x), c.tangent);
    for (int k = 0; k < 2; ++k)
      if (c.free_dof[k] >= 0) r(c.free_dof[k]) -= f(k);
    if (c.free_dof[0] >= 0 || c.free_dof[1] >= 0) {
      complementarity = std::max(complementarity, std::abs(nc.normal_force * nc.gap));
      violation = std::max(violation, -nc.gap);
    }
  }
  result->residual = r.norm() / force_scale;
  IpoptDetails& details = result->details.fill<IpoptDetails>();
  details.complementarity = complementarity / force_scale;
  details.constraint_violation = violation;
  return true;
}

}  // namespace roller::ipopt_detail
