#include "roller/analysis/melan.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>
#include <IpIpoptApplication.hpp>
#include <IpSolveStatistics.hpp>
#include <IpTNLP.hpp>

#include "roller/core/error.hpp"
#include "roller/material/j2_plasticity.hpp"

namespace roller {

namespace {

using IIndex = Ipopt::Index;
using Ipopt::Number;
using ShiftBasis = Eigen::Matrix<Real, 4, Eigen::Dynamic, 0, 4, 5>;
using RowMatrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;

// sigma_vm^2 = x^T M x for x = [xx, yy, zz, xy] (3 J2 with the shear counted once).
Eigen::Matrix4d von_mises_form() {
  Eigen::Matrix4d m;
  m << 1.0, -0.5, -0.5, 0.0, -0.5, 1.0, -0.5, 0.0, -0.5, -0.5, 1.0, 0.0, 0.0, 0.0, 0.0, 3.0;
  return m;
}

// The shift's columns, in units of the row's largest yield stress: residual stresses rho_xx and
// rho_zz (added) and the back-stress deviator alpha_xx, alpha_yy, alpha_xy (subtracted). With an
// unbounded back-stress the residual stresses add nothing (their deviators lie in alpha's span).
struct Shift {
  ShiftBasis rho{4, 0}, alpha{4, 0};
  int n() const { return static_cast<int>(rho.cols() + alpha.cols()); }
};

Shift shift_basis(ShakedownBound bound, bool back_stress_bounded) {
  Shift s;
  if (bound == ShakedownBound::Elastic || back_stress_bounded) {
    s.rho.resize(4, 2);
    s.rho << 1, 0, 0, 0, 0, 1, 0, 0;  // columns: xx, zz
  }
  if (bound == ShakedownBound::Kinematic) {
    s.alpha.resize(4, 3);
    s.alpha << 1, 0, 0, 0, 1, 0, -1, -1, 0, 0, 0, 1;  // columns: xx, yy, xy (zz = -xx - yy)
  }
  return s;
}

// One row's problem in the unknowns v = [lambda, shift]: each point's constraint is the quadratic
// form v^T H_i v <= 1 (sigma_vm^2 over sigma_y^2), and the back-stress bound is one more.
struct RowForms {
  Shift shift;
  Real scale = 1.0;  // of the shift: the row's largest yield stress
  std::vector<RowMatrix> points;
  std::optional<RowMatrix> back_stress;

  RowForms(const MelanRow& row, ShakedownBound bound) {
    const bool bounded = bound == ShakedownBound::Kinematic && std::isfinite(row.back_stress_bound);
    shift = shift_basis(bound, bounded);
    scale = *std::max_element(row.yield_stress.begin(), row.yield_stress.end());
    const Eigen::Matrix4d m = von_mises_form();
    Eigen::Matrix<Real, 4, Eigen::Dynamic, 0, 4, 6> a(4, n());
    a.middleCols(1, shift.rho.cols()) = scale * shift.rho;
    a.rightCols(shift.alpha.cols()) = -scale * shift.alpha;
    for (std::size_t i = 0; i < row.stress.size(); ++i) {
      a.col(0) = row.stress[i];
      points.push_back(a.transpose() * m * a / (row.yield_stress[i] * row.yield_stress[i]));
    }
    if (bounded) {
      a.setZero();
      a.rightCols(shift.alpha.cols()) = scale * shift.alpha;
      back_stress = a.transpose() * m * a / (row.back_stress_bound * row.back_stress_bound);
    }
  }
  int n() const { return 1 + shift.n(); }
  Vec4 residual_stress(const Eigen::VectorXd& v) const { return scale * shift.rho * v.segment(1, shift.rho.cols()); }
  Vec4 back_stress_at(const Eigen::VectorXd& v) const { return scale * shift.alpha * v.tail(shift.alpha.cols()); }
};

constexpr Real kShiftPull = 1e-9;

// maximise lambda s.t. v^T H_i v <= 1 for the points `active` (and the back-stress bound).
class MelanRowNlp : public Ipopt::TNLP {
 public:
  MelanRowNlp(const RowForms& forms, const std::vector<std::size_t>& active, Real cap) : cap_(cap), n_(forms.n()) {
    for (const std::size_t i : active) forms_.push_back(&forms.points[i]);
    if (forms.back_stress) forms_.push_back(&*forms.back_stress);
  }

