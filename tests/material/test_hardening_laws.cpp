// Kinematic, mixed, Armstrong-Frederick, Chaboche and Voce hardening at a material point in
// uniaxial stress against their closed forms (docs/validation.md, Hardening laws), the
// consistent tangent and the incremental energy against finite differences, and the frozen
// recovery's fixed point.
//
// Backward Euler is first-order accurate in the plastic increment for Armstrong-Frederick, so a
// run with N steps differs from the closed form by c1/N + c2/N^2: the checks extrapolate runs
// with N, 2N and 4N steps (Richardson) and also check that the error halves.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "roller/material/j2_plasticity.hpp"
#include "roller/material/uniaxial_point.hpp"

using namespace roller;

namespace {

MaterialParams base_steel() {
  MaterialParams p;
  p.youngs_modulus = 2.0e5;
  p.poisson_ratio = 0.3;
  p.plastic = true;
  p.yield_stress = 250.0;
  return p;
}

// base_steel with Chaboche's law and these back-stresses (C_i, gamma_i).
MaterialParams chaboche(std::initializer_list<BackStressLaw> laws) {
  MaterialParams p = base_steel();
  p.hardening = Hardening::Chaboche;
  p.n_chaboche = static_cast<int>(laws.size());
  std::copy(laws.begin(), laws.end(), p.chaboche.begin());
  return p;
}

// Armstrong-Frederick: one back-stress saturating at C/gamma = 200 MPa.
MaterialParams armstrong_frederick() { return chaboche({{5.0e4, 250.0}}); }

// Chaboche with three back-stresses, the last one linear (gamma = 0).
MaterialParams chaboche3() { return chaboche({{1.2e5, 1200.0}, {2.0e4, 150.0}, {2.0e3, 0.0}}); }

// Ten back-stresses, the most the law takes: R260's six (problems/ratchet_rail.toml), four more with
// a linear one last, and a softening Voce term fast enough to show within the tests' strains.
MaterialParams chaboche10_softening() {
  MaterialParams p = chaboche({{3.5e5, 5000.0},
                               {8.0e4, 1000.0},
                               {1.5e4, 150.0},
                               {1.0e4, 20.0},
                               {8.0e3, 20.0},
                               {190.0, 0.01},
                               {5.0e3, 400.0},
                               {3.0e3, 60.0},
                               {1.0e3, 5.0},
                               {500.0, 0.0}});
  p.voce_saturation = -60.0;
  p.voce_rate = 30.0;
  return p;
}

MaterialParams prager() {
  MaterialParams p = base_steel();
  p.hardening = Hardening::Kinematic;
  p.tangent_modulus = 0.05 * p.youngs_modulus;
  return p;
}

// sigma_Y(eps_p) (Voce's term of either sign) + sum of the back-stresses' monotonic closed forms
// at plastic strain eps_p.
Real monotonic_stress(const MaterialParams& p, Real eps_p) {
  Real s = p.yield_stress - p.voce_saturation * std::expm1(-p.voce_rate * eps_p);
  for (int i = 0; i < p.n_chaboche; ++i) {
    const BackStressLaw b = p.chaboche[static_cast<std::size_t>(i)];
    s += b.recovery > 0.0 ? b.modulus / b.recovery * -std::expm1(-b.recovery * eps_p) : b.modulus * eps_p;
  }
  return s;
}

// The stabilised loop's peak under symmetric cycling with plastic strain range d_eps_p.
Real loop_peak_stress(const MaterialParams& p, Real d_eps_p) {
  Real s = p.yield_stress;
  for (int i = 0; i < p.n_chaboche; ++i) {
    const BackStressLaw b = p.chaboche[static_cast<std::size_t>(i)];
    s += b.recovery > 0.0 ? b.modulus / b.recovery * std::tanh(0.5 * b.recovery * d_eps_p) : 0.5 * b.modulus * d_eps_p;
  }
  return s;
}

// Uniaxial monotonic tension: exactly to the yield strain, then n steps to eps_end. Returns the
// error of the end stress against the closed form at the run's own plastic strain.
Real monotonic_error(const MaterialParams& p, Real eps_end, int n) {
  MaterialState state = initial_state(p);
  const Real eps_y = p.yield_stress / p.youngs_modulus;
  state = uniaxial_strain_step(p, eps_y, state).update.trial;
  for (int k = 0; k < n; ++k) state = uniaxial_strain_step(p, (eps_end - eps_y) / n, state).update.trial;
  return state.stress(0) - monotonic_stress(p, state.eq_plastic_strain);
}

// Strain cycling between -eps_a and eps_a, n steps per half cycle: the stabilised peak stress
// minus the closed form at the measured plastic strain range.
Real loop_error(const MaterialParams& p, Real eps_a, int n, int cycles) {
  MaterialState state = initial_state(p);
  Real eps = 0.0;
  auto strain_to = [&](Real target, int steps) {
    const Real d = (target - eps) / steps;
    for (int k = 0; k < steps; ++k) {
      state = uniaxial_strain_step(p, d, state).update.trial;
      eps += d;
    }
  };
  strain_to(eps_a, n / 2);
  Real peak = 0.0, eps_p_top = 0.0, eps_p_bottom = 0.0;
  for (int c = 0; c < cycles; ++c) {
    strain_to(-eps_a, n);
    eps_p_bottom = eps - state.stress(0) / p.youngs_modulus;
    strain_to(eps_a, n);
    eps_p_top = eps - state.stress(0) / p.youngs_modulus;
    peak = state.stress(0);
  }
  return peak - loop_peak_stress(p, eps_p_top - eps_p_bottom);
}

// Stress cycling between s_min and s_max, n steps per branch: the axial plastic strain at each
// s_max peak.
std::vector<Real> ratchet_peaks(const MaterialParams& p, Real s_min, Real s_max, int n, int cycles) {
  MaterialState state = initial_state(p);
  Real eps = 0.0;
  std::vector<Real> peaks;
  auto stress_to = [&](Real target) {
    const Real s0 = state.stress(0);
    for (int k = 1; k <= n; ++k) {
      const auto step = uniaxial_stress_step(p, s0 + (target - s0) * k / n, state);
      state = step.update.trial;
      eps += step.strain_increment(0);
    }
  };
  for (int c = 0; c < cycles; ++c) {
    stress_to(s_max);
    peaks.push_back(eps - state.stress(0) / p.youngs_modulus);
    stress_to(s_min);
  }
  return peaks;
}

// Richardson's extrapolation of an error c1/n + c2/n^2 from runs with n, 2n and 4n steps, after
// checking that it is first order (it halves).
template <class Run>
Real extrapolated_error(Run run, int n) {
  const Real e1 = run(n), e2 = run(2 * n), e4 = run(4 * n);
  INFO("error with " << n << ", " << 2 * n << ", " << 4 * n << " steps: " << e1 << ", " << e2 << ", " << e4);
  CHECK(e1 / e2 == Approx(2.0).epsilon(0.05));
  CHECK(e2 / e4 == Approx(2.0).epsilon(0.05));
  return (8.0 * e4 - 6.0 * e2 + e1) / 3.0;
}

}  // namespace

