// The interior-point contact backend (SPEC §1, §2.4, §2.7; issue 4).
//
// One increment = one or more nonlinear programs (NLP), each solved by Ipopt with MUMPS.
//
// Variables  z = [x, s+, s-]: x the free-dof increments; for the "split" friction one pair of
//            auxiliaries s+_j, s-_j >= 0 per friction candidate j (none when mu = 0, none for
//            the "regularized" friction, none for a candidate whose normal-force estimate is
//            zero: its friction term vanishes and a zero-cost pair would be unbounded under
//            the barrier).
// Objective  f(z) = Pi(x) + sum_j mu Fbar_j (s+_j + s-_j)                      ("split")
//            f(x) = Pi(x) + sum_j mu Fbar_j sqrt(slip_j(x)^2 + eps^2)          ("regularized")
//            with Pi the strip's incremental potential (IncrementProblem::strip_energy).
// Constraints g_i(x) = |x_i^n + u_i - c^{n+1}| - R >= 0 for every candidate with a free dof
//            (exact circle); slip_j(x) - s+_j + s-_j = 0 for the split friction (linear).
// Derivatives are exact: grad g_i = n_i on the node's free dofs, and the Hessian of the
//            Lagrangian is sigma_f (K + friction) + sum_i lambda_i (I - n_i n_i^T) / |x_i - c|
//            (lower triangle; the gap is curved, its Hessian is not zero); the regularized
//            friction adds sigma_f mu Fbar eps^2 / (slip^2 + eps^2)^(3/2) t t^T.
// Forces     Ipopt's Lagrangian is f + lambda^T g, so at a KKT point grad Pi = -sum lambda_i n_i
//            - sum lambda_j t_j: the force of the roller on the strip node is F_N n + F_T t with
//            F_N = -lambda_gap >= 0 and F_T = -lambda_slip (split; |F_T| <= mu Fbar from the
//            bounds' multipliers) or F_T = -mu Fbar slip / sqrt(slip^2 + eps^2) (regularized).
// Coulomb    Fixed point on the normal force (SPEC §2.4, thesis §2.1.3): pass 1 takes Fbar from
//            the candidates' normal_force_guess, pass k+1 from pass k's F_N. fixed_point =
//            "converge" repeats until max|F_N - Fbar| <= max(fixed_point_tol * max F_N, F_tol)
//            with F_tol (below) the resolution of a pass's multipliers: changes below it are the
//            inner solves' noise, not the fixed point's (measured on Z1 refine 2: warm-started
//            passes of 1-2 iterations moved an F_N of 1454 N by ~1e-2 N back and forth or in a
//            slow drift, the 30 passes ran out and the step was cut, which moved the roller force
//            by 3 %). "single" stops after one pass (the thesis's explicit variant). Pass k+1
//            starts from pass k's solution. stats["fixed_point_iterations"] = number of passes.
//
// Scaling. Ipopt's tolerances are absolute in the units of the scaled NLP. The objective is
// scaled by 1/F_ref with F_ref = max(IncrementProblem::force_scale(x0), E* l_step): the first
// is the size of the loads/reactions/start-of-step internal forces, the second the nodal force
// of a surface element (width ~ depth) displaced by the step's length scale
//   l_step = max(|dc|, R |dphi|, |full increment at x0|_inf, max penetration at x0, 1e-9 R).
// So contact.ipopt.tol is a relative equilibrium tolerance (dual infeasibility / F_ref), and a
// length tolerance in mm for gaps and complementarity (constraints are not scaled: mm).
//
// Ipopt options (beyond contact.ipopt.*): linear_solver mumps with MUMPS's default ordering (on
// this strip matrix it beat SCOTCH, mumps_pivot_order 3, by ~25 % in CPU at 1.3e4 and 5.2e4
// unknowns — the opposite of the membrane prototype in notes/ipopt-on-debian.md);
// hessian_approximation exact; bound_relax_factor 0 and honor_original_bounds yes (no
// constraint violation left by relaxed bounds); line_search_method penalty (an exact-penalty
// merit function instead of the default filter: the curved gap leaves a constraint violation
// ~1e-9 mm after every step, and the filter then accepts any full step that lowers it whatever
// the energy does. On Z1 that let Newton 2-cycle between plastic loading and unloading along a
// soft mode (the part of the strip beyond the roller sliding in x, held only by a plastic zone
// through the thickness, when no friction holds it): frictionless Z1 failed at step 4 after 500
// iterations; with the merit function every step must lower energy + violation, and Z1 needs
// 15-27 iterations per step with or without friction, the Z2 and friction tests 3x fewer); obj_scaling_factor 1/F_ref; dual_inf_tol and
// compl_inf_tol (Ipopt's unscaled checks): the first raised to 100 tol F_ref so that it never binds,
// the second set to tol F_ref so that max F_N g / F_ref ends below tol
// before tol does; sb yes (no banner); Initialize("") so that a stray ./ipopt.opt is ignored.
// Warm start (warm_start_init_point, mu_init and pushes 1e-6): pass 1 only when
// contact.ipopt.warm_start (multipliers from normal_force_guess / tangential_force), every later
// fixed-point pass always (from the previous pass; this cut the friction tests' iterations ~3x).
// Solved_To_Acceptable_Level counts as converged and is flagged in stats["acceptable_level"].
//
// Status per candidate, with F_tol = 1e-6 max(F_ref, max F_N):
//   open   if F_N <= F_tol and g > 0;
//   stick  if |slip| <= l_step (1 - |F_T| / (mu Fbar))   (candidates with a friction term)
//          or |slip| <= 1e-6 l_step                        (frictionless candidates);
//   slip   otherwise.
// Interior-point multipliers of inactive constraints are small but not zero (~ barrier / gap);
// F_tol separates them from real contact forces, and only candidates with Fbar > F_tol carry
// friction in the next pass. Likewise a sticking node keeps an interior-point slip
// ~ barrier / (mu Fbar - |F_T|) (measured ~1e-9 mm, ~1e-6 of the step, on the Cattaneo scene),
// so a fixed slip tolerance would misread it: the slip is weighed against the step's length
// scale times the node's distance from the Coulomb bound. A node at the bound (|F_T| = mu Fbar)
// slips for any non-zero slip; at a converged solution |slip| (mu Fbar - |F_T|) ~ barrier, so
// the two cases separate by many orders of magnitude. Candidates whose dofs are all prescribed get no constraint (their
// gap cannot change); they are reported with F_N = 0 and their gap.
//
// strip_energy may throw NumericalError (inverted element at a trial point): eval_f/eval_grad_f
// return false so that Ipopt cuts its step; eval_h returning false ends the solve (Ipopt cannot
// recover from that) and is reported with the cause.
#include "roller/contact/ipopt_backend.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <limits>
#include <map>
#include <stdexcept>

