#include "ipopt_full.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>
#include <IpIpoptApplication.hpp>

#include "friction_passes.hpp"
#include "ipopt_common.hpp"
#include "roller/core/error.hpp"

namespace roller::ipopt_detail {

StripObjective::StripObjective(IncrementProblem& problem, SparseMatrix start_hessian)
    : problem_(problem), x_(VecX::Zero(problem.n_free())) {
  SparseMatrix& h = start_hessian;
  h.makeCompressed();
  const int* outer = h.outerIndexPtr();
  const int* inner = h.innerIndexPtr();
  for (int k = 0; k < h.outerSize(); ++k)
    for (int q = outer[k]; q < outer[k + 1]; ++q)
      if (inner[q] >= k) {
        slot_.push_back(q);
        row_.push_back(inner[q]);
        col_.push_back(k);
      }
  inner_.assign(inner, inner + h.nonZeros());
  outer_.assign(outer, outer + h.outerSize() + 1);
}

bool StripObjective::update(const Real* d) {
  if (cache_valid_ && std::equal(d, d + n(), x_.data())) return cache_ok_;
  x_ = Eigen::Map<const VecX>(d, n());
  cache_valid_ = true;
  const Expected<ObjectiveValue> value = problem_.strip_energy(x_, &gradient_, nullptr);
  if (!value) {
    evaluation_error_ = value.error();
    cache_ok_ = false;
    return cache_ok_;
  }
  energy_ = value->value;
  cache_ok_ = std::isfinite(energy_) && gradient_.allFinite();
  if (!cache_ok_) evaluation_error_ = "the strip energy or its gradient is not finite";
  return cache_ok_;
}

bool StripObjective::value(const Real* d, Real& f) {
  if (!update(d)) return false;
  f = energy_;
  return true;
}

bool StripObjective::gradient(const Real* d, Real* g) {
  if (!update(d)) return false;
  std::copy(gradient_.data(), gradient_.data() + n(), g);
  return true;
}

void StripObjective::hessian_structure(int* row, int* col) const {
  std::copy(row_.begin(), row_.end(), row);
  std::copy(col_.begin(), col_.end(), col);
}

bool StripObjective::hessian_values(const Real* d, Real obj_factor, Real* values) {
  if (obj_factor == 0.0) {
    std::fill_n(values, slot_.size(), 0.0);
    return true;
  }
  const Expected<ObjectiveValue> value = problem_.strip_energy(Eigen::Map<const VecX>(d, n()), nullptr, &hessian_);
  if (!value) {
    evaluation_error_ = value.error();
    return false;
  }
  const bool same_pattern = hessian_.isCompressed() && static_cast<std::size_t>(hessian_.nonZeros()) == inner_.size() &&
                            std::equal(outer_.begin(), outer_.end(), hessian_.outerIndexPtr()) &&
                            std::equal(inner_.begin(), inner_.end(), hessian_.innerIndexPtr());
  if (!same_pattern)
    throw std::logic_error("ipopt backend: the strip Hessian's sparsity pattern changed between evaluations");
  const Real* h = hessian_.valuePtr();
  for (std::size_t e = 0; e < slot_.size(); ++e) values[e] = obj_factor * h[slot_[e]];
  return true;
}

std::vector<RowMap> full_rows(const IncrementProblem& problem) {
  std::vector<RowMap> rows;
  const auto& cands = problem.candidates();
  for (std::size_t i = 0; i < cands.size(); ++i) {
    const ContactCandidate& c = cands[i];
    if (c.free_dof[0] < 0 && c.free_dof[1] < 0) continue;  // its gap cannot change: no row
    RowMap r;
    r.candidate = static_cast<int>(i);
    for (int a = 0; a < 2; ++a) {
      r.slot[a] = static_cast<int>(c.free_dof[a]);
      r.base(a) = c.free_dof[a] >= 0 ? 0.0 : c.prescribed(a);
    }
    rows.push_back(r);
  }
  return rows;
}

NlpStart full_start(const IncrementProblem& problem, const std::vector<RowMap>& rows, const VecX& x0) {
  NlpStart start;
  start.primal = x0;
  for (const RowMap& r : rows) {
    const ContactCandidate& c = problem.candidates()[r.candidate];
    start.guess.normal.push_back(std::max(c.normal_force_guess, 0.0));
    start.guess.tangential.push_back(c.tangential_force);
  }
  return start;
}

BackendResult solve_full(IncrementProblem& problem, const VecX& x0, const ContactOptions& options) {
  const IpoptOptions& o = options.ipopt;
  BackendResult result;
  result.x = x0;
  result.contact.assign(problem.candidates().size(), NodeContact{});

  VecX g;
  SparseMatrix h;
  const Expected<ObjectiveValue> start = problem.strip_energy(x0, &g, &h);
  if (!start) {
    result.status = Termination::Failed;
    result.message = fmt::format(
        "ipopt backend: the strip cannot be evaluated at the start vector ({}); "
        "use smaller steps (a larger steps.count, or steps.max_cuts)",
        start.error());
    return result;
  }
  const Scales scales = increment_scales(problem, x0, start->force_scale);
  StripObjective strip(problem, std::move(h));
  // An elastic roller's rim displacements follow the strip's free dofs (docs/model.md, Elastic roller).
  std::optional<RimObjective> with_rim;
  if (problem.rim()) {
    if (o.friction == IpoptFriction::Regularized && problem.roller().friction > 0.0) {
      result.status = Termination::Failed;
      result.message =
          "ipopt backend: an elastic roller takes contact.ipopt.friction = \"split\" (the regularized law's "
          "curvature in the rim's displacements is not built)";
      return result;
    }
    with_rim.emplace(strip, problem.rim()->stiffness);
  }
  NlpObjective& objective = with_rim ? static_cast<NlpObjective&>(*with_rim) : strip;

  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = make_application(o, scales);
  if (app->Initialize("") != Ipopt::Solve_Succeeded) {  // "": never read ./ipopt.opt
    result.status = Termination::Failed;
    result.message = "ipopt backend: Ipopt failed to initialise";
    return result;
  }

  NormalForceFixedPoint fixed_point(problem, o, scales.force);
  const std::vector<RowMap> rows = full_rows(problem);
  const int max_passes = fixed_point.iterated() ? o.fixed_point_max : 1;
  NlpStart first = full_start(problem, rows, x0);
  if (problem.rim()) {
    first.primal.conservativeResize(problem.n_free() + problem.n_rim());
    first.primal.tail(problem.n_rim()) = problem.rim_start();
  }
  const FrictionPasses passes =
      solve_friction_passes(*app, objective, problem, rows, fixed_point, std::move(first), max_passes, o.warm_start, o);
  result.counters.iterations = passes.iterations;
  IpoptDetails& details = result.details.fill<IpoptDetails>();
  details.fixed_point_iterations = passes.passes;
  details.nlp_solves = passes.nlp_solves;
  details.cold_restarts = passes.cold_restarts;
  details.nlp_variables = passes.nlp_variables;
  details.nlp_constraints = passes.nlp_constraints;
  details.ipopt_time_s = passes.ipopt_time_s;
  details.acceptable_level = passes.acceptable_level;
  if (passes.last.finalized) {
    result.x = passes.last.z.head(problem.n_free());
    if (problem.rim()) {
      result.rim = passes.last.z.segment(problem.n_free(), problem.n_rim());
      problem.set_rim_displacement(result.rim);
    }
  }
  if (passes.status != Termination::Converged) {
    result.status = passes.status;
    result.message = passes.message;
    if (problem.roller().friction > 0.0)
      result.message += fmt::format(" (friction fixed-point pass {})", passes.passes);
    return result;
  }
  result.counters.factorizations = result.counters.iterations;  // one KKT factorisation per interior-point iteration
  if (!report_increment(problem, result.x, passes.normal, passes.tangential, passes.fbar, passes.has_friction, scales,
                        &result))
    return result;
  if (!passes.fixed_point_converged) {
    result.status = Termination::LimitReached;
    result.message = fixed_point.failure_message(passes.passes);
    return result;
  }
  result.status = Termination::Converged;
  result.message = fmt::format("Ipopt converged in {} iterations ({} fixed-point pass{})", result.counters.iterations,
                               passes.passes, passes.passes == 1 ? "" : "es");
  return result;
}

}  // namespace roller::ipopt_detail
