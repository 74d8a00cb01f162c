// The condensed formulation of the interior-point backend (contact.ipopt.formulation =
// "condensed", the default; issue 7).
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
// from one interior solve. Ipopt then solves, with the friction fixed point of the full
// formulation around it (ipopt_backend.cpp, header comment "Coulomb"),
//   min q_C(d_C) + friction   s.t.  |x_i^n + u_i(x_k + d) - c| - R >= 0   (exact circle)
// with the same variables for friction (split s+- or regularised), the same scaling, options and
// force signs as the full formulation, and a dense Hessian S + sum lambda_i (I - n n^T)/rho. A
// second interior solve gives d_I. Because the gap of a node depends on that node's dofs only,
// the condensation is exact: for an elastic strip with small kinematics (Hertz) one linearisation
// solves the increment.
//
// Step and convergence. x_{k+1} = x_k + alpha d, alpha from backtracking on the l1 merit
// Pi + friction + nu sum max(0, -g_i) (nu = 2 max F_N), alpha = 1 whenever the predicted decrease
// is at round-off level. The increment has converged when a full step was taken, the friction
// fixed point converged on that linearisation, and the model was exact to tol:
//   |grad Pi(x_{k+1}) - g - K d|_inf <= tol F_ref
// (the inner NLP holds grad q = contact forces to Ipopt's tol, so grad Pi(x_{k+1}) = contact
// forces to tol as well: the full problem's KKT conditions).
//
// Working set. Candidates with a free dof whose gap at the start vector is within kReach l_step
// (l_step the increment's length scale, ipopt_common.hpp), or that carried a normal force in the
// previous increment. After each step every other candidate's gap is checked; a penetrating one
// joins the set (with every candidate within kReach l_step of the roller then) and the increment
// goes on with a new linearisation. So the constraint set of the solution is the full one.
//
// Failure of the formulation (singular K_II, no descent, linearisations ran out) sets
// stats["condensed_failed"]; IpoptBackend then solves the increment with the full formulation.
#include "ipopt_condensed.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include <IpIpoptApplication.hpp>
#include <IpSolveStatistics.hpp>
#include <IpTNLP.hpp>
#include <fmt/format.h>

#include "ipopt_common.hpp"
#include "roller/core/error.hpp"
#include "roller/solver/mumps_factorization.hpp"

namespace roller::ipopt_detail {

namespace {

constexpr int kMaxLinearisations = 30;
constexpr int kMaxBacktracks = 12;
// Working-set reach in units of l_step (see the header comment). The dense NLP costs ~m^3 per
// interior-point iteration: with 2 l_step Z1's first rolling increment at 1.1e5 dofs (a 600 mm
// roller moving 4 mm over a nearly flat strip) took 571 candidates into the set for 47 in contact
// and spent 28 of its 35 s in Ipopt; with 0.25 l_step 236 candidates, 2.2 of 7.6 s, same result.
constexpr Real kReach = 0.25;

// One linearisation: the working candidates, where their free dofs sit in d_C, and the
// condensed model.
struct Condensation {
  std::vector<int> working;             // candidate indices (each with >= 1 free dof)
  std::vector<Index> dofs;              // free-dof index of each entry of d_C
  std::vector<std::array<int, 2>> slot; // per working candidate: entry of d_C of x / y, -1 if prescribed
  std::vector<Vec2> base;               // per working candidate: its increment at x_k
  MatX schur;                           // S
  VecX gradient;                        // gc
};

// Friction set-up of one pass (a subset of the working candidates).
struct FrictionSetup {
  std::vector<int> friction;  // indices into Condensation::working
  std::vector<Real> weight;   // mu Fbar per friction entry
  bool split = true;
  Real eps = 1e-8;
};

// Solution (and warm start) of one pass.
struct DenseSolution {
  bool finalized = false;
  VecX z;                        // [d_C, s+, s-]
  std::vector<Real> normal;      // F_N per working candidate
  std::vector<Real> tangential;  // F_T per working candidate
};

class CondensedNlp : public Ipopt::TNLP {
 public:
  CondensedNlp(const IncrementProblem& problem, const Condensation& cond, const FrictionSetup& fs,
               const DenseSolution& start)
      : problem_(problem),
        cond_(cond),
        fs_(fs),
        start_(start),
        m_(static_cast<IIndex>(cond.dofs.size())),
        n_w_(static_cast<IIndex>(cond.working.size())),
        n_s_(fs.split ? static_cast<IIndex>(fs.friction.size()) : 0) {}