#include <IpIpoptApplication.hpp>
#include <IpJournalist.hpp>
#include <IpSolveStatistics.hpp>
#include <IpTNLP.hpp>
#include <fmt/format.h>

#include "roller/core/error.hpp"
#include "ipopt_common.hpp"
#include "ipopt_condensed.hpp"

namespace roller {

namespace {

using namespace ipopt_detail;

// ---------------------------------------------------------------------------------------------
// Data shared by all passes of one increment.

// Lower triangle of the strip Hessian's fixed pattern: value slots and (row, col).
struct StripPattern {
  std::vector<int> slot;
  std::vector<IIndex> row, col;
  std::vector<int> inner;  // full pattern, to check that it does not change between evaluations
  std::vector<int> outer;
};

StripPattern make_pattern(SparseMatrix hessian) {
  hessian.makeCompressed();
  StripPattern p;
  const int* outer = hessian.outerIndexPtr();
  const int* inner = hessian.innerIndexPtr();
  for (int k = 0; k < hessian.outerSize(); ++k)
    for (int q = outer[k]; q < outer[k + 1]; ++q)
      if (inner[q] >= k) {
        p.slot.push_back(q);
        p.row.push_back(inner[q]);
        p.col.push_back(k);
      }
  p.inner.assign(inner, inner + hessian.nonZeros());
  p.outer.assign(outer, outer + hessian.outerSize() + 1);
  return p;
}

bool same_pattern(const StripPattern& p, const SparseMatrix& h) {
  return h.isCompressed() && static_cast<std::size_t>(h.nonZeros()) == p.inner.size() &&
         std::equal(p.outer.begin(), p.outer.end(), h.outerIndexPtr()) &&
         std::equal(p.inner.begin(), p.inner.end(), h.innerIndexPtr());
}

// One NLP pass: which candidates carry a gap constraint and which a friction term.
struct PassSetup {
  std::vector<int> active;     // candidate indices with a gap constraint (>= 1 free dof)
  std::vector<int> friction;   // candidate indices with a friction term (subset of active)
  std::vector<Real> fbar;      // normal-force estimate per candidate (all candidates)
  Real mu = 0.0;
  bool split = true;
  Real eps = 1e-8;
};

PassSetup make_setup(const IncrementProblem& problem, const ContactOptions& options,
                     const std::vector<Real>& fbar, Real force_tol) {
  PassSetup s;
  s.mu = problem.roller().friction;
  s.split = options.ipopt.friction == "split";
  s.eps = options.ipopt.regularization;
  s.fbar = fbar;
  const auto& cands = problem.candidates();
  for (std::size_t i = 0; i < cands.size(); ++i) {
    if (cands[i].free_dof[0] < 0 && cands[i].free_dof[1] < 0) continue;
    s.active.push_back(static_cast<int>(i));
    if (s.mu > 0.0 && fbar[i] > force_tol) s.friction.push_back(static_cast<int>(i));
  }
  return s;
}

// Start values for one pass (primal, and multipliers for a warm start).
struct PassStart {
  VecX x;                       // free dofs
  std::vector<Real> normal;     // F_N guess per candidate
  std::vector<Real> tangential; // F_T guess per candidate
  bool warm = false;
};

// Solution of one pass.
struct PassSolution {
  bool finalized = false;
  VecX z;                       // all NLP variables
  std::vector<Real> normal;     // F_N per candidate (0 for candidates without a constraint)
  std::vector<Real> tangential; // F_T per candidate
};

// ---------------------------------------------------------------------------------------------
// The TNLP adapter.

class ContactNlp : public Ipopt::TNLP {
 public:
  ContactNlp(IncrementProblem& problem, const PassSetup& setup, const StripPattern& pattern,
             const PassStart& start)
      : problem_(problem),
        setup_(setup),
        pattern_(pattern),
        start_(start),
        n_x_(static_cast<IIndex>(problem.n_free())),
        n_a_(static_cast<IIndex>(setup.active.size())),
        n_f_(static_cast<IIndex>(setup.friction.size())),
        n_s_(setup.split ? n_f_ : 0),
        x_cache_(VecX::Zero(problem.n_free())) {
    const auto& cands = problem.candidates();
    for (const int i : setup.active) {
      Block b;
      b.candidate = i;
      for (int k = 0; k < 2; ++k)
        if (cands[i].free_dof[k] >= 0) b.comp[b.n_free++] = k;
      blocks_.push_back(b);
    }
    friction_block_.assign(cands.size(), -1);
    for (std::size_t j = 0; j < setup.friction.size(); ++j) friction_block_[setup.friction[j]] = static_cast<int>(j);
    active_row_.assign(cands.size(), -1);
    for (std::size_t k = 0; k < setup.active.size(); ++k) active_row_[setup.active[k]] = static_cast<int>(k);
  }