TEST_CASE("Armstrong-Frederick and Chaboche follow their monotonic closed forms in uniaxial tension",
          "[material][hardening]") {
  SECTION("Armstrong-Frederick: sigma = sigma_y + C/gamma (1 - exp(-gamma eps_p))") {
    const MaterialParams p = armstrong_frederick();
    const Real error = extrapolated_error([&](int n) { return monotonic_error(p, 0.012, n); }, 400);
    CHECK(std::abs(error) / monotonic_stress(p, 0.012) < 1e-6);
  }
  SECTION("Chaboche: the sum of the back-stresses' closed forms") {
    const MaterialParams p = chaboche3();
    const Real error = extrapolated_error([&](int n) { return monotonic_error(p, 0.012, n); }, 800);
    CHECK(std::abs(error) / monotonic_stress(p, 0.012) < 1e-6);
  }
  SECTION("Chaboche with ten back-stresses and a softening Voce term") {
    const MaterialParams p = chaboche10_softening();
    // The Voce term has softened the yield stress by more than half its Q at the end.
    REQUIRE(-std::expm1(-p.voce_rate * 0.03) > 0.5);
    const Real error = extrapolated_error([&](int n) { return monotonic_error(p, 0.03, n); }, 1600);
    CHECK(std::abs(error) / monotonic_stress(p, 0.03) < 1e-6);
  }
}