  bool get_nlp_info(IIndex& n, IIndex& m, IIndex& nnz_jac, IIndex& nnz_h, IndexStyleEnum& style) override {
    n = n_;
    m = static_cast<IIndex>(forms_.size());
    nnz_jac = m * n_;
    nnz_h = n_ * (n_ + 1) / 2;
    style = C_STYLE;
    return true;
  }
  bool get_bounds_info(IIndex n, Number* xl, Number* xu, IIndex m, Number* gl, Number* gu) override {
    xl[0] = 0.0;
    xu[0] = cap_;
    for (IIndex j = 1; j < n; ++j) xl[j] = -1e19, xu[j] = 1e19;
    for (IIndex i = 0; i < m; ++i) gl[i] = -1e19, gu[i] = 1.0;
    return true;
  }
  bool get_starting_point(IIndex n, bool, Number* x, bool, Number*, Number*, IIndex, bool, Number*) override {
    std::fill(x, x + n, 0.0);  // strictly inside every yield surface
    return true;
  }
  // -lambda, plus a small pull of the shift to zero: where the optimal shift is not unique (rho_zz
  // is free within a range on a frictionless row) it picks the smallest, and the KKT matrix keeps
  // full rank. It moves lambda by about kShiftPull.
  bool eval_f(IIndex n, const Number* x, bool, Number& f) override {
    f = -x[0];
    for (IIndex j = 1; j < n; ++j) f += 0.5 * kShiftPull * x[j] * x[j];
    return true;
  }
  bool eval_grad_f(IIndex n, const Number* x, bool, Number* g) override {
    g[0] = -1.0;
    for (IIndex j = 1; j < n; ++j) g[j] = kShiftPull * x[j];
    return true;
  }
  bool eval_g(IIndex n, const Number* x, bool, IIndex m, Number* g) override {
    const Eigen::Map<const Eigen::VectorXd> v(x, n);
    for (IIndex i = 0; i < m; ++i) g[i] = v.dot(*forms_[i] * v);
    return true;
  }
  bool eval_jac_g(IIndex n, const Number* x, bool, IIndex m, IIndex, IIndex* rows, IIndex* cols,
                  Number* values) override {
    for (IIndex i = 0, k = 0; i < m; ++i)
      for (IIndex j = 0; j < n; ++j, ++k) {
        if (values) {
          values[k] = 2.0 * forms_[i]->row(j).dot(Eigen::Map<const Eigen::VectorXd>(x, n));
        } else {
          rows[k] = i;
          cols[k] = j;
        }
      }
    return true;
  }
  bool eval_h(IIndex n, const Number*, bool, Number obj_factor, IIndex m, const Number* lambda, bool, IIndex,
              IIndex* rows, IIndex* cols, Number* values) override {
    RowMatrix h = RowMatrix::Zero(n, n);
    for (IIndex j = 1; j < n; ++j) h(j, j) = obj_factor * kShiftPull;
    if (values)
      for (IIndex i = 0; i < m; ++i) h += 2.0 * lambda[i] * *forms_[i];
    for (IIndex r = 0, k = 0; r < n; ++r)
      for (IIndex c = 0; c <= r; ++c, ++k) {
        if (values) {
          values[k] = h(r, c);
        } else {
          rows[k] = r;
          cols[k] = c;
        }
      }
    return true;
  }
  void finalize_solution(Ipopt::SolverReturn, IIndex n, const Number* x, const Number*, const Number*, IIndex,
                         const Number*, const Number*, Number, const Ipopt::IpoptData*,
                         Ipopt::IpoptCalculatedQuantities*) override {
    solution_ = Eigen::Map<const Eigen::VectorXd>(x, n);
  }
  const Eigen::VectorXd& solution() const { return solution_; }

