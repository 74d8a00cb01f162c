// The interior-point contact backend (docs/model.md, "Contact" and "Friction"). Files:
// nlp_contact_rows (gap and slip rows, friction terms), contact_tnlp (the one Ipopt adapter),
// friction_passes (the Coulomb fixed point), ipopt_full and ipopt_condensed (the formulations),
// ipopt_common (Ipopt set-up, scales, status messages, the report), this file (the facade).
//
// The NLP (variables, objective, constraints, exact derivatives, forces), its scaling, Ipopt's
// options and why, warm starts and the status of each candidate: docs/model.md, "The interior-point
// backend's NLP in detail". strip_energy may throw NumericalError (an inverted element at a trial
// point): eval_f/eval_grad_f return false so that Ipopt cuts its step; eval_h returning false ends
// the solve (Ipopt cannot recover from that), reported with the cause.
#include "roller/contact/ipopt_backend.hpp"

#include <cstdarg>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>
#include <IpIpoptApplication.hpp>
#include <IpJournalist.hpp>

#include "friction_passes.hpp"
#include "ipopt_common.hpp"
#include "ipopt_condensed.hpp"
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
    r.status = ContactTermination::Converged;
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
  if (options_.ipopt.formulation == IpoptFormulation::Full) return solve_full(problem, x0, options_);
  CondensedOutcome condensed = solve_condensed(problem, x0, options_, condenser_);
  // Factors are kept only for the next increment's same tangent, and never beside the full formulation's.
  if (!problem.strip_tangent_is_constant() || condensed.formulation_failed) condenser_.release();
  // The full formulation has no roller variable: a suspended roller's failure goes back to the
  // driver, which couples the suspension by passes with the roller placed instead.
  if (!condensed.formulation_failed || problem.roller_potential()) return std::move(condensed.result);
  // The condensed formulation itself failed (singular interior tangent, no descent, the
  // linearisations ran out): the full formulation solves the increment from the same start.
  BackendResult full = solve_full(problem, x0, options_);
  full.iterations += condensed.result.iterations;
  full.factorizations += condensed.result.factorizations;
  full.stats.condensed_fallback = true;
  full.message += fmt::format(" [full formulation after the condensed one failed: {}]", condensed.result.message);
  return full;
}

// Testing hooks. They are not declared in a public header (ipopt_backend.hpp keeps Ipopt out of
// the interface); tests/contact/test_ipopt_backend.cpp declares them itself.
namespace ipopt_testing {

namespace {

// Collects Ipopt's journal output (the derivative checker's report).
class StringJournal : public Ipopt::Journal {
 public:
  StringJournal(std::string* out, Ipopt::EJournalLevel level) : Ipopt::Journal("roller-string", level), out_(out) {}

 protected:
  void PrintImpl(Ipopt::EJournalCategory, Ipopt::EJournalLevel, const char* str) override { out_->append(str); }
  void PrintfImpl(Ipopt::EJournalCategory, Ipopt::EJournalLevel, const char* format, va_list ap) override {
    char buffer[4096];
    std::vsnprintf(buffer, sizeof buffer, format, ap);
    out_->append(buffer);
  }
  void FlushBufferImpl() override {}