  IIndex n_variables() const { return n_x_ + 2 * n_s_; }
  IIndex n_constraints() const { return n_a_ + n_s_; }
  const PassSolution& solution() const { return solution_; }
  const std::string& evaluation_error() const { return evaluation_error_; }

  bool get_nlp_info(IIndex& n, IIndex& m, IIndex& nnz_jac_g, IIndex& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = n_variables();
    m = n_constraints();
    nnz_jac_g = 0;
    nnz_h_lag = static_cast<IIndex>(pattern_.slot.size());
    for (const Block& b : blocks_) {
      nnz_jac_g += b.n_free;
      nnz_h_lag += b.n_free == 2 ? 3 : 1;
    }
    for (const int i : setup_.friction) {
      (void)i;
      if (setup_.split) nnz_jac_g += block_of(i).n_free + 2;
    }
    index_style = TNLP::C_STYLE;
    return true;
  }

  bool get_bounds_info(IIndex n, Number* x_l, Number* x_u, IIndex m, Number* g_l, Number* g_u) override {
    const Number inf = 2e19;  // beyond nlp_upper_bound_inf (1e19): no bound
    for (IIndex k = 0; k < n; ++k) {
      x_l[k] = k < n_x_ ? -inf : 0.0;
      x_u[k] = inf;
    }
    for (IIndex r = 0; r < m; ++r) {
      g_l[r] = 0.0;
      g_u[r] = r < n_a_ ? inf : 0.0;
    }
    return true;
  }

