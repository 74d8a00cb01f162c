// Testing hooks of the interior-point backend (ipopt_testing.hpp).
#include "ipopt_testing.hpp"

#include <cstdarg>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <vector>

#include <IpIpoptApplication.hpp>
#include <IpJournalist.hpp>

#include "friction_passes.hpp"
#include "ipopt_common.hpp"
#include "ipopt_condensed.hpp"
#include "ipopt_full.hpp"
#include "roller/core/error.hpp"

namespace roller::ipopt_testing {

using namespace ipopt_detail;

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
    const Expected<ObjectiveValue> at_x0 = problem.strip_energy(x0, &g, &k);
    if (!at_x0) throw NumericalError("FirstPassNlp: " + at_x0.error());
    scales = increment_scales(problem, x0, at_x0->force_scale);
    std::vector<RowMap> rows;
    if (options.ipopt.formulation == IpoptFormulation::Full) {
      objective = std::make_unique<StripObjective>(problem, k);
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

NlpEvaluation evaluate_nlp(IncrementProblem& problem, const ContactOptions& options, const VecX& z, double obj_factor,
                           const VecX& lambda) {
  FirstPassNlp first(problem, VecX::Zero(problem.n_free()), options);
  ContactTnlp& nlp = *first.tnlp;
  IIndex n, m, nnz_j, nnz_h;
  Ipopt::TNLP::IndexStyleEnum style;
  nlp.get_nlp_info(n, m, nnz_j, nnz_h, style);
  NlpEvaluation out;
  out.n_variables = n;
  out.n_constraints = m;
  if (z.size() == 0) return out;
  if (z.size() != n || lambda.size() != m) throw std::logic_error("evaluate_nlp: z or lambda has the wrong size");
  Number fv;
  if (!nlp.eval_f(n, z.data(), true, fv)) throw NumericalError("evaluate_nlp: f failed");
  out.f = fv;
  out.grad_f.resize(n);
  nlp.eval_grad_f(n, z.data(), false, out.grad_f.data());
  out.g.resize(m);
  nlp.eval_g(n, z.data(), false, m, out.g.data());
  std::vector<IIndex> ri(nnz_j), ci(nnz_j);
  std::vector<Number> v(nnz_j);
  nlp.eval_jac_g(n, nullptr, false, m, nnz_j, ri.data(), ci.data(), nullptr);
  nlp.eval_jac_g(n, z.data(), false, m, nnz_j, nullptr, nullptr, v.data());
  out.jacobian = MatX::Zero(m, n);
  for (IIndex e = 0; e < nnz_j; ++e) out.jacobian(ri[e], ci[e]) += v[e];
  std::vector<IIndex> hr(nnz_h), hc(nnz_h);
  std::vector<Number> hv(nnz_h);
  nlp.eval_h(n, nullptr, false, obj_factor, m, nullptr, false, nnz_h, hr.data(), hc.data(), nullptr);
  nlp.eval_h(n, z.data(), false, obj_factor, m, lambda.data(), true, nnz_h, nullptr, nullptr, hv.data());
  out.hessian = MatX::Zero(n, n);
  for (IIndex e = 0; e < nnz_h; ++e) {
    if (hr[e] < hc[e]) throw std::logic_error("evaluate_nlp: Hessian entry above the diagonal");
    out.hessian(hr[e], hc[e]) += hv[e];
    if (hr[e] != hc[e]) out.hessian(hc[e], hr[e]) += hv[e];
  }
  return out;
}

}  // namespace roller::ipopt_testing