 private:
  std::string* out_;
};

// The NLP of the first fixed-point pass at x0 (Fbar = the candidates' normal_force_guess) as the
// backend builds it: for the full formulation every free dof a variable; for the condensed one
// the first linearisation's working set and model.
struct FirstPassNlp {
  FirstPassNlp(IncrementProblem& problem, const VecX& x0, const ContactOptions& options) {
    VecX g;
    SparseMatrix k;
    scales = increment_scales(problem, x0, problem.strip_energy(x0, &g, &k).force_scale);
    std::vector<RowMap> rows;
    if (options.ipopt.formulation == IpoptFormulation::Full) {
      objective = std::make_unique<StripObjective>(problem, x0);
      rows = full_rows(problem);
      start = full_start(problem, rows, x0);
    } else {
      if (condense(problem, initial_working_set(problem, x0, scales.length), x0, g, k, condenser, &condensation) ==
          SchurCondenser::Outcome::Failed)
        throw NumericalError("FirstPassNlp: the condensation failed: " + condenser.message());
      objective = problem.roller_potential() ? std::make_unique<QuadraticModel>(
                                                   condensation, *problem.roller_potential(), problem.roller_offset())
                                             : std::make_unique<QuadraticModel>(condensation);
      rows = condensation.rows;
      start.primal = VecX::Zero(objective->n());
      for (const RowMap& r : rows) {
        start.guess.normal.push_back(std::max(problem.candidates()[r.candidate].normal_force_guess, 0.0));
        start.guess.tangential.push_back(problem.candidates()[r.candidate].tangential_force);
      }
    }
    const NormalForceFixedPoint fixed_point(problem, options.ipopt, scales.force);
    contact = std::make_unique<ContactRows>(
        problem, rows,
        friction_terms(rows, fixed_point.fbar(), problem.roller().friction, fixed_point.force_tol(), options.ipopt),
        objective->n(), objective->roller_slot());
    tnlp = new ContactTnlp(*objective, *contact, start);
  }
  SchurCondenser condenser;
  Condensation condensation;
  Scales scales;
  std::unique_ptr<NlpObjective> objective;
  std::unique_ptr<ContactRows> contact;
  NlpStart start;
  Ipopt::SmartPtr<ContactTnlp> tnlp;
};

}  // namespace

// Runs Ipopt's derivative checker ("second-order") on the first pass's NLP at its start point
// and returns its journal output.
std::string derivative_checker_output(IncrementProblem& problem, const VecX& x0, const ContactOptions& options,
                                      double perturbation) {
  FirstPassNlp nlp(problem, x0, options);
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = make_application(options.ipopt, nlp.scales);
  set(*app, "derivative_test", std::string("second-order"));
  set(*app, "derivative_test_print_all", std::string("no"));
  set(*app, "derivative_test_perturbation", perturbation);
  set(*app, "point_perturbation_radius", 0.0);  // check at the start point itself
  set(*app, "max_iter", 0);
  if (app->Initialize("") != Ipopt::Solve_Succeeded) throw std::logic_error("derivative_checker_output: Initialize");
  std::string out;
  Ipopt::SmartPtr<Ipopt::Journal> journal = new StringJournal(&out, Ipopt::J_WARNING);
  app->Jnlst()->AddJournal(journal);
  app->OptimizeTNLP(GetRawPtr(nlp.tnlp));
  return out;
}

// Dense evaluation of the first pass's NLP at z (all NLP variables; z of size 0 only returns
// the sizes): objective f, its gradient, constraints, Jacobian, Hessian of the Lagrangian
// obj_factor * f + lambda . g (both triangles filled). The NLP is built at x0 = 0.
void evaluate_nlp(IncrementProblem& problem, const ContactOptions& options, const VecX& z, double obj_factor,
                  const VecX& lambda, long* n_variables, long* n_constraints, double* f, VecX* grad_f, VecX* g,
                  MatX* jacobian, MatX* hessian) {
  FirstPassNlp first(problem, VecX::Zero(problem.n_free()), options);
  ContactTnlp& nlp = *first.tnlp;
  IIndex n, m, nnz_j, nnz_h;
  Ipopt::TNLP::IndexStyleEnum style;
  nlp.get_nlp_info(n, m, nnz_j, nnz_h, style);
  *n_variables = n;
  *n_constraints = m;
  if (z.size() == 0) return;
  if (z.size() != n || lambda.size() != m) throw std::logic_error("evaluate_nlp: z or lambda has the wrong size");
  Number fv;
  if (!nlp.eval_f(n, z.data(), true, fv)) throw NumericalError("evaluate_nlp: f failed");
  *f = fv;
  grad_f->resize(n);
  nlp.eval_grad_f(n, z.data(), false, grad_f->data());
  g->resize(m);
  nlp.eval_g(n, z.data(), false, m, g->data());
  std::vector<IIndex> ri(nnz_j), ci(nnz_j);
  std::vector<Number> v(nnz_j);
  nlp.eval_jac_g(n, nullptr, false, m, nnz_j, ri.data(), ci.data(), nullptr);
  nlp.eval_jac_g(n, z.data(), false, m, nnz_j, nullptr, nullptr, v.data());
  *jacobian = MatX::Zero(m, n);
  for (IIndex e = 0; e < nnz_j; ++e) (*jacobian)(ri[e], ci[e]) += v[e];
  std::vector<IIndex> hr(nnz_h), hc(nnz_h);
  std::vector<Number> hv(nnz_h);
  nlp.eval_h(n, nullptr, false, obj_factor, m, nullptr, false, nnz_h, hr.data(), hc.data(), nullptr);
  nlp.eval_h(n, z.data(), false, obj_factor, m, lambda.data(), true, nnz_h, nullptr, nullptr, hv.data());
  *hessian = MatX::Zero(n, n);
  for (IIndex e = 0; e < nnz_h; ++e) {
    if (hr[e] < hc[e]) throw std::logic_error("evaluate_nlp: Hessian entry above the diagonal");
    (*hessian)(hr[e], hc[e]) += hv[e];
    if (hr[e] != hc[e]) (*hessian)(hc[e], hr[e]) += hv[e];
  }
}

}  // namespace ipopt_testing

}  // namespace roller