  bool get_starting_point(IIndex n, bool init_x, Number* x, bool init_z, Number* z_l, Number* z_u,
                          IIndex m, bool init_lambda, Number* lambda) override {
    const auto& cands = problem_.candidates();
    if (init_x) {
      for (IIndex k = 0; k < n_x_; ++k) x[k] = start_.x(k);
      for (IIndex j = 0; j < n_s_; ++j) {
        const Real s = slip(cands[setup_.friction[j]], x);
        x[n_x_ + j] = std::max(s, 0.0);
        x[n_x_ + n_s_ + j] = std::max(-s, 0.0);
      }
    }
    if (init_z) {
      // Bound multipliers of s+- from stationarity: z+ = mu Fbar + F_T, z- = mu Fbar - F_T.
      for (IIndex k = 0; k < n; ++k) z_l[k] = z_u[k] = 0.0;
      for (IIndex j = 0; j < n_s_; ++j) {
        const int i = setup_.friction[j];
        const Real bound = setup_.mu * setup_.fbar[i];
        const Real ft = std::clamp(start_.tangential[i], -bound, bound);
        z_l[n_x_ + j] = bound + ft;
        z_l[n_x_ + n_s_ + j] = bound - ft;
      }
    }
    if (init_lambda) {
      for (IIndex r = 0; r < m; ++r) lambda[r] = 0.0;
      for (IIndex k = 0; k < n_a_; ++k) lambda[k] = -start_.normal[setup_.active[k]];
      for (IIndex j = 0; j < n_s_; ++j) lambda[n_a_ + j] = -start_.tangential[setup_.friction[j]];
    }
    return true;
  }

  bool eval_f(IIndex /*n*/, const Number* x, bool /*new_x*/, Number& obj_value) override {
    if (!update_strip(x)) return false;
    obj_value = energy_ + friction_energy(x);
    return std::isfinite(obj_value);
  }

  bool eval_grad_f(IIndex n, const Number* x, bool /*new_x*/, Number* grad_f) override {
    if (!update_strip(x)) return false;
    for (IIndex k = 0; k < n_x_; ++k) grad_f[k] = gradient_(k);
    for (IIndex k = n_x_; k < n; ++k) grad_f[k] = 0.0;
    const auto& cands = problem_.candidates();
    for (std::size_t j = 0; j < setup_.friction.size(); ++j) {
      const int i = setup_.friction[j];
      const Real w = setup_.mu * setup_.fbar[i];
      if (setup_.split) {
        grad_f[n_x_ + j] = w;
        grad_f[n_x_ + n_s_ + j] = w;
      } else {
        const Real s = slip(cands[i], x);
        const Real d = w * s / std::sqrt(s * s + setup_.eps * setup_.eps);
        add_on_free(cands[i], d * cands[i].tangent, grad_f);
      }
    }
    return true;
  }

  bool eval_g(IIndex /*n*/, const Number* x, bool /*new_x*/, IIndex /*m*/, Number* g) override {
    const auto& cands = problem_.candidates();
    const Real radius = problem_.roller().radius;
    for (IIndex k = 0; k < n_a_; ++k) g[k] = (position(cands[setup_.active[k]], x) - centre()).norm() - radius;
    for (IIndex j = 0; j < n_s_; ++j)
      g[n_a_ + j] = slip(cands[setup_.friction[j]], x) - x[n_x_ + j] + x[n_x_ + n_s_ + j];
    return true;
  }

  bool eval_jac_g(IIndex /*n*/, const Number* x, bool /*new_x*/, IIndex /*m*/, IIndex /*nele_jac*/,
                  IIndex* i_row, IIndex* j_col, Number* values) override {
    const auto& cands = problem_.candidates();
    IIndex e = 0;
    for (IIndex k = 0; k < n_a_; ++k) {
      const Block& b = blocks_[k];
      const ContactCandidate& c = cands[b.candidate];
      Vec2 nrm = Vec2::Zero();
      if (values) nrm = (position(c, x) - centre()).normalized();
      for (int a = 0; a < b.n_free; ++a, ++e) {
        if (values) values[e] = nrm(b.comp[a]);
        else {
          i_row[e] = k;
          j_col[e] = static_cast<IIndex>(c.free_dof[b.comp[a]]);
        }
      }
    }
    for (IIndex j = 0; j < n_s_; ++j) {
      const IIndex r = n_a_ + j;
      const Block& b = block_of(setup_.friction[j]);
      const ContactCandidate& c = cands[b.candidate];
      for (int a = 0; a < b.n_free; ++a, ++e) {
        if (values) values[e] = c.tangent(b.comp[a]);
        else {
          i_row[e] = r;
          j_col[e] = static_cast<IIndex>(c.free_dof[b.comp[a]]);
        }
      }
      if (values) {
        values[e++] = -1.0;
        values[e++] = 1.0;
      } else {
        i_row[e] = r;
        j_col[e++] = n_x_ + j;
        i_row[e] = r;
        j_col[e++] = n_x_ + n_s_ + j;
      }
    }
    return true;
  }