TEST_CASE("Armstrong-Frederick and Chaboche stabilise on the closed-form loop under symmetric strain cycling",
          "[material][hardening]") {
  SECTION("Armstrong-Frederick: sigma_max = sigma_y + C/gamma tanh(gamma d_eps_p / 2)") {
    const MaterialParams p = armstrong_frederick();
    const Real error = extrapolated_error([&](int n) { return loop_error(p, 0.006, n, 6); }, 400);
    CHECK(std::abs(error) / p.yield_stress < 1e-6);
  }
  SECTION("Chaboche: the sum of the back-stresses' loops") {
    const MaterialParams p = chaboche3();
    // The linear back-stress drifts nothing under symmetric cycling once the others have settled.
    const Real error = extrapolated_error([&](int n) { return loop_error(p, 0.006, n, 8); }, 800);
    CHECK(std::abs(error) / p.yield_stress < 1e-6);
  }
  SECTION("Chaboche with ten back-stresses: the sum of their loops") {
    // Every recovery fast enough (gamma >= 150) to forget the first quarter cycle within eight, and
    // no Voce term (the loop of a softening surface keeps shrinking).
    const MaterialParams p = chaboche({{3.5e5, 5000.0},
                                       {8.0e4, 1000.0},
                                       {1.5e4, 150.0},
                                       {1.0e4, 400.0},
                                       {8.0e3, 250.0},
                                       {5.0e3, 600.0},
                                       {3.0e3, 300.0},
                                       {1.0e3, 200.0},
                                       {2.0e3, 1500.0},
                                       {500.0, 0.0}});
    const Real error = extrapolated_error([&](int n) { return loop_error(p, 0.006, n, 8); }, 1600);
    CHECK(std::abs(error) / p.yield_stress < 1e-6);
  }
}

TEST_CASE("Armstrong-Frederick ratchets by the closed-form strain per cycle, Prager closes its loop",
          "[material][hardening]") {
  const Real s_max = 400.0, s_min = -300.0;
  SECTION("Armstrong-Frederick: d_eps_p = 1/gamma ln[((C/gamma)^2 - X_min^2) / ((C/gamma)^2 - X_max^2)]") {
    const MaterialParams p = armstrong_frederick();
    const Real c = p.chaboche[0].modulus, gamma = p.chaboche[0].recovery;
    const Real x_max = s_max - p.yield_stress, x_min = s_min + p.yield_stress;
    const Real sat = c / gamma;
    const Real expected = std::log((sat * sat - x_min * x_min) / (sat * sat - x_max * x_max)) / gamma;
    auto ratchet_error = [&](int n) {
      const std::vector<Real> peaks = ratchet_peaks(p, s_min, s_max, n, 4);
      // Every cycle after the first ratchets by the same amount.
      CHECK(peaks[3] - peaks[2] == Approx(peaks[2] - peaks[1]).epsilon(1e-9));
      return peaks[3] - peaks[2] - expected;
    };
    // n a multiple of 56: yield starts on a step boundary on every branch (at 5/8 of the first,
    // 5/7 of the others), so the error is c/n with no jitter of the onset.
    const Real error = extrapolated_error(ratchet_error, 448);
    INFO("expected ratchet strain per cycle " << expected);
    CHECK(std::abs(error) / expected < 1e-6);
  }
  SECTION("Prager: no ratchet after the first cycle, plastic strain range (X_max - X_min)/C") {
    const MaterialParams p = prager();
    const std::vector<Real> peaks = ratchet_peaks(p, s_min, s_max, 50, 4);
    const Real range = ((s_max - p.yield_stress) - (s_min + p.yield_stress)) / p.plastic_modulus();
    CHECK(std::abs(peaks[3] - peaks[1]) < 1e-12 * range);
    CHECK(std::abs(peaks[2] - peaks[1]) < 1e-12 * range);
    // The first peak sits at X_max / C on the virgin curve.
    CHECK(peaks[0] == Approx((s_max - p.yield_stress) / p.plastic_modulus()).epsilon(1e-10));
  }
}