 private:
  Real cap_;
  IIndex n_;
  std::vector<const RowMatrix*> forms_;
  Eigen::VectorXd solution_;
};

Real row_first_yield(const MelanRow& row) {
  Real f = std::numeric_limits<Real>::infinity();
  for (std::size_t i = 0; i < row.stress.size(); ++i) {
    const Real vm = von_mises(row.stress[i]);
    if (vm > 0.0) f = std::min(f, row.yield_stress[i] / vm);
  }
  return f;
}

}  // namespace

Real MelanLimit::first_yield() const {
  Real f = std::numeric_limits<Real>::infinity();
  for (const MelanRowLimit& r : rows) f = std::min(f, r.first_yield);
  return f;
}

namespace {

Ipopt::SmartPtr<Ipopt::IpoptApplication> melan_application() {
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  app->Options()->SetStringValue("sb", "yes");
  app->Options()->SetIntegerValue("print_level", 0);
  app->Options()->SetNumericValue("tol", 1e-8);
  app->Options()->SetNumericValue("constr_viol_tol", 1e-9);
  app->Options()->SetNumericValue("bound_relax_factor", 0.0);  // no constraint violation at the limit
  app->Options()->SetStringValue("mu_strategy", "monotone");
  app->Options()->SetIntegerValue("max_iter", 500);
  // MUMPS, not the dense KKT solver (solver/dense_kkt_solver.hpp) the contact's small NLPs use: on
  // rows whose constraints nearly repeat each other (a nearly symmetric load) the dense one stops
  // Ipopt in its restoration phase just short of the optimum, and the search prunes rows so that
  // MUMPS's fixed cost per call does not show (docs/benchmarks.md, Melan's bound).
  if (app->Initialize("") != Ipopt::Solve_Succeeded) throw NumericalError("Melan's bound: Ipopt did not start");
  return app;
}

// Where the search starts: the points whose elastic stress is a local maximum of sigma_vm/sigma_y
// along the row, and the largest few. The limit's active points lie near such peaks; the rest
// join in later rounds if the solution violates them.
std::vector<std::size_t> starting_points(const RowForms& forms) {
  const std::size_t n = forms.points.size();
  std::vector<Real> ratio(n);
  for (std::size_t i = 0; i < n; ++i) ratio[i] = forms.points[i](0, 0);
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return ratio[a] > ratio[b]; });
  std::vector<std::size_t> out(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(std::min<std::size_t>(8, n)));
  for (std::size_t i = 1; i + 1 < n; ++i)
    if (ratio[i] > ratio[i - 1] && ratio[i] >= ratio[i + 1]) out.push_back(i);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// Whether point i's constraint repeats one of `active` (a symmetric load gives the points at x and
// -x the same form): a repeated constraint makes the constraints' Jacobian rank-deficient.
bool repeats(const RowForms& forms, const std::vector<std::size_t>& active, std::size_t i) {
  const RowMatrix& h = forms.points[i];
  return std::any_of(active.begin(), active.end(),
                     [&](std::size_t j) { return (forms.points[j] - h).norm() <= 1e-10 * h.norm(); });
}

std::vector<std::size_t> without_repeats(const RowForms& forms, const std::vector<std::size_t>& points) {
  std::vector<std::size_t> out;
  for (const std::size_t i : points)
    if (!repeats(forms, out, i)) out.push_back(i);
  return out;
}

constexpr int kMaxRounds = 50;
constexpr std::size_t kAddedPerRound = 16;
constexpr Real kViolation = 1e-8;  // of sigma_vm^2 / sigma_y^2: Ipopt keeps to 1e-9

}  // namespace