  bool eval_h(IIndex /*n*/, const Number* x, bool /*new_x*/, Number obj_factor, IIndex /*m*/,
              const Number* lambda, bool /*new_lambda*/, IIndex /*nele_hess*/, IIndex* i_row,
              IIndex* j_col, Number* values) override {
    const std::size_t n_strip = pattern_.slot.size();
    if (!values) {
      std::copy(pattern_.row.begin(), pattern_.row.end(), i_row);
      std::copy(pattern_.col.begin(), pattern_.col.end(), j_col);
      IIndex e = static_cast<IIndex>(n_strip);
      const auto& cands = problem_.candidates();
      for (const Block& b : blocks_) {
        const ContactCandidate& c = cands[b.candidate];
        for (int a = 0; a < b.n_free; ++a)
          for (int bb = 0; bb <= a; ++bb, ++e) {
            const IIndex p = static_cast<IIndex>(c.free_dof[b.comp[a]]);
            const IIndex q = static_cast<IIndex>(c.free_dof[b.comp[bb]]);
            i_row[e] = std::max(p, q);
            j_col[e] = std::min(p, q);
          }
      }
      return true;
    }
    // Strip part.
    if (obj_factor != 0.0) {
      load_x(x);
      try {
        problem_.strip_energy(x_eval_, nullptr, &hessian_);
      } catch (const NumericalError& error) {
        evaluation_error_ = error.what();
        return false;
      }
      if (!same_pattern(pattern_, hessian_))
        throw std::logic_error("ipopt backend: the strip Hessian's sparsity pattern changed between evaluations");
      const Real* h = hessian_.valuePtr();
      for (std::size_t e = 0; e < n_strip; ++e) values[e] = obj_factor * h[pattern_.slot[e]];
    } else {
      std::fill_n(values, n_strip, 0.0);
    }
    // Gap curvature and regularized friction, per candidate block.
    const auto& cands = problem_.candidates();
    IIndex e = static_cast<IIndex>(n_strip);
    for (std::size_t k = 0; k < blocks_.size(); ++k) {
      const Block& b = blocks_[k];
      const ContactCandidate& c = cands[b.candidate];
      const Vec2 d = position(c, x) - centre();
      const Real rho = d.norm();
      const Vec2 nrm = d / rho;
      Mat2 block = lambda[k] * (Mat2::Identity() - nrm * nrm.transpose()) / rho;
      const int j = friction_block_[b.candidate];
      if (!setup_.split && j >= 0 && obj_factor != 0.0) {
        const Real s = slip(c, x);
        const Real q = s * s + setup_.eps * setup_.eps;
        const Real curvature = setup_.mu * setup_.fbar[b.candidate] * setup_.eps * setup_.eps / (q * std::sqrt(q));
        block += obj_factor * curvature * c.tangent * c.tangent.transpose();
      }
      for (int a = 0; a < b.n_free; ++a)
        for (int bb = 0; bb <= a; ++bb, ++e) values[e] = block(b.comp[a], b.comp[bb]);
    }
    return true;
  }

