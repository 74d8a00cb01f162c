#include "roller/contact/backend.hpp"

#include <chrono>

#include <fmt/format.h>

#include "roller/contact/ipopt_backend.hpp"
#include "roller/contact/penalty_backend.hpp"
#include "roller/core/error.hpp"

namespace roller {

const char* to_string(ContactStatus s) {
  switch (s) {
    case ContactStatus::Open: return "open";
    case ContactStatus::Stick: return "stick";
    case ContactStatus::Slip: return "slip";
  }
  return "?";
}

std::string BackendStats::brief() const {
  std::string s;
  auto add = [&s](const char* name, double value) {
    if (value != 0.0) s += fmt::format("{}{} {:.3g}", s.empty() ? "" : ", ", name, value);
  };
  add("complementarity", complementarity);
  add("constraint_violation", constraint_violation);
  add("fixed_point_iterations", fixed_point_iterations);
  add("nlp_solves", nlp_solves);
  add("cold_restarts", cold_restarts);
  add("nlp_variables", nlp_variables);
  add("nlp_constraints", nlp_constraints);
  add("linearisations", linearisations);
  add("condensed_dofs", condensed_dofs);
  add("ipopt_time_s", ipopt_time_s);
  add("acceptable_level", acceptable_level ? 1.0 : 0.0);
  add("condensed_fallback", condensed_fallback ? 1.0 : 0.0);
  add("active_set_passes", active_set_passes);
  add("penalty_stages", penalty_stages);
  return s;
}

void BackendStats::add(const BackendStats& later) {
  const BackendStats work = *this;
  *this = later;
  nlp_solves += work.nlp_solves;
  cold_restarts += work.cold_restarts;
  linearisations += work.linearisations;
  ipopt_time_s += work.ipopt_time_s;
  active_set_passes += work.active_set_passes;
  penalty_stages += work.penalty_stages;
  acceptable_level = acceptable_level || work.acceptable_level;
  condensed_fallback = condensed_fallback || work.condensed_fallback;
}

std::string BackendResult::brief_report() const {
  std::string s = fmt::format("{} in {} iterations, |r|/F {:.2e}, max penetration {:.2e} mm",
                              converged() ? "converged" : "FAILED", iterations, residual, max_penetration);
  const std::string details = stats.brief();
  if (!details.empty()) s += ", " + details;
  if (!converged()) s += ": " + message;
  return s;
}

BackendResult ContactBackend::solve(IncrementProblem& problem, const VecX& x0) {
  if (x0.size() != problem.n_free())
    throw std::logic_error(fmt::format("{} backend: start vector has {} entries, the problem {} free dofs", name(),
                                       x0.size(), problem.n_free()));
  if (problem.roller_potential() && !solves_roller_height())
    throw std::logic_error(fmt::format("{} backend: a suspended roller's position is not among its unknowns", name()));
  const auto t0 = std::chrono::steady_clock::now();
  BackendResult r = do_solve(problem, x0);
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // Nothing non-finite leaves a backend: a converged result with NaN is a failure.
  bool finite =
      r.x.size() == problem.n_free() && r.x.allFinite() && (!r.roller_offset || std::isfinite(*r.roller_offset));
  for (const auto& c : r.contact)
    finite = finite && std::isfinite(c.normal_force) && std::isfinite(c.tangential_force) && std::isfinite(c.gap) &&
             std::isfinite(c.slip);
  if (!finite && r.converged()) {
    r.status = ContactTermination::Failed;
    r.message = fmt::format(
        "{} backend returned non-finite values; use smaller steps (a larger steps.count, or steps.max_cuts)", name());
  }
  r.max_penetration = 0.0;
  for (const auto& c : r.contact) r.max_penetration = std::max(r.max_penetration, -c.gap);
  return r;
}

bool PenaltyOptions::is_valid(std::string* why) const {
  if (!(factor > 0.0)) {
    if (why) *why = fmt::format("contact.penalty.factor = {}: must be > 0", factor);
    return false;
  }
  if (!(tangential_factor > 0.0)) {
    if (why) *why = fmt::format("contact.penalty.tangential_factor = {}: must be > 0", tangential_factor);
    return false;
  }
  return true;
}

bool IpoptOptions::is_valid(std::string* why) const {
  auto bad = [why](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  if (!(tol > 0.0 && tol < 1.0)) return bad(fmt::format("contact.ipopt.tol = {}: must be in (0, 1)", tol));
  if (max_iter < 1) return bad(fmt::format("contact.ipopt.max_iter = {}: must be >= 1", max_iter));
  if (print_level < 0 || print_level > 12)
    return bad(fmt::format("contact.ipopt.print_level = {}: expected 0..12", print_level));
  if (!(regularization > 0.0))
    return bad(fmt::format("contact.ipopt.regularization = {}: must be > 0", regularization));
  if (!(fixed_point_tol > 0.0))
    return bad(fmt::format("contact.ipopt.fixed_point_tol = {}: must be > 0", fixed_point_tol));
  if (fixed_point_max < 1) return bad(fmt::format("contact.ipopt.fixed_point_max = {}: must be >= 1", fixed_point_max));
  for (const RawIpoptOption& r : raw)
    if (r.name == "linear_solver")
      return bad(
          fmt::format("contact.ipopt.options.linear_solver = {}: roller chooses Ipopt's linear solver per NLP; "
                      "use contact.ipopt.kkt_solver = \"auto\", \"dense\" or \"mumps\"",
                      r.text));
  return true;
}

bool ContactOptions::is_valid(std::string* why) const {
  if (!(friction >= 0.0 && friction <= 10.0)) {
    if (why) *why = fmt::format("contact.friction = {}: expected 0 <= mu <= 10", friction);
    return false;
  }
  return penalty.is_valid(why) && ipopt.is_valid(why);
}

std::unique_ptr<ContactBackend> make_contact_backend(const ContactOptions& options, const NewtonOptions& newton) {
  std::string why;
  if (!options.is_valid(&why)) throw InputError(why);
  if (options.backend == ContactBackendKind::Ipopt) return std::make_unique<IpoptBackend>(options, newton.linear);
  return std::make_unique<PenaltyBackend>(options, newton);
}

}  // namespace roller