TEST_CASE("Voce isotropic hardening is exact under monotonic tension", "[material][hardening]") {
  MaterialParams p = base_steel();
  p.voce_saturation = 150.0;
  p.voce_rate = 40.0;
  p.tangent_modulus = 0.01 * p.youngs_modulus;
  MaterialState state = initial_state(p);
  for (int k = 0; k < 50; ++k) state = uniaxial_strain_step(p, 4e-4, state).update.trial;
  const Real eps_p = state.eq_plastic_strain;
  REQUIRE(eps_p > 0.01);
  const Real expected = p.yield_stress + p.plastic_modulus() * eps_p + 150.0 * -std::expm1(-40.0 * eps_p);
  CHECK(state.stress(0) == Approx(expected).epsilon(1e-12));
  CHECK(state.yield_stress == Approx(expected).epsilon(1e-12));
}

TEST_CASE("Kinematic and mixed laws reduce to the isotropic law where they must", "[material][hardening]") {
  MaterialParams iso = base_steel();
  iso.tangent_modulus = 0.02 * iso.youngs_modulus;
  MaterialParams mixed0 = iso;
  mixed0.hardening = Hardening::Mixed;
  mixed0.kinematic_fraction = 0.0;
  MaterialParams kin = iso;
  kin.hardening = Hardening::Kinematic;
  MaterialState s_iso = initial_state(iso), s_mixed = initial_state(mixed0), s_kin = initial_state(kin);
  const Vec4 de(1.2e-3, -0.4e-3, 0.0, 0.9e-3);
  for (int k = 0; k < 5; ++k) {
    const MaterialUpdate a = update_material(iso, de, s_iso);
    const MaterialUpdate b = update_material(mixed0, de, s_mixed);
    const MaterialUpdate c = update_material(kin, de, s_kin);
    // Mixed with no kinematic share is the isotropic law, bit for bit.
    CHECK(b.stress == a.stress);
    CHECK(b.tangent == a.tangent);
    CHECK(b.energy == a.energy);
    // Under a proportional, monotonic path the moving and the growing surface agree.
    CHECK((c.stress - a.stress).norm() < 1e-10 * a.stress.norm());
    CHECK(c.energy == Approx(a.energy).epsilon(1e-10));
    s_iso = a.trial;
    s_mixed = b.trial;
    s_kin = c.trial;
  }
  CHECK(s_kin.back_stress[0].norm() > 0.0);
  // After a reversal they part: the kinematic surface yields again sooner (Bauschinger).
  const MaterialUpdate back_iso = update_material(iso, -2.0 * de, s_iso);
  const MaterialUpdate back_kin = update_material(kin, -2.0 * de, s_kin);
  CHECK(back_kin.yielded);
  CHECK_FALSE(back_iso.yielded);
}

