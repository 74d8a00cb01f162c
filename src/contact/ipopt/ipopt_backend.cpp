// The interior-point contact backend (docs/model.md, "Contact" and "Friction"). Files:
// nlp_contact_rows (gap and slip rows, friction terms), contact_tnlp (the one Ipopt adapter),
// friction_passes (the Coulomb fixed point), ipopt_full and ipopt_condensed with condensed_solve
// (the formulations),
// ipopt_common (Ipopt set-up, scales, status messages, the report), ipopt_testing (the tests' hooks),
// this file (the facade).
//
// The NLP (variables, objective, constraints, exact derivatives, forces), its scaling, Ipopt's
// options and why, warm starts and the status of each candidate: docs/model.md, "The interior-point
// backend's NLP in detail". strip_energy may fail (an inverted element at a trial
// point): eval_f/eval_grad_f return false so that Ipopt cuts its step; eval_h returning false ends
// the solve (Ipopt cannot recover from that), reported with the cause.
#include "roller/contact/ipopt_backend.hpp"

#include <stdexcept>

#include <fmt/format.h>
#include <IpIpoptApplication.hpp>

#include "condensed_solve.hpp"
#include "friction_passes.hpp"
#include "ipopt_common.hpp"
#include "ipopt_full.hpp"
#include "roller/core/error.hpp"

namespace roller {

using namespace ipopt_detail;

IpoptBackend::IpoptBackend(ContactOptions options, LinearSolverOptions linear)
    : options_(std::move(options)), condenser_(linear) {
  std::string why;
  if (!options_.ipopt.is_valid(&why)) throw InputError(why);
  if (!options_.ipopt.raw.empty()) {
    // Validate the pass-through options before any step is computed.
    Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
    set(*app, "sb", std::string("yes"));
    set(*app, "print_level", 0);
    apply_raw_options(*app, options_.ipopt.raw);
  }
}

BackendResult IpoptBackend::do_solve(IncrementProblem& problem, const VecX& x0) {
  if (problem.n_free() == 0) {
    BackendResult r;
    r.status = Termination::Converged;
    r.x = x0;
    for (const auto& c : problem.candidates()) {
      NodeContact nc;
      nc.gap = problem.gap(c, x0);
      nc.slip = problem.slip(c, x0);
      r.contact.push_back(nc);
    }
    r.message = "no free dofs: nothing to solve";
    return r;
  }
  // The regularized friction's curvature in an elastic roller's rim displacements is not built:
  // the full formulation says so.
  const bool regularized_rim =
      problem.rim() && options_.ipopt.friction == IpoptFriction::Regularized && problem.roller().friction > 0.0;
  if (options_.ipopt.formulation == IpoptFormulation::Full || regularized_rim) return solve_full(problem, x0, options_);
  CondensedOutcome condensed = CondensedSolve(problem, options_, condenser_).run(x0);
  if (problem.rim() && condensed.result.rim.size() > 0) problem.set_rim_displacement(condensed.result.rim);
  // Factors are kept only for the next increment's same tangent, and never beside the full formulation's.
  if (!problem.strip_tangent_is_constant() || condensed.formulation_failed) condenser_.release();
  // The full formulation has no roller variable: a suspended roller's failure goes back to the
  // driver, which couples the suspension by passes with the roller placed instead.
  if (!condensed.formulation_failed || problem.roller_potential()) return std::move(condensed.result);
  // The condensed formulation itself failed (singular interior tangent, no descent, the
  // linearisations ran out): the full formulation solves the increment from the same start.
  BackendResult full = solve_full(problem, x0, options_);
  full.counters += condensed.result.counters;
  full.details.fill<IpoptDetails>().condensed_fallback = true;
  full.message += fmt::format(" [full formulation after the condensed one failed: {}]", condensed.result.message);
  return full;
}

}  // namespace roller