MelanRowLimit melan_row_limit(const MelanRow& row, ShakedownBound bound) {
  ROLLER_ASSERT(row.stress.size() == row.yield_stress.size() && row.x.size() == row.stress.size(),
                "one stress, yield stress and x per point");
  MelanRowLimit out;
  out.depth = row.depth;
  out.first_yield = row_first_yield(row);
  if (!std::isfinite(out.first_yield)) {  // no stress along the row
    out.load_factor = std::numeric_limits<Real>::infinity();
    out.status = MelanRowStatus::Unlimited;
    return out;
  }
  const Real cap = kMelanCapOverFirstYield * out.first_yield;
  if (!(row.back_stress_bound > 0.0)) bound = ShakedownBound::Elastic;  // no back-stress to shift by
  const RowForms forms(row, bound);
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = melan_application();
  // Constraint generation: solve over a working set of points, add the points the solution
  // violates, until it violates none; it then solves the whole row's problem.
  std::vector<std::size_t> active = without_repeats(forms, starting_points(forms));
  Eigen::VectorXd v;
  for (int round = 0;; ++round) {
    Ipopt::SmartPtr<MelanRowNlp> nlp = new MelanRowNlp(forms, active, cap);
    const Ipopt::ApplicationReturnStatus status = app->OptimizeTNLP(nlp);
    if (status != Ipopt::Solve_Succeeded && status != Ipopt::Solved_To_Acceptable_Level)
      throw NumericalError(fmt::format("Melan's bound at depth {:.4g} mm: Ipopt stopped with status {}", row.depth,
                                       static_cast<int>(status)));
    out.iterations += app->Statistics()->IterationCount();
    v = nlp->solution();
    std::vector<std::pair<Real, std::size_t>> violated;
    for (std::size_t i = 0; i < forms.points.size(); ++i)
      if (const Real g = v.dot(forms.points[i] * v); g > 1.0 + kViolation) violated.emplace_back(g, i);
    if (violated.empty()) break;
    if (round == kMaxRounds)
      throw NumericalError(fmt::format("Melan's bound at depth {:.4g} mm: {} points still violated after {} rounds",
                                       row.depth, violated.size(), kMaxRounds));
    std::sort(violated.rbegin(), violated.rend());
    std::size_t added = 0;
    for (std::size_t k = 0; k < violated.size() && added < kAddedPerRound; ++k)
      if (!repeats(forms, active, violated[k].second)) active.push_back(violated[k].second), ++added;
    if (added == 0)
      throw NumericalError(
          fmt::format("Melan's bound at depth {:.4g} mm: Ipopt's solution violates constraints "
                      "it was given",
                      row.depth));
  }
  out.load_factor = v[0];
  if (out.load_factor >= cap * (1.0 - 1e-6)) out.status = MelanRowStatus::Unlimited;
  out.residual_stress = forms.residual_stress(v);
  out.back_stress = forms.back_stress_at(v);
  std::size_t critical = 0;
  Real most = -1.0;
  for (std::size_t i = 0; i < forms.points.size(); ++i)
    if (const Real g = v.dot(forms.points[i] * v); g > most) most = g, critical = i;
  out.critical_x = row.x[critical];
  out.critical_yield_stress = row.yield_stress[critical];
  return out;
}

MelanLimit melan_limit(const std::vector<MelanRow>& rows, ShakedownBound bound, MelanSearch search) {
  MelanLimit out;
  out.bound = bound;
  out.rows.resize(rows.size());
  std::vector<std::size_t> order(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    order[i] = i;
    out.rows[i].depth = rows[i].depth;
    out.rows[i].first_yield = row_first_yield(rows[i]);
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return out.rows[a].first_yield < out.rows[b].first_yield; });
  for (const std::size_t i : order) {
    if (search == MelanSearch::StrictestRow && out.critical_row >= 0 && out.rows[i].first_yield >= out.load_factor()) {
      out.rows[i].status = MelanRowStatus::NotLimiting;
      continue;
    }
    out.rows[i] = melan_row_limit(rows[i], bound);
    if (out.rows[i].status == MelanRowStatus::Solved &&
        (out.critical_row < 0 || out.rows[i].load_factor < out.load_factor()))
      out.critical_row = static_cast<Index>(i);
  }
  return out;
}

}  // namespace roller