namespace {

// A state reached by a non-proportional plastic path, so that stress, back-stresses and the next
// increment are not aligned.
MaterialState prestate(const MaterialParams& p) {
  const Real ey = p.yield_stress / p.youngs_modulus;
  MaterialState s = initial_state(p);
  s = update_material(p, ey * Vec4(2.0, -0.5, 0.0, 0.0), s).trial;
  s = update_material(p, ey * Vec4(0.3, 0.2, 0.0, 2.5), s).trial;
  s = update_material(p, ey * Vec4(-0.4, 0.9, 0.1, -0.6), s).trial;
  REQUIRE(s.eq_plastic_strain > 0.0);
  return s;
}

// Central differences of the stress (a 4x4 tangent) and of the energy (its 1x4 gradient) of an
// update with respect to the strain increment.
template <class Update>
std::pair<Mat4, Eigen::Matrix<Real, 1, 4>> central_differences(Update update, const Vec4& de, Real h) {
  Mat4 tangent;
  Eigen::Matrix<Real, 1, 4> gradient;
  for (int j = 0; j < 4; ++j) {
    Vec4 plus = de, minus = de;
    plus(j) += h;
    minus(j) -= h;
    const MaterialUpdate up = update(plus), down = update(minus);
    tangent.col(j) = (up.stress - down.stress) / (2.0 * h);
    gradient(j) = (up.energy - down.energy) / (2.0 * h);
  }
  return {tangent, gradient};
}
Mat4 fd_tangent(const std::function<MaterialUpdate(const Vec4&)>& update, const Vec4& de, Real h) {
  return central_differences(update, de, h).first;
}
Vec4 fd_energy(const std::function<MaterialUpdate(const Vec4&)>& update, const Vec4& de, Real h) {
  return central_differences(update, de, h).second.transpose();
}

std::vector<std::pair<std::string, MaterialParams>> laws() {
  MaterialParams kin = prager();
  MaterialParams mixed = prager();
  mixed.hardening = Hardening::Mixed;
  mixed.kinematic_fraction = 0.3;
  mixed.voce_saturation = 80.0;
  mixed.voce_rate = 30.0;
  return {{"kinematic", kin},
          {"mixed with Voce", mixed},
          {"Armstrong-Frederick", armstrong_frederick()},
          {"Chaboche", chaboche3()},
          {"Chaboche, ten with Voce softening", chaboche10_softening()}};
}

}  // namespace

TEST_CASE("The consistent tangent of every hardening law matches finite differences", "[material][hardening]") {
  for (const auto& [name, p] : laws()) {
    INFO(name);
    const MaterialState s = prestate(p);
    const Real ey = p.yield_stress / p.youngs_modulus;
    const Vec4 de = ey * Vec4(0.7, -0.2, 0.05, 0.8);
    const MaterialUpdate u = update_material(p, de, s);
    REQUIRE(u.yielded);
    auto exact = [&](const Vec4& e) { return update_material(p, e, s); };
    const Mat4 fd = fd_tangent(exact, de, 1e-6 * ey);
    CHECK((u.tangent - fd).norm() / fd.norm() < 1e-6);
    if (p.has_potential()) {
      CHECK((fd_energy(exact, de, 1e-6 * ey) - u.stress).norm() / u.stress.norm() < 1e-6);
      CHECK((u.tangent - u.tangent.transpose()).norm() < 1e-9 * u.tangent.norm());
    }
    // With the recovery frozen there is a potential and the tangent is its symmetric Hessian.
    const FrozenRecovery frozen{0.7 * (u.trial.eq_plastic_strain - s.eq_plastic_strain)};
    auto frozen_update = [&](const Vec4& e) { return update_material(p, e, s, frozen); };
    const MaterialUpdate f = frozen_update(de);
    CHECK((f.tangent - fd_tangent(frozen_update, de, 1e-6 * ey)).norm() / f.tangent.norm() < 1e-6);
    CHECK((fd_energy(frozen_update, de, 1e-6 * ey) - f.stress).norm() / f.stress.norm() < 1e-6);
    CHECK((f.tangent - f.tangent.transpose()).norm() < 1e-9 * f.tangent.norm());
  }
}

namespace {

Vec4 deviator_of(const Vec4& stress) {
  const Real mean = (stress(0) + stress(1) + stress(2)) / 3.0;
  return stress - mean * Vec4(1.0, 1.0, 1.0, 0.0);
}
Real norm_of(const Vec4& t) { return std::sqrt(t(0) * t(0) + t(1) * t(1) + t(2) * t(2) + 2.0 * t(3) * t(3)); }

// Chaboche with four back-stresses, one fast to saturate (gamma d ~ 1 to 10 over one increment).
MaterialParams chaboche4_fast() {
  MaterialParams p = chaboche({{1.0e6, 1.0e4}, {1.5e5, 2000.0}, {1.0e4, 60.0}, {2.0e3, 0.0}});
  p.voce_saturation = 60.0;
  p.voce_rate = 20.0;
  return p;
}

}  // namespace

