#include "friction_passes.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <IpSolveStatistics.hpp>

#include "ipopt_common.hpp"

namespace roller::ipopt_detail {

NormalForceFixedPoint::NormalForceFixedPoint(const IncrementProblem& problem, const IpoptOptions& o, Real force_scale)
    : o_(o), mu_(problem.roller().friction), force_scale_(force_scale) {
  for (const auto& c : problem.candidates()) fbar_.push_back(std::max(c.normal_force_guess, 0.0));
}

Real NormalForceFixedPoint::force_tol() const {
  Real fb = 0.0;
  for (const Real f : fbar_) fb = std::max(fb, f);
  return 1e-6 * std::max(force_scale_, fb);
}

bool NormalForceFixedPoint::update(const std::vector<Real>& normal) {
  // Single: Fbar stays the previous increment's F_N (the thesis's explicit variant), also for
  // the condensed formulation's later linearisations.
  if (!iterated()) return true;
  const Real tol = force_tol();
  last_change_ = 0.0;
  last_max_ = 0.0;
  for (std::size_t i = 0; i < fbar_.size(); ++i) {
    last_change_ = std::max(last_change_, std::abs(normal[i] - fbar_[i]));
    last_max_ = std::max(last_max_, normal[i]);
  }
  std::vector<Real> residual(fbar_.size());
  for (std::size_t i = 0; i < fbar_.size(); ++i) residual[i] = normal[i] - fbar_[i];
  if (previous_change_ < 1e300 && last_change_ > 0.5 * previous_change_) relaxed_ = true;
  if (relaxed_) {
    // Aitken: w_k = -w_{k-1} r_{k-1}.(r_k - r_{k-1}) / |r_k - r_{k-1}|^2, the secant step of the
    // residual along the last update; for a linear map of slope s it gives w = 1/(1 - s). Kept in
    // [1/64, 1]: the projection on Fbar >= 0 and the stick/slip switches make the map only
    // piecewise linear.
    Real num = 0.0, den = 0.0;
    for (std::size_t i = 0; i < residual.size(); ++i) {
      const Real dr = residual[i] - previous_residual_[i];
      num += previous_residual_[i] * dr;
      den += dr * dr;
    }
    relaxation_ = den > 0.0 ? std::clamp(-relaxation_ * num / den, 1.0 / 64.0, 1.0) : 0.5;
  }
  previous_change_ = last_change_;
  previous_residual_ = residual;
  for (std::size_t i = 0; i < fbar_.size(); ++i)
    fbar_[i] = std::max((1.0 - relaxation_) * fbar_[i] + relaxation_ * normal[i], 0.0);
  return last_change_ <= std::max(o_.fixed_point_tol * last_max_, tol) || last_max_ <= 1e-6 * force_scale_;
}

std::string NormalForceFixedPoint::failure_message(int passes) const {
  return fmt::format(
      "the friction fixed point on the normal force did not converge in {} passes (contact.ipopt.fixed_point_max): "
      "max |dF_N| = {:.3g} vs contact.ipopt.fixed_point_tol * max F_N = {:.3g}; use smaller steps (a larger "
      "steps.count, or steps.max_cuts), raise "
      "contact.ipopt.fixed_point_max, or use contact.ipopt.fixed_point = \"single\"",
      passes, last_change_, o_.fixed_point_tol * last_max_);
}

FrictionPasses solve_friction_passes(Ipopt::IpoptApplication& app, NlpObjective& objective,
                                     const IncrementProblem& problem, const std::vector<RowMap>& rows,
                                     NormalForceFixedPoint& fixed_point, NlpStart start, int max_passes,
                                     bool warm_first, const IpoptOptions& o) {
  const std::size_t n_c = problem.candidates().size();
  const Real mu = problem.roller().friction;
  FrictionPasses out;
  for (int pass = 1; pass <= max_passes; ++pass) {
    const ContactRows contact(problem, rows, friction_terms(rows, fixed_point.fbar(), mu, fixed_point.force_tol(), o),
                              objective.n(), objective.roller_slot(), objective.rim_slot());
    // Pass 1 warm-starts only on request (its guesses may be poor); later passes always start
    // from the previous pass's primal-dual solution, which is close. A warm start that fails
    // (a poor guess can send Ipopt into restoration) is repeated once from a cold start.
    const bool warm = pass > 1 || warm_first;
    Ipopt::SmartPtr<ContactTnlp> nlp;
    Ipopt::ApplicationReturnStatus status = Ipopt::Internal_Error;
    StatusText st{Termination::Failed, ""};
    set(app, "linear_solver", kkt_linear_solver(o.kkt_solver, contact.n_variables(), contact.n_constraints()));
    for (const bool warm_here : {warm, false}) {
      set_warm_start(app, warm_here);
      nlp = new ContactTnlp(objective, contact, start);
      const auto t0 = std::chrono::steady_clock::now();
      status = app.OptimizeTNLP(GetRawPtr(nlp));
      out.ipopt_time_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      ++out.nlp_solves;
      const int iterations = IsValid(app.Statistics()) ? app.Statistics()->IterationCount() : 0;
      out.iterations += iterations;
      st = map_status(status, iterations, o, objective.evaluation_error());
      const bool solved = st.status == Termination::Converged && nlp->solution().finalized;
      // The iteration limit is the user's (contact.ipopt.max_iter): reported, not retried.
      if (solved || !warm_here || status == Ipopt::Maximum_Iterations_Exceeded) break;
      ++out.cold_restarts;
    }
    out.passes = pass;
    out.nlp_variables = contact.n_variables();
    out.nlp_constraints = contact.n_constraints();
    if (nlp->solution().finalized) out.last = nlp->solution();
    if (status == Ipopt::Solved_To_Acceptable_Level) out.acceptable_level = true;
    if (st.status != Termination::Converged || !nlp->solution().finalized) {
      out.status = st.status == Termination::Converged ? Termination::Failed : st.status;
      out.message = st.status == Termination::Converged ? "Ipopt returned no solution" : st.message;
      return out;
    }
    out.normal.assign(n_c, 0.0);
    out.tangential.assign(n_c, 0.0);
    out.has_friction.assign(n_c, false);
    out.fbar = fixed_point.fbar();
    for (std::size_t k = 0; k < rows.size(); ++k) {
      out.normal[rows[k].candidate] = out.last.forces.normal[k];
      out.tangential[rows[k].candidate] = out.last.forces.tangential[k];
    }
    out.friction = contact.friction();
    for (const int k : out.friction.rows) out.has_friction[rows[k].candidate] = true;
    const bool done = fixed_point.update(out.normal);
    if (done || !fixed_point.iterated()) {
      out.fixed_point_converged = done;
      break;
    }
    start.primal = out.last.z.head(objective.n());
    start.guess = out.last.forces;
  }
  return out;
}

}  // namespace roller::ipopt_detail