  void finalize_solution(Ipopt::SolverReturn /*status*/, IIndex n, const Number* x, const Number* /*z_l*/,
                         const Number* /*z_u*/, IIndex /*m*/, const Number* /*g*/, const Number* lambda,
                         Number /*obj_value*/, const Ipopt::IpoptData* /*ip_data*/,
                         Ipopt::IpoptCalculatedQuantities* /*ip_cq*/) override {
    const auto& cands = problem_.candidates();
    solution_.finalized = true;
    solution_.z = Eigen::Map<const VecX>(x, n);
    solution_.normal.assign(cands.size(), 0.0);
    solution_.tangential.assign(cands.size(), 0.0);
    for (IIndex k = 0; k < n_a_; ++k) solution_.normal[setup_.active[k]] = -lambda[k];
    for (std::size_t j = 0; j < setup_.friction.size(); ++j) {
      const int i = setup_.friction[j];
      if (setup_.split) {
        solution_.tangential[i] = -lambda[n_a_ + static_cast<IIndex>(j)];
      } else {
        const Real s = slip(cands[i], x);
        solution_.tangential[i] = -setup_.mu * setup_.fbar[i] * s / std::sqrt(s * s + setup_.eps * setup_.eps);
      }
    }
  }

 private:
  struct Block {
    int candidate = -1;
    int n_free = 0;
    int comp[2] = {-1, -1};  // free components (0 = x, 1 = y)
  };

  const Block& block_of(int candidate) const { return blocks_[active_row_[candidate]]; }
  const Vec2& centre() const { return problem_.roller().end.centre; }

  // Kinematics of IncrementProblem (increment_problem.hpp) on Ipopt's raw variable array.
  Vec2 increment(const ContactCandidate& c, const Number* x) const {
    Vec2 u = c.prescribed;
    for (int k = 0; k < 2; ++k)
      if (c.free_dof[k] >= 0) u(k) = x[c.free_dof[k]];
    return u;
  }
  Vec2 position(const ContactCandidate& c, const Number* x) const { return c.position + increment(c, x); }
  Real slip(const ContactCandidate& c, const Number* x) const {
    const RollerMotion& r = problem_.roller();
    return c.tangent.dot(increment(c, x) - r.dc()) - r.radius * r.dphi();
  }
  void add_on_free(const ContactCandidate& c, const Vec2& v, Number* out) const {
    for (int k = 0; k < 2; ++k)
      if (c.free_dof[k] >= 0) out[c.free_dof[k]] += v(k);
  }

  Real friction_energy(const Number* x) const {
    Real e = 0.0;
    const auto& cands = problem_.candidates();
    for (std::size_t j = 0; j < setup_.friction.size(); ++j) {
      const int i = setup_.friction[j];
      const Real w = setup_.mu * setup_.fbar[i];
      if (setup_.split) {
        e += w * (x[n_x_ + j] + x[n_x_ + n_s_ + j]);
      } else {
        const Real s = slip(cands[i], x);
        e += w * std::sqrt(s * s + setup_.eps * setup_.eps);
      }
    }
    return e;
  }

  void load_x(const Number* x) { x_eval_ = Eigen::Map<const VecX>(x, n_x_); }

  // Energy and gradient of the strip at x (cached: Ipopt asks for f and grad f separately).
  bool update_strip(const Number* x) {
    if (cache_valid_ && std::equal(x, x + n_x_, x_cache_.data())) return cache_ok_;
    load_x(x);
    x_cache_ = x_eval_;
    cache_valid_ = true;
    try {
      energy_ = problem_.strip_energy(x_eval_, &gradient_, nullptr);
      cache_ok_ = std::isfinite(energy_) && gradient_.allFinite();
      if (!cache_ok_) evaluation_error_ = "the strip energy or its gradient is not finite";
    } catch (const NumericalError& error) {
      evaluation_error_ = error.what();
      cache_ok_ = false;
    }
    return cache_ok_;
  }

  IncrementProblem& problem_;
  const PassSetup& setup_;
  const StripPattern& pattern_;
  const PassStart& start_;
  IIndex n_x_, n_a_, n_f_, n_s_;
  std::vector<Block> blocks_;
  std::vector<int> friction_block_;  // per candidate: friction index or -1
  std::vector<int> active_row_;      // per candidate: gap row or -1