  const DenseSolution& solution() const { return solution_; }

  bool get_nlp_info(IIndex& n, IIndex& m, IIndex& nnz_jac_g, IIndex& nnz_h_lag, IndexStyleEnum& style) override {
    n = m_ + 2 * n_s_;
    m = n_w_ + n_s_;
    nnz_jac_g = 0;
    for (IIndex k = 0; k < n_w_; ++k) nnz_jac_g += n_free(k);
    for (IIndex j = 0; j < n_s_; ++j) nnz_jac_g += n_free(fs_.friction[j]) + 2;
    nnz_h_lag = m_ * (m_ + 1) / 2;
    style = TNLP::C_STYLE;
    return true;
  }

  bool get_bounds_info(IIndex n, Number* x_l, Number* x_u, IIndex m, Number* g_l, Number* g_u) override {
    const Number inf = 2e19;
    for (IIndex k = 0; k < n; ++k) {
      x_l[k] = k < m_ ? -inf : 0.0;
      x_u[k] = inf;
    }
    for (IIndex r = 0; r < m; ++r) {
      g_l[r] = 0.0;
      g_u[r] = r < n_w_ ? inf : 0.0;
    }
    return true;
  }

  bool get_starting_point(IIndex n, bool init_x, Number* x, bool init_z, Number* z_l, Number* z_u, IIndex m,
                          bool init_lambda, Number* lambda) override {
    if (init_x) {
      for (IIndex k = 0; k < m_; ++k) x[k] = start_.z.size() >= m_ ? start_.z(k) : 0.0;
      for (IIndex j = 0; j < n_s_; ++j) {
        const Real s = slip(fs_.friction[j], x);
        x[m_ + j] = std::max(s, 0.0);
        x[m_ + n_s_ + j] = std::max(-s, 0.0);
      }
    }
    if (init_z) {
      for (IIndex k = 0; k < n; ++k) z_l[k] = z_u[k] = 0.0;
      for (IIndex j = 0; j < n_s_; ++j) {
        const Real bound = fs_.weight[j];
        const Real ft = std::clamp(start_.tangential[fs_.friction[j]], -bound, bound);
        z_l[m_ + j] = bound + ft;
        z_l[m_ + n_s_ + j] = bound - ft;
      }
    }
    if (init_lambda) {
      for (IIndex r = 0; r < m; ++r) lambda[r] = 0.0;
      for (IIndex k = 0; k < n_w_; ++k) lambda[k] = -start_.normal[k];
      for (IIndex j = 0; j < n_s_; ++j) lambda[n_w_ + j] = -start_.tangential[fs_.friction[j]];
    }
    return true;
  }

  bool eval_f(IIndex /*n*/, const Number* x, bool /*new_x*/, Number& f) override {
    const Eigen::Map<const VecX> d(x, m_);
    f = cond_.gradient.dot(d) + 0.5 * d.dot(cond_.schur * d) + friction_energy(x);
    return std::isfinite(f);
  }

  bool eval_grad_f(IIndex n, const Number* x, bool /*new_x*/, Number* grad) override {
    const Eigen::Map<const VecX> d(x, m_);
    Eigen::Map<VecX> gd(grad, m_);
    gd = cond_.gradient + cond_.schur * d;
    for (IIndex k = m_; k < n; ++k) grad[k] = 0.0;
    for (std::size_t j = 0; j < fs_.friction.size(); ++j) {
      const Real w = fs_.weight[j];
      if (fs_.split) {
        grad[m_ + j] = w;
        grad[m_ + n_s_ + j] = w;
      } else {
        const int k = fs_.friction[j];
        const Real s = slip(k, x);
        add_on_slots(k, w * s / std::sqrt(s * s + fs_.eps * fs_.eps) * tangent(k), grad);
      }
    }
    return true;
  }