// The consistency iteration stops early (its first iterate from a model, its last Newton step taken
// to first order; docs/model.md, Hardening laws): what it returns must still solve the
// backward-Euler equations to round-off, from small to large plastic increments:
//   q(xi) = sigma_Y(eps_p + dp),  xi = s - sum alpha_i,  s = s_trial - 2G deps_p,  deps_p = 3/2 dp xi/q(xi),
//   alpha_i (1 + gamma_i dp) = alpha_i^n + 2/3 C_i deps_p.
TEST_CASE("The return mapping of every recovery law solves the backward-Euler equations to round-off",
          "[material][hardening]") {
  for (const auto& [name, p] : std::vector<std::pair<std::string, MaterialParams>>{
           {"Armstrong-Frederick", armstrong_frederick()},
           {"Chaboche", chaboche3()},
           {"Chaboche, four with Voce", chaboche4_fast()},
           {"Chaboche, ten with Voce softening", chaboche10_softening()}}) {
    const Real ey = p.yield_stress / p.youngs_modulus;
    const Real g = p.shear_modulus();
    const Vec4 direction(0.7, -0.2, 0.05, 0.8);
    const MaterialUpdate onto_surface = update_material(p, 2.0 * ey * direction, prestate(p));
    REQUIRE(onto_surface.yielded);
    const MaterialState s = onto_surface.trial;  // on the surface, loading on along `direction`
    for (const Real size : {1e-3, 0.03, 0.3, 1.0, 3.0, 10.0, 30.0}) {
      INFO(name << ", increment " << size << " yield strains");
      const Vec4 de = size * ey * direction;
      const MaterialUpdate u = update_material(p, de, s);
      REQUIRE(u.yielded);
      const Real dp = u.trial.eq_plastic_strain - s.eq_plastic_strain;
      Vec4 xi = deviator_of(u.stress);
      for (int i = 0; i < p.n_chaboche; ++i) xi -= u.trial.back_stress[static_cast<std::size_t>(i)];
      const Real q = von_mises(xi);  // xi is a deviator
      CHECK(std::abs(q - u.trial.yield_stress) <= 1e-12 * u.trial.yield_stress);
      const Vec4 d_eps_p = 1.5 * dp * xi / q;
      const Vec4 s_trial = deviator_of(s.stress + elastic_matrix(p) * de);
      CHECK(norm_of(deviator_of(u.stress) - (s_trial - 2.0 * g * d_eps_p)) <= 1e-12 * norm_of(s_trial));
      for (int i = 0; i < p.n_chaboche; ++i) {
        const std::size_t k = static_cast<std::size_t>(i);
        const BackStressLaw law = p.chaboche[k];
        const Vec4 lhs = u.trial.back_stress[k] * (1.0 + law.recovery * dp);
        const Vec4 rhs = s.back_stress[k] + 2.0 / 3.0 * law.modulus * d_eps_p;
        CHECK(norm_of(lhs - rhs) <= 1e-12 * (norm_of(s.back_stress[k]) + law.modulus * norm_of(d_eps_p)));
      }
    }
  }
}

TEST_CASE("Armstrong-Frederick's tangent is not symmetric, and its frozen recovery has the exact update as fixed point",
          "[material][hardening]") {
  const MaterialParams p = chaboche3();
  const MaterialState s = prestate(p);
  const Real ey = p.yield_stress / p.youngs_modulus;
  const Vec4 de = ey * Vec4(0.7, -0.2, 0.05, 0.8);
  const MaterialUpdate exact = update_material(p, de, s);
  CHECK((exact.tangent - exact.tangent.transpose()).norm() > 1e-6 * exact.tangent.norm());

  // d* <- d(d*) from d* = 0 converges to the exact update (a contraction: the recovery factor
  // 1/(1 + gamma d) changes slowly with d).
  Real d_star = 0.0;
  MaterialUpdate f;
  int iterations = 0;
  for (; iterations < 50; ++iterations) {
    f = update_material(p, de, s, FrozenRecovery{d_star});
    const Real d = f.trial.eq_plastic_strain - s.eq_plastic_strain;
    if (std::abs(d - d_star) <= 1e-14 * d) break;
    d_star = d;
  }
  INFO("fixed-point iterations: " << iterations);
  CHECK(iterations < 50);
  CHECK((f.stress - exact.stress).norm() < 1e-11 * exact.stress.norm());
  for (int i = 0; i < p.n_chaboche; ++i)
    CHECK((f.trial.back_stress[i] - exact.trial.back_stress[i]).norm() <=
          1e-10 * exact.trial.back_stress[i].norm() + 1e-12);
}