  VecX x_eval_;
  VecX x_cache_;
  bool cache_valid_ = false;
  bool cache_ok_ = false;
  Real energy_ = 0.0;
  VecX gradient_;
  SparseMatrix hessian_;
  std::string evaluation_error_;
  PassSolution solution_;
};

// Collects Ipopt's journal output (used by the derivative-checker hook).
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

// ---------------------------------------------------------------------------------------------
// The solve.

struct Hooks {
  bool derivative_test = false;
  Real derivative_perturbation = 1e-8;
  std::string* journal = nullptr;
};

BackendResult solve_increment(IncrementProblem& problem, const VecX& x0, const ContactOptions& options,
                              const Hooks& hooks) {
  const IpoptOptions& o = options.ipopt;
  const auto& cands = problem.candidates();
  const std::size_t n_c = cands.size();
  BackendResult result;
  result.x = x0;
  result.contact.assign(n_c, NodeContact{});

  // The strip at the start vector: force scale and the Hessian's fixed pattern.
  StripPattern pattern;
  Scales scales;
  try {
    VecX g;
    SparseMatrix h;
    problem.strip_energy(x0, &g, &h);
    pattern = make_pattern(h);
    scales = increment_scales(problem, x0);
  } catch (const NumericalError& error) {
    result.status = NewtonStatus::Failure;
    result.message = fmt::format("ipopt backend: the strip cannot be evaluated at the start vector ({}); "
                                 "use smaller steps", error.what());
    return result;
  }

  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = make_application(o, scales);
  if (hooks.derivative_test) {
    set(*app, "derivative_test", std::string("second-order"));
    set(*app, "derivative_test_print_all", std::string("no"));
    set(*app, "derivative_test_perturbation", hooks.derivative_perturbation);
    set(*app, "point_perturbation_radius", 0.0);  // check at x0 itself, not at a random point
    set(*app, "max_iter", 0);
  }
  if (app->Initialize("") != Ipopt::Solve_Succeeded) {  // "": never read ./ipopt.opt
    result.status = NewtonStatus::Failure;
    result.message = "ipopt backend: Ipopt failed to initialise";
    return result;
  }
  if (hooks.journal) {
    Ipopt::SmartPtr<Ipopt::Journal> j = new StringJournal(hooks.journal, Ipopt::J_WARNING);
    app->Jnlst()->AddJournal(j);
  }

  const Real mu = problem.roller().friction;
  NormalForceFixedPoint fixed_point(problem, o, scales.force);
  PassStart start;
  start.x = x0;
  start.normal = fixed_point.fbar();
  start.tangential.assign(n_c, 0.0);
  for (std::size_t i = 0; i < n_c; ++i) start.tangential[i] = cands[i].tangential_force;

  const int max_passes = (mu > 0.0 && o.fixed_point == "converge") ? o.fixed_point_max : 1;
  PassSolution last;
  PassSetup setup;
  double ipopt_time = 0.0;
  int passes = 0;
  bool fixed_point_converged = mu == 0.0 || o.fixed_point == "single";
  std::string evaluation_error;
  for (int pass = 1; pass <= max_passes; ++pass) {
    setup = make_setup(problem, options, fixed_point.fbar(), fixed_point.force_tol());
    // Pass 1 warm-starts only on request (its guesses may be poor); later passes always start
    // from the previous pass's primal-dual solution, which is close.
    set_warm_start(*app, pass > 1 || o.warm_start);
    Ipopt::SmartPtr<ContactNlp> nlp = new ContactNlp(problem, setup, pattern, start);
    const auto t0 = std::chrono::steady_clock::now();
    const Ipopt::ApplicationReturnStatus status = app->OptimizeTNLP(GetRawPtr(nlp));
    ipopt_time += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    passes = pass;
    int iterations = 0;
    if (IsValid(app->Statistics())) iterations = app->Statistics()->IterationCount();
    result.iterations += iterations;
    evaluation_error = nlp->evaluation_error();
    result.stats["nlp_variables"] = nlp->n_variables();
    result.stats["nlp_constraints"] = nlp->n_constraints();
    if (nlp->solution().finalized) {
      last = nlp->solution();
      result.x = last.z.head(problem.n_free());
    }
    if (status == Ipopt::Solved_To_Acceptable_Level) result.stats["acceptable_level"] = 1.0;
    if (hooks.derivative_test) {
      result.status = NewtonStatus::NotConverged;
      result.message = "derivative test only";
      return result;
    }
    const StatusText st = map_status(status, iterations, o, evaluation_error);
    if (st.status != NewtonStatus::Converged || !last.finalized) {
      result.status = st.status == NewtonStatus::Converged ? NewtonStatus::Failure : st.status;
      result.message = st.status == NewtonStatus::Converged ? "Ipopt returned no solution" : st.message;
      if (mu > 0.0) result.message += fmt::format(" (friction fixed-point pass {})", pass);
      result.stats["fixed_point_iterations"] = pass;
      result.stats["ipopt_time_s"] = ipopt_time;
      return result;
    }
    const bool done = fixed_point.update(last.normal);
    if (done || mu == 0.0 || o.fixed_point == "single") {
      fixed_point_converged = done;
      break;
    }
    start.x = result.x;
    start.normal = last.normal;
    start.tangential = last.tangential;
  }
  result.stats["fixed_point_iterations"] = passes;
  result.stats["ipopt_time_s"] = ipopt_time;
  result.factorizations = result.iterations;  // one KKT factorisation per interior-point iteration

  std::vector<bool> has_friction(n_c, false);
  for (const int i : setup.friction) has_friction[i] = true;
  if (!report_increment(problem, result.x, last.normal, last.tangential, setup.fbar, has_friction, scales, &result))
    return result;
  if (!fixed_point_converged) {
    result.status = NewtonStatus::NotConverged;
    result.message = fixed_point_message(passes, fixed_point, o);
    return result;
  }
  result.status = NewtonStatus::Converged;
  result.message = fmt::format("Ipopt converged in {} iterations ({} fixed-point pass{})", result.iterations,
                               passes, passes == 1 ? "" : "es");
  return result;
}

}  // namespace

IpoptBackend::IpoptBackend(ContactOptions options, LinearSolverOptions linear)
    : options_(std::move(options)), linear_(std::move(linear)) {
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
    r.status = NewtonStatus::Converged;
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
  if (options_.ipopt.formulation == "full") return solve_increment(problem, x0, options_, Hooks{});
  BackendResult condensed = solve_condensed(problem, x0, options_, linear_);
  if (!condensed.stats.count("condensed_failed")) return condensed;
  // The condensed formulation itself failed (singular interior tangent, no descent, the
  // linearisations ran out): the full formulation solves the increment from the same start.
  BackendResult full = solve_increment(problem, x0, options_, Hooks{});
  full.iterations += condensed.iterations;
  full.factorizations += condensed.factorizations;
  full.stats["condensed_fallback"] = 1.0;
  full.message += fmt::format(" [full formulation after the condensed one failed: {}]", condensed.message);
  return full;
}

// Testing hooks. They are not declared in a public header (ipopt_backend.hpp is fixed and keeps
// Ipopt out of the interface); tests/contact/test_ipopt_backend.cpp declares them itself.
namespace ipopt_testing {

// Runs Ipopt's derivative checker ("second-order") on the NLP of the first fixed-point pass at
// x0 (Fbar = the candidates' normal_force_guess) and returns its journal output.
std::string derivative_checker_output(IncrementProblem& problem, const VecX& x0, const ContactOptions& options,
                                      double perturbation) {
  std::string out;
  Hooks hooks;
  hooks.derivative_test = true;
  hooks.derivative_perturbation = perturbation;
  hooks.journal = &out;
  solve_increment(problem, x0, options, hooks);
  return out;
}

// Dense evaluation of the first pass's NLP at z (all NLP variables; z of size 0 only returns
// the sizes): objective f, its gradient, constraints, Jacobian, Hessian of the Lagrangian
// obj_factor * f + lambda . g (both triangles filled).
void evaluate_nlp(IncrementProblem& problem, const ContactOptions& options, const VecX& z, double obj_factor,
                  const VecX& lambda, long* n_variables, long* n_constraints, double* f, VecX* grad_f, VecX* g,
                  MatX* jacobian, MatX* hessian) {
  VecX x0 = VecX::Zero(problem.n_free());
  VecX grad0;
  SparseMatrix h0;
  problem.strip_energy(z.size() > 0 ? VecX(z.head(problem.n_free())) : x0, &grad0, &h0);
  const StripPattern pattern = make_pattern(h0);
  const Scales scales = increment_scales(problem, x0);
  std::vector<Real> fbar;
  Real fb = 0.0;
  for (const auto& c : problem.candidates()) {
    fbar.push_back(std::max(c.normal_force_guess, 0.0));
    fb = std::max(fb, fbar.back());
  }
  const PassSetup setup = make_setup(problem, options, fbar, 1e-6 * std::max(scales.force, fb));
  PassStart start;
  start.x = x0;
  start.normal = fbar;
  start.tangential.assign(fbar.size(), 0.0);
  ContactNlp nlp(problem, setup, pattern, start);
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