  bool eval_g(IIndex /*n*/, const Number* x, bool /*new_x*/, IIndex /*m*/, Number* g) override {
    const Real radius = problem_.roller().radius;
    for (IIndex k = 0; k < n_w_; ++k) g[k] = (position(k, x) - centre()).norm() - radius;
    for (IIndex j = 0; j < n_s_; ++j) g[n_w_ + j] = slip(fs_.friction[j], x) - x[m_ + j] + x[m_ + n_s_ + j];
    return true;
  }

  bool eval_jac_g(IIndex /*n*/, const Number* x, bool /*new_x*/, IIndex /*m*/, IIndex /*nele*/, IIndex* i_row,
                  IIndex* j_col, Number* values) override {
    IIndex e = 0;
    for (IIndex k = 0; k < n_w_; ++k) {
      Vec2 nrm = Vec2::Zero();
      if (values) nrm = (position(k, x) - centre()).normalized();
      for (int a = 0; a < 2; ++a) {
        const int s = cond_.slot[k][a];
        if (s < 0) continue;
        if (values) values[e] = nrm(a);
        else {
          i_row[e] = k;
          j_col[e] = s;
        }
        ++e;
      }
    }
    for (IIndex j = 0; j < n_s_; ++j) {
      const int k = fs_.friction[j];
      const Vec2 t = tangent(k);
      for (int a = 0; a < 2; ++a) {
        const int s = cond_.slot[k][a];
        if (s < 0) continue;
        if (values) values[e] = t(a);
        else {
          i_row[e] = n_w_ + j;
          j_col[e] = s;
        }
        ++e;
      }
      if (values) {
        values[e++] = -1.0;
        values[e++] = 1.0;
      } else {
        i_row[e] = n_w_ + j;
        j_col[e++] = m_ + j;
        i_row[e] = n_w_ + j;
        j_col[e++] = m_ + n_s_ + j;
      }
    }
    return true;
  }

  bool eval_h(IIndex /*n*/, const Number* x, bool /*new_x*/, Number obj_factor, IIndex /*m*/, const Number* lambda,
              bool /*new_lambda*/, IIndex /*nele*/, IIndex* i_row, IIndex* j_col, Number* values) override {
    // Dense lower triangle of the d_C block, row by row: entry (r, c), c <= r, at r (r+1)/2 + c.
    if (!values) {
      IIndex e = 0;
      for (IIndex r = 0; r < m_; ++r)
        for (IIndex c = 0; c <= r; ++c, ++e) {
          i_row[e] = r;
          j_col[e] = c;
        }
      return true;
    }
    IIndex e = 0;
    for (IIndex r = 0; r < m_; ++r)
      for (IIndex c = 0; c <= r; ++c, ++e) values[e] = obj_factor * cond_.schur(r, c);
    std::vector<int> friction_of(n_w_, -1);
    for (std::size_t j = 0; j < fs_.friction.size(); ++j) friction_of[fs_.friction[j]] = static_cast<int>(j);
    for (IIndex k = 0; k < n_w_; ++k) {
      const Vec2 dvec = position(k, x) - centre();
      const Real rho = dvec.norm();
      const Vec2 nrm = dvec / rho;
      Mat2 block = lambda[k] * (Mat2::Identity() - nrm * nrm.transpose()) / rho;
      const int j = friction_of[k];
      if (!fs_.split && j >= 0 && obj_factor != 0.0) {
        const Real s = slip(k, x);
        const Real q = s * s + fs_.eps * fs_.eps;
        const Vec2 t = tangent(k);
        block += obj_factor * fs_.weight[j] * fs_.eps * fs_.eps / (q * std::sqrt(q)) * t * t.transpose();
      }
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b <= a; ++b) {
          int r = cond_.slot[k][a], c = cond_.slot[k][b];
          if (r < 0 || c < 0) continue;
          if (r < c) std::swap(r, c);
          values[static_cast<IIndex>(r) * (r + 1) / 2 + c] += a == b ? block(a, a) : block(a, b);
        }
    }
    return true;
  }