TEST_CASE("Hardening parameters are checked", "[material][hardening]") {
  std::string why;
  MaterialParams p = armstrong_frederick();
  CHECK(p.is_valid(&why));
  p.tangent_modulus = 1000.0;
  CHECK_FALSE(p.is_valid(&why));
  CHECK(why.find("material.tangent_modulus") != std::string::npos);
  p = armstrong_frederick();
  p.chaboche[0].recovery = -1.0;
  CHECK_FALSE(p.is_valid(&why));
  CHECK(why.find("material.chaboche_gamma = -1: entry 1") != std::string::npos);
  p = armstrong_frederick();
  p.n_chaboche = kMaxBackStresses + 1;
  CHECK_FALSE(p.is_valid(&why));
  CHECK(why.find("1 to 10 back-stresses") != std::string::npos);
  p = chaboche10_softening();
  CHECK(p.is_valid(&why));
  p.voce_saturation = -p.yield_stress;  // the yield stress would saturate at zero
  CHECK_FALSE(p.is_valid(&why));
  CHECK(why.find("material.voce_Q = -250: must satisfy yield_stress + voce_Q > 0") != std::string::npos);
  p = chaboche10_softening();
  p.voce_rate = 3.1 * p.shear_modulus() / 60.0;  // softens faster than 3G
  CHECK_FALSE(p.is_valid(&why));
  CHECK(why.find("voce_Q * voce_b > -3G") != std::string::npos);
  p = prager();
  p.integration = StressIntegration::Substep;
  CHECK_FALSE(p.is_valid(&why));
  CHECK(why.find("stress_integration") != std::string::npos);
  p = prager();
  p.hardening = Hardening::Mixed;
  p.kinematic_fraction = 1.5;
  CHECK_FALSE(p.is_valid(&why));
  CHECK(why.find("kinematic_fraction") != std::string::npos);
}

TEST_CASE("The continuum tangent of a kinematic state is the consistent tangent of a vanishing plastic increment",
          "[material][hardening]") {
  // The run-time monotonicity monitor's C^EP (docs/model.md, Hardening laws): xi = s - alpha and
  // the state's hardening modulus h = sigma_Y' + sum (C_i - gamma_i sqrt(3/2) n:alpha_i).
  for (const auto& [name, p] : laws()) {
    INFO(name);
    MaterialState s = prestate(p);
    const Real ey = p.yield_stress / p.youngs_modulus;
    // Push the state plastically along its own flow, so it sits on the surface.
    Vec4 xi = s.stress;
    const Real mean = (s.stress(0) + s.stress(1) + s.stress(2)) / 3.0;
    xi.head<3>().array() -= mean;
    for (int i = 0; i < p.n_back_stresses(); ++i) xi -= s.back_stress[static_cast<std::size_t>(i)];
    Vec4 flow = xi / xi.norm();
    flow(3) *= 2.0;  // as an engineering strain
    const MaterialUpdate push = update_material(p, 0.5 * ey * flow, s);
    REQUIRE(push.yielded);
    s = push.trial;
    const MaterialUpdate tiny = update_material(p, 1e-9 * ey * flow, s);
    REQUIRE(tiny.yielded);
    const Mat4 continuum = continuum_tangent(p, s);
    CHECK((continuum - tiny.tangent).norm() / continuum.norm() < 1e-6);
    CHECK((continuum - elastic_matrix(p)).norm() > 1e-3 * continuum.norm());
  }
}
