#include "roller/material/j2_plasticity.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <string>

#include "roller/core/error.hpp"

namespace roller {
namespace {

// A trial stress counts as plastic only when it exceeds the yield stress by more than this
// relative margin, so that a zero increment from a state on the yield surface is elastic
// (decided by the data, not by round-off).
constexpr Real kYieldTolerance = 1e-12;
// continuum_tangent treats a stress as on the yield surface down to this relative margin
// below it: stresses returned to the surface sit there only up to round-off.
constexpr Real kOnSurfaceTolerance = 1e-8;

const Vec4 kIdentity = (Vec4() << 1.0, 1.0, 1.0, 0.0).finished();

Vec4 deviator(const Vec4& stress) {
  const Real mean = (stress(0) + stress(1) + stress(2)) / 3.0;
  return stress - mean * kIdentity;
}

// a:b of two symmetric tensors stored as [xx, yy, zz, xy]: the shear pair counts twice.
Real contract(const Vec4& a, const Vec4& b) { return a(0) * b(0) + a(1) * b(1) + a(2) * b(2) + 2.0 * a(3) * b(3); }

// The same tensor in the strain convention [xx, yy, zz, 2xy], so that a . b_strain = a:b.
Vec4 as_strain_vector(const Vec4& tensor) {
  Vec4 v = tensor;
  v(3) *= 2.0;
  return v;
}

// sigma_Y(eps_p) = sigma_y0 + H_iso eps_p + Q (1 - exp(-b eps_p)) and its slope H_iso + Q b exp(-b eps_p),
// from one expm1 (the consistency iteration evaluates both at every iterate); without a Voce term
// no call into libm.
struct YieldAt {
  Real stress;
  Real slope;
};
YieldAt yield_at(const MaterialParams& p, Real eq_plastic_strain) {
  YieldAt y{p.yield_stress + p.isotropic_modulus() * eq_plastic_strain, p.isotropic_modulus()};
  if (p.has_voce()) {
    const Real em1 = std::expm1(-p.voce_rate * eq_plastic_strain);  // exp(-b eps_p) - 1
    y.stress -= p.voce_saturation * em1;
    y.slope += p.voce_saturation * p.voce_rate * (1.0 + em1);
  }
  return y;
}
Real yield_stress_at(const MaterialParams& p, Real eq_plastic_strain) { return yield_at(p, eq_plastic_strain).stress; }
Real yield_slope_at(const MaterialParams& p, Real eq_plastic_strain) { return yield_at(p, eq_plastic_strain).slope; }

// int_{eps_p}^{eps_p + d} sigma_Y(a) da, exact (thesis (2.28); docs/model.md, J2 plasticity and
// work hardening); Voce's part as Q d + Q/b e^(-b eps_p) expm1(-b d).
Real plastic_work_increment(const MaterialParams& p, Real eq_plastic_strain, Real d) {
  Real w = p.yield_stress * d + p.isotropic_modulus() * (eq_plastic_strain * d + 0.5 * d * d);
  if (p.has_voce()) {
    w += p.voce_saturation *
         (d + std::exp(-p.voce_rate * eq_plastic_strain) * std::expm1(-p.voce_rate * d) / p.voce_rate);
  }
  return w;
}

// C^-1 in the [xx, yy, zz, xy] -> [xx, yy, zz, 2xy] convention (isotropic 3D compliance).
Mat4 compliance_matrix(const MaterialParams& p) {
  const Real e = p.youngs_modulus;
  const Real nu = p.poisson_ratio;
  Mat4 s = Mat4::Zero();
  s.topLeftCorner<3, 3>().setConstant(-nu / e);
  s.topLeftCorner<3, 3>().diagonal().setConstant(1.0 / e);
  s(3, 3) = 1.0 / p.shear_modulus();
  return s;
}

// psi_e(C^-1 new) - psi_e(C^-1 old) written as 1/2 (new - old) . C^-1 (new + old), which
// avoids cancelling two large stored energies when the increment is small.
Real elastic_energy_change(const MaterialParams& p, const Vec4& stress_old, const Vec4& stress_new) {
  return 0.5 * (stress_new - stress_old).dot(compliance_matrix(p) * (stress_new + stress_old));
}

void require_finite(const Vec4& strain_increment, const MaterialState& committed) {
  if (strain_increment.allFinite() && committed.stress.allFinite() && std::isfinite(committed.eq_plastic_strain)) {
    return;
  }
  std::ostringstream msg;
  msg << "update_material: non-finite input (strain increment [" << strain_increment.transpose()
      << "], committed stress [" << committed.stress.transpose() << "], eq_plastic_strain "
      << committed.eq_plastic_strain << "); the displacement iterate has diverged, cut the step";
  throw NumericalError(msg.str());
}

MaterialUpdate elastic_update(const MaterialParams& p, const Vec4& strain_increment, const MaterialState& committed) {
  MaterialUpdate u;
  u.tangent = elastic_matrix(p);
  u.stress = committed.stress + u.tangent * strain_increment;
  u.energy = committed.stress.dot(strain_increment) + 0.5 * strain_increment.dot(u.tangent * strain_increment);
  u.trial = committed;
  u.trial.stress = u.stress;
  u.trial.yield_stress = 0.0;
  return u;
}

// Algorithmic tangent of the radial return for linear isotropic hardening (Simo & Hughes,
// Computational Inelasticity, 1998, ch. 3):
//   C_alg = K 1(x)1 + 2G theta I_dev - 2G theta_bar n(x)n,
//   theta = 1 - 3G d/q_trial,  theta_bar = 1/(1 + H'/(3G)) - (1 - theta),
// n = s_trial/|s_trial|. As a [xx,yy,zz,2xy] -> [xx,yy,zz,xy] map, I_dev = diag(1,1,1,1/2)
// - 1/3 m m^T and n(x)n is n n^T of the stress-like n.
Mat4 consistent_tangent(const MaterialParams& p, const Vec4& unit_normal, Real theta, Real theta_bar) {
  const Real g = p.shear_modulus();
  Mat4 i_dev = Mat4::Zero();
  i_dev.diagonal() << 1.0, 1.0, 1.0, 0.5;
  i_dev -= kIdentity * kIdentity.transpose() / 3.0;
  return p.bulk_modulus() * kIdentity * kIdentity.transpose() + 2.0 * g * theta * i_dev -
         2.0 * g * theta_bar * unit_normal * unit_normal.transpose();
}

// The back-stress part of the consistency condition at a trial plastic multiplier d. Back-stress
// i ends at beta_i (alpha_i^n + sqrt(2/3) C_i d n) with beta_i = 1/(1 + gamma_i d) (backward
// Euler of Armstrong-Frederick), or at a fixed beta_i = 1/(1 + gamma_i d*) when the recovery is
// frozen at d* (docs/model.md, Hardening laws: the interior-point backend's scheme). The flow
// direction n is that of eta = s_trial - sum beta_i alpha_i^n.
// Per-back-stress arrays sized to the law's count, held inline up to kMaxBackStresses (no heap
// allocation in the update).
using BackStressArray = Eigen::Array<Real, Eigen::Dynamic, 1, 0, kMaxBackStresses, 1>;
using BackStressColumns = Eigen::Matrix<Real, 4, Eigen::Dynamic, 0, 4, kMaxBackStresses>;

struct BackStressTerms {  // every field set by evaluate_back_stress_terms
  Vec4 eta;               // s_trial - sum beta_i alpha_i^n
  Vec4 drift;             // d eta / d d = sum gamma_i beta_i^2 alpha_i^n (0 when frozen)
  Real modulus;           // sum C_i beta_i
  Real slope;             // d(d * sum C_i beta_i)/d d
  BackStressArray beta;   // beta_i
};

// A committed state's back-stresses with their laws, gathered once per update so that the
// consistency iteration works on arrays of the law's length.
struct BackStressSet {
  int n = 0;
  Real max_recovery = 0.0;   // max gamma_i (0 without back-stresses)
  BackStressArray modulus;   // C_i
  BackStressArray recovery;  // gamma_i
  BackStressColumns alpha;   // columns alpha_i^n
};

BackStressSet back_stress_set(const MaterialParams& p, const MaterialState& committed) {
  BackStressSet b;
  b.n = p.n_back_stresses();
  b.modulus.resize(b.n);
  b.recovery.resize(b.n);
  b.alpha.resize(4, b.n);
  for (int i = 0; i < b.n; ++i) {
    const BackStressLaw law = p.back_stress_law(i);
    b.modulus(i) = law.modulus;
    b.recovery(i) = law.recovery;
    b.alpha.col(i) = committed.back_stress[static_cast<std::size_t>(i)];
  }
  b.max_recovery = b.n > 0 ? b.recovery.maxCoeff() : 0.0;
  return b;
}

// Fills every field of `t` (no object per call: the consistency iteration evaluates this a few
// times per update, and zero-filling a fresh one cost as much as the arithmetic).
void evaluate_back_stress_terms(const BackStressSet& b, const Vec4& s_trial, Real d, std::optional<Real> frozen,
                                BackStressTerms& t) {
  t.eta = s_trial;
  t.drift.setZero();
  if (b.n == 0) {
    t.modulus = t.slope = 0.0;
    t.beta.resize(0);
    return;
  }
  const Real d_recovery = frozen.value_or(d);
  if (d_recovery == 0.0) {
    t.beta.setOnes(b.n);  // the elastic check's d = 0, without n divisions on its path
  } else {
    t.beta = 1.0 / (1.0 + b.recovery * d_recovery);
  }
  t.eta.noalias() -= b.alpha * t.beta.matrix();
  t.modulus = (b.modulus * t.beta).sum();
  if (frozen) {
    t.slope = t.modulus;
  } else {
    t.slope = (b.modulus * t.beta.square()).sum();
    t.drift.noalias() = b.alpha * (b.recovery * t.beta.square()).matrix();
  }
}

// The von Mises norm sqrt(3/2 x:x) of a deviator.
Real von_mises_of_deviator(const Vec4& s) { return std::sqrt(3.0) * std::sqrt(0.5 * contract(s, s)); }

// Consistency residual r(d) = q(eta) - (3G + sum C_i beta_i) d - sigma_Y(eps_p + d) and -dr/dd
// = 3G + slope + sigma_Y' - 3/2 eta:drift / q, held as q (-dr/dd) so that Newton's step r/(-dr/dd)
// costs one division (the iteration waits on each).
struct Consistency {
  Real residual;
  Real q;                                             // q(eta) > 0
  Real stiffness_q;                                   // q (-dr/dd)
  Real stiffness() const { return stiffness_q / q; }  // -dr/dd > 0
  Real newton_step() const { return residual * q / stiffness_q; }
};

// q = q(eta), which the caller has (the elastic check needs it first).
Consistency consistency(const MaterialParams& p, const BackStressTerms& t, Real q, Real eps_p, Real d) {
  const Real g = p.shear_modulus();
  const YieldAt y = yield_at(p, eps_p + d);
  return {q - (3.0 * g + t.modulus) * d - y.stress, q,
          q * (3.0 * g + t.slope + y.slope) - 1.5 * contract(t.eta, t.drift)};
}

// The last Newton step is taken without evaluating at its end once |r| <= 1e-8 sigma_Y and the
// step delta = r/D is below 1e-8/gamma_max: the terms then move to first order in delta, which
// leaves relative errors of order (gamma_i delta)^2 <= 1e-16 in the beta_i, and Newton's own remainder
// is of order r^2 (measured: r_next/sigma_Y ~ 0.05 (r/sigma_Y)^2), where one more evaluation would only
// confirm |r| <= 1e-14 sigma_Y. One evaluation of the consistency fewer an update (bench_return_mapping).
constexpr Real kLastNewtonStepResidual = 1e-8;
constexpr Real kLastNewtonStepRecovery = 1e-8;

// The plastic multiplier and the back-stress terms and consistency at it.
struct PlasticSolution {
  Real d = 0.0;
  BackStressTerms terms;
  Consistency consistency{0.0, 0.0, 0.0};
};

// The first iterate of the consistency iteration: the root of a model of r that keeps the
// recovery of every back-stress exact and expands q(eta) to first order in the beta_i about d = 0
// (eta = s_trial - sum beta_i alpha_i^n is linear in them); with 1 - beta_i = gamma_i beta_i d,
//   m(d) = q0 - 3G d - sum c_i beta_i d - sigma_Y(eps_p + d),
//   c_i = C_i - gamma_i k_i,  k_i = 3/2 eta_0:alpha_i^n / q0.
// m(0) = r(0) and m'(0) = r'(0); m leaves out what is second order in (1 - beta_i) alpha_i^n
// against eta, and costs no square root. Newton's method on m starts with r's linear step. On a
// Chaboche set with gamma_1 = 2000 at d = 5.5e-4 (bench_return_mapping) one step on m leaves r at
// 2.5e-4 sigma_Y, the linear step 0.04 (docs/model.md, Hardening laws).
Real first_multiplier_guess(const MaterialParams& p, const BackStressSet& b, const BackStressTerms& t0, Real q0,
                            const Consistency& c0, Real eps_p) {
  const Real linear = c0.newton_step();
  if (!(q0 > 0.0) || !(linear > 0.0)) return linear;
  const BackStressArray k = (1.5 / q0) * (b.alpha.transpose() * as_strain_vector(t0.eta)).array();
  const BackStressArray c = b.modulus - b.recovery * k;
  // sigma_Y taken linear from eps_p: Voce's curvature over d moves the root by far less than m's error.
  const Real g3h = 3.0 * p.shear_modulus() + yield_slope_at(p, eps_p);
  const Real r0 = c0.residual;  // q0 - sigma_Y(eps_p)
  Real d = linear;
  for (int iter = 0; iter < 20; ++iter) {
    const BackStressArray beta = 1.0 / (1.0 + b.recovery * d);
    const Real m = r0 - (g3h + (c * beta).sum()) * d;
    const Real descent = g3h + (c * beta.square()).sum();
    const Real step = m / descent;
    if (!(descent > 0.0) || !std::isfinite(step) || !(d + step > 0.0)) return linear;  // m not convex here
    d += step;
    // A step below a tenth of d leaves m's root to within about (step/d)^2 / 100 of d
    // (measured: m/sigma_Y at 7e-5 after a step of 0.07 d), near m's own error: Newton's method on r
    // takes it from there.
    if (std::abs(step) <= 0.1 * d) return d;
  }
  return linear;
}

// `at` moved from its d by delta to first order: beta_i' = -gamma_i beta_i^2, so eta' = drift,
// (sum C_i beta_i)' = -sum C_i gamma_i beta_i^2, slope' = -2 sum C_i gamma_i beta_i^3 and
// drift' = -2 sum gamma_i^2 beta_i^3 alpha_i (all 0 when frozen); r moves to 0 (the step is
// Newton's) and D is kept (it moves by a relative delta D'/D ~ 1e-9).
void advance_first_order(const BackStressSet& b, std::optional<Real> frozen, Real delta, PlasticSolution& at) {
  at.d += delta;
  at.consistency.residual = 0.0;
  if (frozen || b.n == 0) return;
  BackStressTerms& t = at.terms;
  const BackStressArray beta2 = t.beta.square();
  t.eta += delta * t.drift;
  t.modulus -= delta * (b.modulus * b.recovery * beta2).sum();
  t.slope -= 2.0 * delta * (b.modulus * b.recovery * beta2 * t.beta).sum();
  t.drift.noalias() -= 2.0 * delta * (b.alpha * (b.recovery.square() * beta2 * t.beta).matrix());
  t.beta -= delta * b.recovery * beta2;
}

// The plastic multiplier d > 0 of a trial state outside the surface. Linear hardening (every
// back-stress linear or frozen, no Voce term) has it in closed form; otherwise r(d) is strictly
// decreasing (|sqrt(3/2) n:drift| <= sum C_i beta_i^2 while each back-stress stays within its
// saturation sqrt(2/3) C_i/gamma_i) and Newton's method runs inside a bracket that bisection
// keeps.
PlasticSolution plastic_multiplier(const MaterialParams& p, const MaterialState& committed, const BackStressSet& b,
                                   const Vec4& s_trial, const BackStressTerms& t0, Real q0,
                                   std::optional<Real> frozen) {
  const Real eps_p = committed.eq_plastic_strain;
  const Consistency c0 = consistency(p, t0, q0, eps_p, 0.0);
  const bool linear = (frozen || p.has_potential()) && !p.has_voce();
  // Linear: the terms do not depend on d, and neither does the stiffness (no Voce term).
  if (linear) return {c0.newton_step(), t0, c0};
  Real lo = 0.0;
  Real hi = std::numeric_limits<Real>::infinity();
  Real d = first_multiplier_guess(p, b, t0, q0, c0, eps_p);
  const Real scale = yield_stress_at(p, eps_p);
  PlasticSolution at;
  for (int iter = 0; iter < 100; ++iter) {
    at.d = d;
    evaluate_back_stress_terms(b, s_trial, d, frozen, at.terms);
    at.consistency = consistency(p, at.terms, von_mises_of_deviator(at.terms.eta), eps_p, d);
    const Real r = at.consistency.residual;
    if (std::abs(r) <= 1e-14 * scale) return at;
    (r > 0.0 ? lo : hi) = d;
    Real next = d + at.consistency.newton_step();
    const bool newton_step = next > lo && next < hi;
    if (!newton_step) next = std::isfinite(hi) ? 0.5 * (lo + hi) : 2.0 * d;
    if (std::abs(next - d) <= 1e-15 * d) return at;
    if (newton_step && std::abs(r) <= kLastNewtonStepResidual * scale &&
        b.max_recovery * std::abs(next - d) <= kLastNewtonStepRecovery) {
      advance_first_order(b, frozen, next - d, at);
      return at;
    }
    d = next;
  }
  throw NumericalError(fmt::format(
      "update_material: the return mapping's plastic multiplier did not converge in 100 iterations (d = {:g}); "
      "check the hardening parameters (chaboche_C, chaboche_gamma, voce_Q, voce_b)",
      d));
}

// Backward-Euler return mapping of J2 plasticity with isotropic (linear and Voce) and kinematic
// (Prager, Armstrong-Frederick, Chaboche) hardening (Simo & Hughes, Computational Inelasticity,
// 1998, ch. 3; Chaboche 2008, Int. J. Plast. 24; docs/model.md, Hardening laws). The plastic flow
// is along n = eta/|eta|, and the consistency condition is one scalar equation in d; with
// isotropic hardening alone it is the radial return of Wilkins.
//
// Algorithmic tangent (docs/model.md derives it):
//   C_alg = K 1(x)1 + 2G theta I_dev - 2G theta_bar n(x)n - (1 - theta) sqrt(3/2) 2G/D (a - n (n:a))(x)n,
//   theta = 1 - 3G d/q(eta),  theta_bar = 3G/D - (1 - theta),  D = -dr/dd,  a = d eta/d d,
// symmetric unless a recovery term acts (a != 0).
MaterialUpdate return_mapping_update(const MaterialParams& p, const Vec4& strain_increment,
                                     const MaterialState& committed, std::optional<Real> frozen) {
  const Mat4 c = elastic_matrix(p);
  const Vec4 trial_stress = committed.stress + c * strain_increment;
  const Vec4 s_trial = deviator(trial_stress);
  const Real eps_p = committed.eq_plastic_strain;
  const Real sigma_pl = yield_stress_at(p, eps_p);
  const BackStressSet b = back_stress_set(p, committed);
  BackStressTerms t0;
  evaluate_back_stress_terms(b, s_trial, 0.0, frozen, t0);

  // Stress and tangent are set on both branches below: not zero-filled first.
  MaterialUpdate u{Vec4(), Mat4(), 0.0, committed, false};
  u.trial.yield_stress = sigma_pl;
  const Real q0 = von_mises_of_deviator(t0.eta);
  if (q0 <= sigma_pl * (1.0 + kYieldTolerance)) {
    u.stress = trial_stress;
    u.tangent = c;
    u.trial.stress = u.stress;
    u.energy = elastic_energy_change(p, committed.stress, u.stress);
    return u;
  }
  const Real g = p.shear_modulus();
  const PlasticSolution solution = plastic_multiplier(p, committed, b, s_trial, t0, q0, frozen);
  const Real d = solution.d;
  const BackStressTerms& t = solution.terms;
  const Real eta_norm = std::sqrt(contract(t.eta, t.eta));
  const Real q_eta = std::sqrt(1.5) * eta_norm;  // von_mises_of_deviator(t.eta)
  const Vec4 n = t.eta / eta_norm;
  const Real theta = 1.0 - 3.0 * g * d / q_eta;
  const Real stiffness = solution.consistency.stiffness();
  const Real theta_bar = 3.0 * g / stiffness - (1.0 - theta);
  u.stress = trial_stress - (1.0 - theta) * t.eta;
  u.tangent = consistent_tangent(p, n, theta, theta_bar);
  if (!frozen && !p.has_potential()) {
    const Vec4 a_perp = t.drift - contract(n, t.drift) * n;
    u.tangent -= (1.0 - theta) * std::sqrt(1.5) * 2.0 * g / stiffness * a_perp * n.transpose();
  }
  u.yielded = true;
  u.trial.eq_plastic_strain = eps_p + d;
  u.trial.yield_stress = yield_stress_at(p, eps_p + d);

  // Plastic strain increment sqrt(3/2) d n; back-stress i ends at beta_i (alpha_i^n + 2/3 C_i deps_p).
  // The stored energy of a linear back-stress, 3/(4 C) alpha:alpha, changes by
  // 1/2 deps_p:(alpha_new + alpha_start): with the recovery frozen, alpha_start = beta alpha^n. Summed
  // over the back-stresses, sum alpha_i^n = s_trial - eta_0 and sum beta_i alpha_i^n = s_trial - eta.
  const Vec4 d_eps_p = std::sqrt(1.5) * d * n;
  Vec4 centre = Vec4::Zero();  // sum of the new back-stresses
  for (int i = 0; i < b.n; ++i) {
    const std::size_t k = static_cast<std::size_t>(i);
    const Vec4 alpha = t.beta(i) * (committed.back_stress[k] + 2.0 / 3.0 * b.modulus(i) * d_eps_p);
    centre += alpha;
    u.trial.back_stress[k] = alpha;
  }
  const Real stored = 0.5 * contract(d_eps_p, centre + s_trial - t.eta);
  const Real kinematic_work = 0.5 * contract(d_eps_p, centre + s_trial - t0.eta);
  const Real isotropic_work = plastic_work_increment(p, eps_p, d);
  u.trial.plastic_work += isotropic_work + kinematic_work;
  u.trial.stress = u.stress;
  if (frozen || p.has_potential()) {
    u.energy = isotropic_work + stored + elastic_energy_change(p, committed.stress, u.stress);
  } else {
    // Armstrong-Frederick's recovery has no potential: the trapezoidal work 1/2 (S_n + S):dE
    // stands in for the energy (a number to report, not an objective).
    u.energy = 0.5 * (committed.stress + u.stress).dot(strain_increment);
  }
  return u;
}

// ---- Substep (the thesis's "variable stiffness"; docs/model.md, Sub-stepping) ----------------

struct PointState {
  Vec4 stress;
  Real eq_plastic_strain;
  Real plastic_work;
};

void add_plastic_strain(const MaterialParams& p, Real d, PointState& state) {
  state.plastic_work += plastic_work_increment(p, state.eq_plastic_strain, d);
  state.eq_plastic_strain += d;
}

// Fraction alpha in [0, 1] of the elastic stress increment ds after which the path
// stress + alpha ds leaves the yield surface for good: the largest root of
//   |s + alpha ds_dev|^2 = 2/3 sigma_pl^2   (a alpha^2 + 2 b alpha + c = 0),
// 1 when the end point is inside or the deviator does not change (a state left outside by
// round-off must not flow under a volumetric strain). From a point on the surface this is 0
// for loading (b > 0) and the re-crossing point for unloading then reloading (b < 0).
Real elastic_fraction(const Vec4& stress, const Vec4& d_stress, Real sigma_pl) {
  if (von_mises(stress + d_stress) <= sigma_pl) return 1.0;
  const Vec4 s = deviator(stress);
  const Vec4 ds = deviator(d_stress);
  const Real a = contract(ds, ds);
  if (!(a > 0.0)) return 1.0;  // a purely volumetric step cannot move the state across J2
  const Real b = contract(s, ds);
  const Real c = contract(s, s) - 2.0 / 3.0 * sigma_pl * sigma_pl;
  const Real disc = std::max(b * b - a * c, 0.0);
  // Rationalised root for b > 0 avoids cancellation when c ~ 0.
  const Real alpha = b > 0.0 ? -c / (b + std::sqrt(disc)) : (-b + std::sqrt(disc)) / a;
  return std::clamp(alpha, 0.0, 1.0);
}

// Drift correction: a closed-form backward-Euler return from the drifted stress at zero strain
// increment (the "consistent correction" of Potts & Gens 1985, exact for J2 with linear
// hardening). It rescales the deviator and moves eps_p together with the stress, so the
// state ends on the yield surface and keeps the hardening law; the correction can be of
// either sign because the forward-Euler drift can be.
void return_to_yield_surface(const MaterialParams& p, PointState& state) {
  const Real q = von_mises(state.stress);
  const Real g = p.shear_modulus();
  const Real d = (q - yield_stress_at(p, state.eq_plastic_strain)) / (3.0 * g + p.plastic_modulus());
  state.stress -= 3.0 * g * d / q * deviator(state.stress);
  add_plastic_strain(p, d, state);
}

// One forward-Euler sub-step: elastic up to the surface, then dS = C^EP dE (thesis (2.29))
// at the stress where plastic flow starts, then the drift correction whenever plastic flow
// occurred or the step left the surface (neutral loading, s:dE = 0, moves tangentially and
// leaves it at second order). Returns true when plastic flow occurred.
bool advance_substep(const MaterialParams& p, const Mat4& c, const Vec4& d_strain, PointState& state) {
  const Vec4 d_stress_elastic = c * d_strain;
  const Real alpha = elastic_fraction(state.stress, d_stress_elastic, yield_stress_at(p, state.eq_plastic_strain));
  state.stress += alpha * d_stress_elastic;
  if (alpha >= 1.0) return false;

  // Plastic multiplier of the flow rule dE^p = d_lambda n, n = df/dS = s (thesis (2.30)).
  const Vec4 rest = (1.0 - alpha) * d_strain;
  const Vec4 s = deviator(state.stress);
  const Real ss = contract(s, s);
  const Vec4 n = as_strain_vector(s);
  const Vec4 c_n = c * n;
  const Real d_lambda = std::max(c_n.dot(rest) / (n.dot(c_n) + 2.0 / 3.0 * p.plastic_modulus() * ss), 0.0);
  state.stress += c * rest - d_lambda * c_n;
  add_plastic_strain(p, d_lambda * std::sqrt(2.0 / 3.0 * ss), state);
  const bool outside = von_mises(state.stress) > yield_stress_at(p, state.eq_plastic_strain);
  if (d_lambda > 0.0 || outside) return_to_yield_surface(p, state);
  return d_lambda > 0.0 || outside;
}

MaterialUpdate substep_update(const MaterialParams& p, const Vec4& strain_increment, const MaterialState& committed) {
  ROLLER_ASSERT(p.n_substeps >= 1, "sub-stepping takes at least one sub-step");
  const int n = std::max(p.n_substeps, 1);
  const Mat4 c = elastic_matrix(p);
  const Vec4 d_strain = strain_increment / static_cast<Real>(n);
  PointState state{committed.stress, committed.eq_plastic_strain, committed.plastic_work};

  MaterialUpdate u;
  for (int k = 0; k < n; ++k) {
    const Vec4 stress_before = state.stress;
    u.yielded = advance_substep(p, c, d_strain, state) || u.yielded;
    u.energy += 0.5 * (stress_before + state.stress).dot(d_strain);
  }
  u.stress = state.stress;
  u.trial = committed;
  u.trial.stress = state.stress;
  u.trial.eq_plastic_strain = state.eq_plastic_strain;
  u.trial.plastic_work = state.plastic_work;
  u.trial.yield_stress = yield_stress_at(p, state.eq_plastic_strain);
  u.tangent = continuum_tangent(p, state.stress, u.trial.yield_stress);
  return u;
}

MaterialUpdate integrate(const MaterialParams& p, const Vec4& strain_increment, const MaterialState& committed,
                         std::optional<Real> frozen) {
  if (!p.plastic) return elastic_update(p, strain_increment, committed);
  if (p.integration == StressIntegration::Substep) {
    return substep_update(p, strain_increment, committed);
  }
  return return_mapping_update(p, strain_increment, committed, frozen);
}

// The plastic branch of C^EP at a relative stress xi on a surface of size sigma_Y with hardening
// modulus h (docs/model.md, Sub-stepping and Hardening laws):
//   C^EP = C - 2G beta xi xi^T,  beta = 3 / (2 sigma_Y^2 (1 + h/(3G))).
Mat4 plastic_branch(const MaterialParams& p, const Vec4& xi, Real yield_stress, Real h) {
  require(yield_stress > 0.0, "plastic_tangent: yield_stress must be > 0 (it divides C^EP)");
  const Real g = p.shear_modulus();
  const Real beta = 1.5 / (yield_stress * yield_stress) / (1.0 + h / (3.0 * g));
  return elastic_matrix(p) - 2.0 * g * beta * xi * xi.transpose();
}

// Relative stress xi = s - sum alpha_i and the hardening modulus of a state,
// h = sigma_Y' + sum (C_i - gamma_i sqrt(3/2) n:alpha_i), n = xi/|xi|: dq(xi) = sigma_Y' dp under flow.
std::pair<Vec4, Real> relative_stress_and_modulus(const MaterialParams& p, const MaterialState& state) {
  Vec4 xi = deviator(state.stress);
  for (int i = 0; i < p.n_back_stresses(); ++i) xi -= state.back_stress[static_cast<std::size_t>(i)];
  const Real q = von_mises_of_deviator(xi);
  Real h = yield_slope_at(p, state.eq_plastic_strain);
  for (int i = 0; i < p.n_back_stresses(); ++i) {
    const BackStressLaw law = p.back_stress_law(i);
    const Vec4& alpha = state.back_stress[static_cast<std::size_t>(i)];
    h += law.modulus - (q > 0.0 ? law.recovery * 1.5 * contract(xi, alpha) / q : 0.0);
  }
  return {xi, h};
}

}  // namespace

Mat4 elastic_matrix(const MaterialParams& p) {
  const Real lambda = p.lame_lambda();
  const Real g = p.shear_modulus();
  Mat4 c = Mat4::Zero();
  c.topLeftCorner<3, 3>().setConstant(lambda);
  c.topLeftCorner<3, 3>().diagonal().setConstant(lambda + 2.0 * g);
  c(3, 3) = g;
  return c;
}

// Thesis (2.29)-(2.30) (docs/model.md, Sub-stepping): C^EP = C - (C n)(C n)^T / (n.C.n + n_p.n)
// with n = s (as a strain-like vector, C n = 2G s) and n_p = 2/3 sigma_pl dsigma_pl/dW_pl s
// = 2/3 H' s, so the denominator is (2G + 2/3 H') s:s. The thesis's explicit forms (2.29
// expanded, (3.4)) put s:s = 2/3 sigma_pl^2 (true on the surface), giving C - 2G beta s s^T with
// beta = 3/(2 sigma_pl^2) / (1 + H'/(3G)); that form is used so that the matrix depends on the
// deviator and sigma_pl separately, as the monotonicity study needs (docs/model.md, Pointwise
// operator A).
Mat4 plastic_tangent(const MaterialParams& p, const Vec4& stress, Real yield_stress) {
  return plastic_branch(p, deviator(stress), yield_stress, p.plastic_modulus());
}

Mat4 continuum_tangent(const MaterialParams& p, const MaterialState& state) {
  if (!p.plastic) return elastic_matrix(p);
  const auto [xi, h] = relative_stress_and_modulus(p, state);
  if (von_mises_of_deviator(xi) < state.yield_stress * (1.0 - kOnSurfaceTolerance) || !(state.yield_stress > 0.0)) {
    return elastic_matrix(p);
  }
  return plastic_branch(p, xi, state.yield_stress, h);
}

Mat4 continuum_tangent(const MaterialParams& p, const Vec4& stress, Real yield_stress) {
  if (!p.plastic || von_mises(stress) < yield_stress * (1.0 - kOnSurfaceTolerance) || !(yield_stress > 0.0)) {
    return elastic_matrix(p);
  }
  return plastic_tangent(p, stress, yield_stress);
}

MaterialState initial_state(const MaterialParams& p) {
  MaterialState state;
  state.yield_stress = p.plastic ? p.yield_stress : 0.0;
  return state;
}

namespace {

MaterialUpdate checked_update(const MaterialParams& p, const Vec4& strain_increment, const MaterialState& committed,
                              std::optional<Real> frozen) {
  require_finite(strain_increment, committed);
  MaterialUpdate u = integrate(p, strain_increment, committed, frozen);
  // Finite input with non-finite output means inadmissible parameters (e.g. E_T = E).
  if (!u.stress.allFinite() || !u.tangent.allFinite() || !std::isfinite(u.energy)) {
    throw NumericalError(
        "update_material: non-finite stress, tangent or energy from a finite strain increment; "
        "check the material with MaterialParams::is_valid (E_T < E, yield_stress > 0)");
  }
  // The return mapping's plastic multiplier is >= 0: plastic strain only accumulates, and the yield
  // stress only grows unless a Voce term softens (the sub-steps' drift correction may take back a little).
  ROLLER_ASSERT(p.integration == StressIntegration::Substep ||
                    (u.trial.eq_plastic_strain >= committed.eq_plastic_strain &&
                     (p.voce_saturation < 0.0 || u.trial.yield_stress >= committed.yield_stress)),
                "the return mapping never lowers the plastic strain, nor the yield stress of a hardening law");
  return u;
}

}  // namespace

MaterialUpdate update_material(const MaterialParams& p, const Vec4& strain_increment, const MaterialState& committed) {
  return checked_update(p, strain_increment, committed, std::nullopt);
}

MaterialUpdate update_material(const MaterialParams& p, const Vec4& strain_increment, const MaterialState& committed,
                               FrozenRecovery frozen) {
  ROLLER_ASSERT(frozen.multiplier >= 0.0, "a frozen plastic multiplier is >= 0");
  return checked_update(p, strain_increment, committed, frozen.multiplier);
}

Real sqrt_j2(const Vec4& stress) {
  const Vec4 s = deviator(stress);
  return std::sqrt(0.5 * contract(s, s));
}

Real von_mises(const Vec4& stress) { return std::sqrt(3.0) * sqrt_j2(stress); }

}  // namespace roller