  void finalize_solution(Ipopt::SolverReturn /*status*/, IIndex n, const Number* x, const Number* /*z_l*/,
                         const Number* /*z_u*/, IIndex /*m*/, const Number* /*g*/, const Number* lambda,
                         Number /*obj*/, const Ipopt::IpoptData* /*ip_data*/,
                         Ipopt::IpoptCalculatedQuantities* /*ip_cq*/) override {
    solution_.finalized = true;
    solution_.z = Eigen::Map<const VecX>(x, n);
    solution_.normal.assign(n_w_, 0.0);
    solution_.tangential.assign(n_w_, 0.0);
    for (IIndex k = 0; k < n_w_; ++k) solution_.normal[k] = -lambda[k];
    for (std::size_t j = 0; j < fs_.friction.size(); ++j) {
      const int k = fs_.friction[j];
      if (fs_.split) {
        solution_.tangential[k] = -lambda[n_w_ + static_cast<IIndex>(j)];
      } else {
        const Real s = slip(k, x);
        solution_.tangential[k] = -fs_.weight[j] * s / std::sqrt(s * s + fs_.eps * fs_.eps);
      }
    }
  }

 private:
  int n_free(int k) const { return (cond_.slot[k][0] >= 0) + (cond_.slot[k][1] >= 0); }
  const ContactCandidate& candidate(int k) const { return problem_.candidates()[cond_.working[k]]; }
  const Vec2& centre() const { return problem_.roller().end.centre; }
  Vec2 tangent(int k) const { return candidate(k).tangent; }
  Vec2 increment(int k, const Number* x) const {
    Vec2 u = cond_.base[k];
    for (int a = 0; a < 2; ++a)
      if (cond_.slot[k][a] >= 0) u(a) += x[cond_.slot[k][a]];
    return u;
  }
  Vec2 position(int k, const Number* x) const { return candidate(k).position + increment(k, x); }
  Real slip(int k, const Number* x) const {
    const RollerMotion& r = problem_.roller();
    return tangent(k).dot(increment(k, x) - r.dc()) - r.radius * r.dphi();
  }
  void add_on_slots(int k, const Vec2& v, Number* out) const {
    for (int a = 0; a < 2; ++a)
      if (cond_.slot[k][a] >= 0) out[cond_.slot[k][a]] += v(a);
  }
  Real friction_energy(const Number* x) const {
    Real e = 0.0;
    for (std::size_t j = 0; j < fs_.friction.size(); ++j) {
      if (fs_.split) {
        e += fs_.weight[j] * (x[m_ + j] + x[m_ + n_s_ + j]);
      } else {
        const Real s = slip(fs_.friction[j], x);
        e += fs_.weight[j] * std::sqrt(s * s + fs_.eps * fs_.eps);
      }
    }
    return e;
  }

  const IncrementProblem& problem_;
  const Condensation& cond_;
  const FrictionSetup& fs_;
  const DenseSolution& start_;
  IIndex m_, n_w_, n_s_;
  DenseSolution solution_;
};

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

// Merit of a point: strip energy + friction (with the pass's weights) + nu * penetration.
struct Merit {
  Real friction_weight_total = 0.0;
  Real value(const IncrementProblem& problem, const Condensation& cond, const FrictionSetup& fs, Real energy,
             const VecX& x, Real nu) const {
    Real m = energy;
    const auto& cands = problem.candidates();
    for (std::size_t j = 0; j < fs.friction.size(); ++j) {
      const Real s = problem.slip(cands[cond.working[fs.friction[j]]], x);
      m += fs.weight[j] * (fs.split ? std::abs(s) : std::sqrt(s * s + fs.eps * fs.eps));
    }
    for (const auto& c : cands)
      if (c.free_dof[0] >= 0 || c.free_dof[1] >= 0) m += nu * std::max(0.0, -problem.gap(c, x));
    return m;
  }
};

BackendResult failed(BackendResult result, NewtonStatus status, std::string message) {
  result.status = status;
  result.message = std::move(message);
  result.stats["condensed_failed"] = 1.0;
  return result;
}

}  // namespace

