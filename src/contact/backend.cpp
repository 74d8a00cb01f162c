#include "roller/contact/backend.hpp"

#include <chrono>

#include <fmt/format.h>

#include "roller/assembly/recovery_iteration.hpp"

namespace roller {

const char* to_string(ContactStatus s) {
  switch (s) {
    case ContactStatus::Open: return "open";
    case ContactStatus::Stick: return "stick";
    case ContactStatus::Slip: return "slip";
  }
  return "?";
}

std::string BackendResult::brief_report() const {
  std::string s = fmt::format("{} in {} iterations, |r|/F {:.2e}, max penetration {:.2e} mm",
                              converged() ? "converged" : "FAILED", counters.iterations, residual, max_penetration);
  const std::string brief = details.brief();
  if (!brief.empty()) s += ", " + brief;
  if (!converged()) s += ": " + message;
  return s;
}

BackendResult BackendResult::of(const NewtonReport& newton, VecX x) {
  BackendResult r;
  r.status = newton.status;
  r.message = newton.message;
  r.x = std::move(x);
  r.counters = newton.counters;
  r.residual = newton.residual;
  return r;
}

// Armstrong-Frederick's recovery has no potential: a minimising backend solves with it frozen,
// until the frozen multipliers are the solution's (docs/model.md, Hardening laws). Each solve
// starts from the previous one's solution; the counters add up.
BackendResult ContactBackend::solve_settling_recovery(IncrementProblem& problem, const VecX& x0) {
  RecoveryIteration recovery(problem.strip_model(), recovery_tolerance());
  BackendResult r;
  SolveCounters counters;
  BackendDetails details;
  VecX start = x0;
  const Termination end = recovery.iterate([&]() -> std::optional<VecX> {
    r = do_solve(problem, start);
    counters += r.counters;
    details.add(r.details);
    if (!r.converged()) return std::nullopt;
    start = r.x;
    return problem.full_increment(r.x);
  });
  if (end == Termination::LimitReached) {
    r.status = end;
    r.message = recovery.failure();
  }
  r.counters = counters;
  r.details = details;
  return r;
}

BackendResult ContactBackend::solve(IncrementProblem& problem, const VecX& x0) {
  if (x0.size() != problem.n_free())
    throw std::logic_error(fmt::format("{} backend: start vector has {} entries, the problem {} free dofs", name(),
                                       x0.size(), problem.n_free()));
  if (problem.roller_potential() && !solves_roller_height())
    throw std::logic_error(fmt::format("{} backend: a suspended roller's position is not among its unknowns", name()));
  const auto t0 = std::chrono::steady_clock::now();
  BackendResult r = minimises_energy() ? solve_settling_recovery(problem, x0) : do_solve(problem, x0);
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // Nothing non-finite leaves a backend: a converged result with NaN is a failure.
  bool finite =
      r.x.size() == problem.n_free() && r.x.allFinite() && (!r.roller_offset || std::isfinite(*r.roller_offset));
  for (const auto& c : r.contact)
    finite = finite && std::isfinite(c.normal_force) && std::isfinite(c.tangential_force) && std::isfinite(c.gap) &&
             std::isfinite(c.slip);
  if (problem.rim() && r.converged() && r.rim.size() != problem.n_rim())
    throw std::logic_error(
        fmt::format("{} backend: an elastic roller's rim displacements are not among its unknowns", name()));
  finite = finite && r.rim.allFinite();
  if (!finite && r.converged()) {
    r.status = Termination::Failed;
    r.message = fmt::format(
        "{} backend returned non-finite values; use smaller steps (a larger steps.count, or steps.max_cuts)", name());
  }
  r.max_penetration = 0.0;
  for (const auto& c : r.contact) r.max_penetration = std::max(r.max_penetration, -c.gap);
  if (problem.rim() && r.converged()) {
    // The rim's compliance is known on its arc only: a contact beyond it would be a rigid roller's.
    const auto& cands = problem.candidates();
    for (std::size_t i = 0; i < cands.size() && i < r.contact.size(); ++i)
      if (r.contact[i].status != ContactStatus::Open && !cands[i].rim.on_rim()) {
        r.status = Termination::Failed;
        r.message = fmt::format(
            "elastic roller: node {} touches the roller outside its rim arc ({:.4g} mm either side of the lowest "
            "point): the contact is wider than the arc taken from the scene's largest force; check the load and "
            "the roller's E (a soft roller's contact is wide)",
            cands[i].node, problem.rim()->arc_half_length());
        break;
      }
  }
  return r;
}

}  // namespace roller