BackendResult solve_condensed(IncrementProblem& problem, const VecX& x0, const ContactOptions& options,
                              const LinearSolverOptions& linear) {
  const IpoptOptions& o = options.ipopt;
  const auto& cands = problem.candidates();
  const std::size_t n_c = cands.size();
  const Real mu = problem.roller().friction;
  BackendResult result;
  result.x = x0;
  result.contact.assign(n_c, NodeContact{});

  Scales scales;
  VecX x = x0, g;
  SparseMatrix k_eff;
  Real energy = 0.0;
  try {
    energy = problem.strip_energy(x, &g, &k_eff);
    scales = increment_scales(problem, x0);  // after an evaluation: force_scale reads its reactions
  } catch (const NumericalError& error) {
    return failed(result, NewtonStatus::Failure,
                  fmt::format("ipopt backend: the strip cannot be evaluated at the start vector ({}); use smaller steps",
                              error.what()));
  }
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = make_application(o, scales);
  if (app->Initialize("") != Ipopt::Solve_Succeeded)
    return failed(result, NewtonStatus::Failure, "ipopt backend: Ipopt failed to initialise");

  const Real reach = kReach * scales.length;
  NormalForceFixedPoint fixed_point(problem, o, scales.force);
  std::vector<Real> normal(n_c, 0.0), tangential(n_c, 0.0);  // per candidate, last pass
  for (std::size_t i = 0; i < n_c; ++i) {
    normal[i] = std::max(cands[i].normal_force_guess, 0.0);
    tangential[i] = cands[i].tangential_force;
  }
  std::vector<Real> fbar_used = fixed_point.fbar();
  std::vector<bool> has_friction(n_c, false);
  MumpsSolver solver(MumpsSolver::Symmetry::Symmetric, linear);
  Condensation cond;
  cond.working = working_set(problem, x, reach, {});
  const int max_passes = (mu > 0.0 && o.fixed_point == "converge") ? o.fixed_point_max : 1;
  double ipopt_time = 0.0;
  int total_passes = 0, linearisations = 0, passes_last = 0;
  bool converged = false, fixed_point_converged = false;
  Real model_error = 0.0;
  Real n_friction = 0.0;

  for (int outer = 1; outer <= kMaxLinearisations && !converged; ++outer) {
    linearisations = outer;
    // Condensation of K onto the working candidates' free dofs.
    const std::size_t n_w = cond.working.size();
    cond.dofs.clear();
    cond.slot.assign(n_w, {-1, -1});
    cond.base.assign(n_w, Vec2::Zero());
    for (std::size_t k = 0; k < n_w; ++k) {
      const ContactCandidate& c = cands[cond.working[k]];
      cond.base[k] = problem.increment(c, x);
      for (int a = 0; a < 2; ++a)
        if (c.free_dof[a] >= 0) {
          cond.slot[k][a] = static_cast<int>(cond.dofs.size());
          cond.dofs.push_back(c.free_dof[a]);
        }
    }
    if (!solver.factorize_with_schur(k_eff, cond.dofs, &cond.schur))
      return failed(result, NewtonStatus::Failure,
                    fmt::format("ipopt backend (condensed): the strip tangent cannot be factorised on its interior "
                                "dofs ({}): the strip is held against rigid-body motion only through contact",
                                solver.message()));
    ++result.factorizations;
    const VecX y = solver.solve_interior(-g);
    const VecX ky = k_eff * y;
    const auto m = static_cast<Index>(cond.dofs.size());
    cond.gradient.resize(m);
    for (Index s = 0; s < m; ++s) cond.gradient(s) = g(cond.dofs[s]) + ky(cond.dofs[s]);

    // Friction fixed point on this linearisation (Tresca passes on the dense NLP).
    fixed_point.restart();
    DenseSolution start;
    start.z = VecX::Zero(m);
    start.normal.assign(n_w, 0.0);
    start.tangential.assign(n_w, 0.0);
    for (std::size_t k = 0; k < n_w; ++k) {
      start.normal[k] = normal[cond.working[k]];
      start.tangential[k] = tangential[cond.working[k]];
    }
    DenseSolution last;
    FrictionSetup fs;
    fixed_point_converged = mu == 0.0 || o.fixed_point == "single";
    // Far from convergence one pass per linearisation suffices (Fbar follows the linearisations);
    // the fixed point is converged once the model is close (model error <= 1e-3).
    const int passes_here = outer > 1 && model_error <= 1e-3 ? max_passes : 1;
    for (int pass = 1; pass <= passes_here; ++pass) {
      fs = FrictionSetup{};
      fs.split = o.friction == "split";
      fs.eps = o.regularization;
      const Real force_tol = fixed_point.force_tol();
      for (std::size_t k = 0; k < n_w; ++k) {
        const Real fb = fixed_point.fbar()[cond.working[k]];
        if (mu > 0.0 && fb > force_tol) {
          fs.friction.push_back(static_cast<int>(k));
          fs.weight.push_back(mu * fb);
        }
      }
      if (m == 0) {  // no working candidate: the strip alone
        last.finalized = true;
        last.z = VecX::Zero(0);
        last.normal.assign(0, 0.0);
        last.tangential.assign(0, 0.0);
        fixed_point_converged = true;
        break;
      }
      set_warm_start(*app, pass > 1 || (outer > 1 && o.warm_start));
      Ipopt::SmartPtr<CondensedNlp> nlp = new CondensedNlp(problem, cond, fs, start);
      const auto t0 = std::chrono::steady_clock::now();
      const Ipopt::ApplicationReturnStatus status = app->OptimizeTNLP(GetRawPtr(nlp));
      ipopt_time += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      ++total_passes;
      int iterations = 0;
      if (IsValid(app->Statistics())) iterations = app->Statistics()->IterationCount();
      result.iterations += iterations;
      const StatusText st = map_status(status, iterations, o, "");
      if (st.status != NewtonStatus::Converged || !nlp->solution().finalized) {
        // Ipopt's own failure on the small NLP: reported as such (the driver cuts the step), no
        // fall-back to the full formulation, which would meet the same NLP.
        result.status = st.status == NewtonStatus::Converged ? NewtonStatus::Failure : st.status;
        result.message = fmt::format("{} (condensed NLP, linearisation {}, friction pass {})",
                                     st.status == NewtonStatus::Converged ? "Ipopt returned no solution" : st.message,
                                     outer, pass);
        return result;
      }
      passes_last = pass;
      if (status == Ipopt::Solved_To_Acceptable_Level) result.stats["acceptable_level"] = 1.0;
      last = nlp->solution();
      fbar_used = fixed_point.fbar();
      std::vector<Real> pass_normal(n_c, 0.0);
      for (std::size_t k = 0; k < n_w; ++k) pass_normal[cond.working[k]] = last.normal[k];
      const bool done = fixed_point.update(pass_normal);
      if (done || mu == 0.0 || o.fixed_point == "single") {
        fixed_point_converged = done;
        break;
      }
      start = last;
    }
    std::fill(normal.begin(), normal.end(), 0.0);
    std::fill(tangential.begin(), tangential.end(), 0.0);
    std::fill(has_friction.begin(), has_friction.end(), false);
    Real fn_max = 0.0;
    for (std::size_t k = 0; k < n_w; ++k) {
      normal[cond.working[k]] = last.normal[k];
      tangential[cond.working[k]] = last.tangential[k];
      fn_max = std::max(fn_max, last.normal[k]);
    }
    for (const int k : fs.friction) has_friction[cond.working[k]] = true;
    n_friction = static_cast<Real>(fs.friction.size());

    // The whole step: d_C from Ipopt, d_I from the interior solve.
    VecX e = VecX::Zero(x.size());
    for (Index s = 0; s < m; ++s) e(cond.dofs[s]) = last.z(s);
    const VecX ke = k_eff * e;
    VecX d = solver.solve_interior(-g - ke) + e;
    const VecX kd = k_eff * d;
    const Real model_change = g.dot(d) + 0.5 * d.dot(kd);

    // Backtracking on the merit function.
    const Real nu = 2.0 * std::max(fn_max, 1e-6 * scales.force);
    const Merit merit;
    const Real phi0 = merit.value(problem, cond, fs, energy, x, nu);
    Real pred = -model_change;
    {
      VecX x1 = x + d;
      pred += merit.value(problem, cond, fs, 0.0, x, nu) - merit.value(problem, cond, fs, 0.0, x1, nu);
    }
    const Real roundoff = 1e-10 * (std::abs(energy) + scales.force * scales.length);
    Real alpha = 1.0;
    VecX x_new, g_new;
    Real energy_new = 0.0;
    bool accepted = false;
    std::string evaluation_error;
    Real next_alpha = 0.5;
    for (int b = 0; b <= kMaxBacktracks && !accepted; ++b, alpha = next_alpha) {
      next_alpha = 0.5 * alpha;
      x_new = x + alpha * d;
      try {
        energy_new = problem.strip_energy(x_new, &g_new, nullptr);
      } catch (const NumericalError& error) {
        evaluation_error = error.what();
        continue;
      }
      const Real phi = merit.value(problem, cond, fs, energy_new, x_new, nu);
      accepted = std::isfinite(phi) && (pred <= roundoff || phi <= phi0 - 1e-4 * alpha * pred ||
                                        (alpha == 1.0 && phi <= phi0 + roundoff));
      // Minimiser of the parabola through phi0 (slope -pred) and phi(alpha), kept in [0.1, 0.9] alpha.
      if (!accepted && std::isfinite(phi) && pred > 0.0) {
        const Real curvature = phi - phi0 + alpha * pred;
        if (curvature > 0.0) next_alpha = std::clamp(0.5 * pred * alpha * alpha / curvature, 0.1 * alpha, 0.9 * alpha);
      }
      if (accepted) break;
    }
    if (!accepted)
      return failed(result, NewtonStatus::NotConverged,
                    fmt::format("ipopt backend (condensed): no descent along the step of linearisation {}{}; "
                                "use smaller steps",
                                outer, evaluation_error.empty() ? "" : " (" + evaluation_error + ")"));
    model_error = (g_new - g - alpha * kd).lpNorm<Eigen::Infinity>() / scales.force;
    x = x_new;
    g = g_new;
    energy = energy_new;

    // Candidates outside the working set must not penetrate.
    bool grew = false;
    {
      std::vector<char> in(n_c, 0);
      for (const int i : cond.working) in[i] = 1;
      for (std::size_t i = 0; i < n_c && !grew; ++i)
        if (!in[i] && (cands[i].free_dof[0] >= 0 || cands[i].free_dof[1] >= 0) && problem.gap(cands[i], x) < 0.0)
          grew = true;
      if (grew) cond.working = working_set(problem, x, reach, cond.working);
    }
    converged = alpha == 1.0 && !grew && fixed_point_converged && model_error <= o.tol;
    if (!converged) {
      try {
        energy = problem.strip_energy(x, &g, &k_eff);
      } catch (const NumericalError& error) {
        return failed(result, NewtonStatus::Failure,
                      fmt::format("ipopt backend (condensed): the strip tangent cannot be evaluated ({}); use "
                                  "smaller steps",
                                  error.what()));
      }
    }
  }
  result.x = x;
  result.stats["fixed_point_iterations"] = passes_last;  // Coulomb passes on the last linearisation
  result.stats["nlp_solves"] = total_passes;
  result.stats["nlp_variables"] = static_cast<Real>(cond.dofs.size()) + (o.friction == "split" ? 2.0 * n_friction : 0.0);
  result.stats["nlp_constraints"] = static_cast<Real>(cond.working.size()) + (o.friction == "split" ? n_friction : 0.0);
  result.stats["linearisations"] = linearisations;
  result.stats["condensed_dofs"] = static_cast<Real>(cond.dofs.size());
  result.stats["ipopt_time_s"] = ipopt_time;
  if (!report_increment(problem, x, normal, tangential, fbar_used, has_friction, scales, &result)) {
    result.stats["condensed_failed"] = 1.0;
    return result;
  }
  if (!converged) {
    if (!fixed_point_converged) {
      result.status = NewtonStatus::NotConverged;
      result.message = fixed_point_message(total_passes, fixed_point, o);
      return result;
    }
    return failed(result, NewtonStatus::NotConverged,
                  fmt::format("ipopt backend (condensed): {} linearisations without convergence (model error "
                              "{:.3g} against contact.ipopt.tol = {:g}); use smaller steps",
                              kMaxLinearisations, model_error, o.tol));
  }
  result.status = NewtonStatus::Converged;
  result.message = fmt::format("Ipopt converged: {} linearisation{}, {} interior-point iterations ({} pass{})",
                               linearisations, linearisations == 1 ? "" : "s", result.iterations, total_passes,
                               total_passes == 1 ? "" : "es");
  return result;
}

}  // namespace roller::ipopt_detail
