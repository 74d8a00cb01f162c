// Plane-strain J2 plasticity against closed-form material-point answers, finite differences of
// the tangent and of the incremental energy, and the Substep integration against the return map.
#include <Eigen/LU>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "roller/core/error.hpp"
#include "roller/material/j2_plasticity.hpp"
#include "roller/material/uniaxial_point.hpp"

using namespace roller;

namespace {

const Real kSqrt3 = std::sqrt(3.0);

MaterialParams steel(Real tangent_ratio, StressIntegration integration = StressIntegration::ReturnMapping) {
  MaterialParams p;
  p.youngs_modulus = 2.1e5;
  p.poisson_ratio = 0.3;
  p.plastic = true;
  p.yield_stress = 250.0;
  p.tangent_modulus = tangent_ratio * p.youngs_modulus;
  p.integration = integration;
  return p;
}

Real yield_strain(const MaterialParams& p) { return p.yield_stress / p.youngs_modulus; }

Vec4 vec4(Real xx, Real yy, Real zz, Real xy) { return (Vec4() << xx, yy, zz, xy).finished(); }

MaterialState advance(const MaterialParams& p, const Vec4& strain_increment, const MaterialState& state) {
  return update_material(p, strain_increment, state).trial;
}

// A state on the yield surface reached by a non-proportional plastic path (tension, then
// shear), so that stress, hardening and the next increment are not aligned.
MaterialState plastic_prestate(const MaterialParams& p) {
  const Real ey = yield_strain(p);
  MaterialState s = initial_state(p);
  s = advance(p, ey * vec4(2.0, -0.5, 0.0, 0.0), s);
  s = advance(p, ey * vec4(0.3, 0.2, 0.0, 2.5), s);
  REQUIRE(s.eq_plastic_strain > 0.0);
  REQUIRE(von_mises(s.stress) == Approx(s.yield_stress).epsilon(1e-12));
  return s;
}

template <typename A, typename B>
Real relative_error(const Eigen::MatrixBase<A>& approx, const Eigen::MatrixBase<B>& exact) {
  return (approx - exact).norm() / exact.norm();
}

// Central differences of the stress with respect to the strain increment.
Mat4 fd_stress_derivative(const MaterialParams& p, const Vec4& de, const MaterialState& state) {
  const Real h = 1e-6 * yield_strain(p);
  Mat4 d;
  for (int j = 0; j < 4; ++j) {
    Vec4 plus = de, minus = de;
    plus(j) += h;
    minus(j) -= h;
    d.col(j) = (update_material(p, plus, state).stress - update_material(p, minus, state).stress) / (2.0 * h);
  }
  return d;
}

// Central differences of the energy density with respect to the strain increment.
Vec4 fd_energy_gradient(const MaterialParams& p, const Vec4& de, const MaterialState& state) {
  const Real h = 1e-6 * yield_strain(p);
  Vec4 g;
  for (int j = 0; j < 4; ++j) {
    Vec4 plus = de, minus = de;
    plus(j) += h;
    minus(j) -= h;
    g(j) = (update_material(p, plus, state).energy - update_material(p, minus, state).energy) / (2.0 * h);
  }
  return g;
}

// The same for plane-strain compression: zz strain held at zero, S_yy = 0.
MaterialUpdate plane_strain_compression_increment(const MaterialParams& p, Real d_axial, const MaterialState& state) {
  const Real nu = p.poisson_ratio;
  Vec4 de = vec4(d_axial, -nu / (1.0 - nu) * d_axial, 0.0, 0.0);
  for (int iteration = 0; iteration < 30; ++iteration) {
    const MaterialUpdate u = update_material(p, de, state);
    if (std::abs(u.stress(1)) <= 1e-11 * p.yield_stress) return u;
    de(1) -= u.stress(1) / u.tangent(1, 1);
  }
  FAIL("plane-strain compression Newton did not converge");
  return {};
}

// Bilinear uniaxial answer on a path loading to eps_max and then reversing: elastic unloading
// with slope E to -sigma_max (isotropic hardening), then reverse yielding with slope E_T.
struct UniaxialAnswer {
  Real stress;
  Real eq_plastic_strain;
};

UniaxialAnswer bilinear_loading(const MaterialParams& p, Real strain) {
  const Real ey = yield_strain(p);
  if (strain <= ey) return {p.youngs_modulus * strain, 0.0};
  const Real stress = p.yield_stress + p.tangent_modulus * (strain - ey);
  return {stress, strain - stress / p.youngs_modulus};
}

UniaxialAnswer bilinear_reversal(const MaterialParams& p, Real eps_max, Real strain) {
  const UniaxialAnswer top = bilinear_loading(p, eps_max);
  const Real e = p.youngs_modulus;
  const Real eps_reverse = eps_max - 2.0 * top.stress / e;
  if (strain >= eps_reverse) return {top.stress - e * (eps_max - strain), top.eq_plastic_strain};
  const Real stress = -top.stress - p.tangent_modulus * (eps_reverse - strain);
  const Real axial_plastic_top = eps_max - top.stress / e;
  return {stress, top.eq_plastic_strain + axial_plastic_top - (strain - stress / e)};
}

// W_pl = int sigma_pl d eps_p for linear hardening.
Real plastic_work_at(const MaterialParams& p, Real eq_plastic_strain) {
  return p.yield_stress * eq_plastic_strain + 0.5 * p.plastic_modulus() * eq_plastic_strain * eq_plastic_strain;
}

}  // namespace

// ---- elasticity -------------------------------------------------------------------------------

TEST_CASE("elastic matrix gives the textbook plane-strain answers", "[material]") {
  const MaterialParams p = steel(0.07);
  const Real e = p.youngs_modulus, nu = p.poisson_ratio;
  const Mat4 c = elastic_matrix(p);
  CHECK(c.isApprox(c.transpose(), 0.0));

  SECTION("uniaxial strain") {
    const Real eps = 1e-4;
    const Vec4 s = c * vec4(eps, 0.0, 0.0, 0.0);
    const Real factor = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
    CHECK(s(0) == Approx(factor * (1.0 - nu) * eps).epsilon(1e-14));
    CHECK(s(1) == Approx(factor * nu * eps).epsilon(1e-14));
    CHECK(s(2) == Approx(factor * nu * eps).epsilon(1e-14));
    CHECK(s(3) == 0.0);
  }
  SECTION("pure shear: engineering strain in, tensor stress out") {
    const Real gamma = 2e-4;
    const Vec4 s = c * vec4(0.0, 0.0, 0.0, gamma);
    CHECK(s(3) == Approx(e / (2.0 * (1.0 + nu)) * gamma).epsilon(1e-14));
    CHECK(s.head<3>().norm() == 0.0);
  }
  SECTION("uniaxial stress needs strains sigma/E and -nu sigma/E") {
    const Vec4 strain = c.inverse() * vec4(100.0, 0.0, 0.0, 0.0);
    CHECK(relative_error(strain, vec4(100.0 / e, -nu * 100.0 / e, -nu * 100.0 / e, 0.0)) < 1e-13);
  }
  SECTION("plane-strain modulus E/(1-nu^2) with S_yy = 0 and zz strain 0") {
    const Mat2 c2 = (Mat2() << c(0, 0), c(0, 1), c(1, 0), c(1, 1)).finished();
    const Real modulus = 1.0 / c2.inverse()(0, 0);
    CHECK(modulus == Approx(e / (1.0 - nu * nu)).epsilon(1e-13));
  }
}

TEST_CASE("an elastic material is linear, stores no plastic state and has the quadratic energy", "[material]") {
  MaterialParams p;  // plastic = false
  MaterialState committed = initial_state(p);
  CHECK(committed.yield_stress == 0.0);
  committed.stress = vec4(10.0, -20.0, 5.0, 7.0);
  const Vec4 de = vec4(1e-3, -2e-3, 0.5e-3, 3e-3);  // far beyond any yield point of steel
  const MaterialUpdate u = update_material(p, de, committed);
  const Mat4 c = elastic_matrix(p);
  CHECK(relative_error(u.stress, committed.stress + c * de) < 1e-15);
  CHECK(u.tangent == c);
  CHECK(u.energy == Approx(committed.stress.dot(de) + 0.5 * de.dot(c * de)).epsilon(1e-14));
  CHECK_FALSE(u.yielded);
  CHECK(u.trial.stress == u.stress);
  CHECK(u.trial.eq_plastic_strain == 0.0);
  CHECK(u.trial.plastic_work == 0.0);
  CHECK(u.trial.yield_stress == 0.0);
}

TEST_CASE("initial state is stress free at the initial yield stress", "[material]") {
  const MaterialState s = initial_state(steel(0.07));
  CHECK(s.stress.isZero(0.0));
  CHECK(s.eq_plastic_strain == 0.0);
  CHECK(s.plastic_work == 0.0);
  CHECK(s.yield_stress == 250.0);
}

TEST_CASE("sqrt_j2 and von_mises include zz and count the shear twice", "[material]") {
  CHECK(von_mises(vec4(100.0, 0.0, 0.0, 0.0)) == Approx(100.0).epsilon(1e-15));
  CHECK(von_mises(vec4(0.0, 0.0, 100.0, 0.0)) == Approx(100.0).epsilon(1e-15));
  CHECK(sqrt_j2(vec4(0.0, 0.0, 0.0, 40.0)) == Approx(40.0).epsilon(1e-15));
  CHECK(von_mises(vec4(0.0, 0.0, 0.0, 40.0)) == Approx(40.0 * kSqrt3).epsilon(1e-15));
  CHECK(von_mises(vec4(-70.0, -70.0, -70.0, 0.0)) == Approx(0.0).margin(1e-13));
  // Plane-strain incompressible flow: S_zz = (S_xx + S_yy)/2 gives q = sqrt(3)/2 |S_xx - S_yy|.
  CHECK(von_mises(vec4(-200.0, 0.0, -100.0, 0.0)) == Approx(100.0 * kSqrt3).epsilon(1e-15));
  CHECK(von_mises(vec4(3.0, -1.0, 2.0, 5.0)) == Approx(kSqrt3 * sqrt_j2(vec4(3.0, -1.0, 2.0, 5.0))));
}

// ---- closed-form material-point paths ---------------------------------------------------------

TEST_CASE("uniaxial stress follows the bilinear curve, through reverse yielding", "[material]") {
  const Real ratio = GENERATE(0.07, 0.0, 0.9);
  CAPTURE(ratio);
  const MaterialParams p = steel(ratio);
  const Real eps_max = 8.05 * yield_strain(p);  // increments straddle first and reverse yield
  const int n_load = 60, n_unload = 120;

  MaterialState state = initial_state(p);
  Real strain = 0.0;
  Real max_lateral_stress = 0.0;
  for (int k = 1; k <= n_load + n_unload; ++k) {
    const Real d = k <= n_load ? eps_max / n_load : -2.0 * eps_max / n_unload;
    const MaterialUpdate u = uniaxial_strain_step(p, d, state).update;
    state = u.trial;
    strain += d;
    const UniaxialAnswer exact = k <= n_load ? bilinear_loading(p, strain) : bilinear_reversal(p, eps_max, strain);
    CAPTURE(k, strain);
    REQUIRE(state.stress(0) == Approx(exact.stress).margin(1e-9 * p.yield_stress));
    REQUIRE(state.eq_plastic_strain == Approx(exact.eq_plastic_strain).margin(1e-9 * yield_strain(p)));
    REQUIRE(state.plastic_work == Approx(plastic_work_at(p, exact.eq_plastic_strain)).epsilon(1e-9).margin(1e-12));
    max_lateral_stress = std::max(max_lateral_stress, state.stress.tail<3>().cwiseAbs().maxCoeff());
  }
  CHECK(max_lateral_stress < 1e-10 * p.yield_stress);
  CHECK(state.eq_plastic_strain > 0.0);
}

TEST_CASE("simple shear follows tau = (sigma_y0 + H' eps_p)/sqrt(3)", "[material]") {
  const Real ratio = GENERATE(0.07, 0.0, 0.9);
  const int n_increments = GENERATE(1, 7, 40);  // radial return is exact on this radial path
  CAPTURE(ratio, n_increments);
  const MaterialParams p = steel(ratio);
  const Real g = p.shear_modulus(), h = p.plastic_modulus(), sy = p.yield_stress;
  const Real gamma_total = 10.0 * sy / (kSqrt3 * g);

  MaterialState state = initial_state(p);
  for (int k = 1; k <= n_increments; ++k) {
    state = advance(p, vec4(0.0, 0.0, 0.0, gamma_total / n_increments), state);
    const Real gamma = gamma_total * k / n_increments;
    // gamma = tau/G + sqrt(3) eps_p, tau = (sigma_y0 + H' eps_p)/sqrt(3)
    const Real eps_p = std::max(0.0, (gamma - sy / (kSqrt3 * g)) / (h / (kSqrt3 * g) + kSqrt3));
    const Real sigma_pl = sy + h * eps_p;
    const Real tau = eps_p > 0.0 ? sigma_pl / kSqrt3 : g * gamma;
    const Real work = h > 0.0 ? (sigma_pl * sigma_pl - sy * sy) / (2.0 * h) : sy * eps_p;
    CAPTURE(k);
    REQUIRE(state.stress(3) == Approx(tau).epsilon(1e-12));
    REQUIRE(state.stress.head<3>().cwiseAbs().maxCoeff() < 1e-12 * sy);
    REQUIRE(state.eq_plastic_strain == Approx(eps_p).epsilon(1e-10).margin(1e-16));
    REQUIRE(state.plastic_work == Approx(work).epsilon(1e-10).margin(1e-14));
    REQUIRE(state.yield_stress == Approx(sigma_pl).epsilon(1e-14));
  }
}

TEST_CASE("plane-strain compression of a perfectly plastic strip tends to 2/sqrt(3) sigma_y", "[material]") {
  const MaterialParams p = steel(0.0);
  const Real sy = p.yield_stress, nu = p.poisson_ratio;
  const Real d = -0.1 * yield_strain(p);
  // Elastic: S_zz = nu S_xx, so first yield at |S_xx| = sigma_y / sqrt(1 - nu + nu^2).
  const Real first_yield = sy / std::sqrt(1.0 - nu + nu * nu);
  const Real limit = 2.0 / kSqrt3 * sy;

  MaterialState state = initial_state(p);
  Real previous = 0.0;
  for (int k = 1; k <= 400; ++k) {
    const MaterialUpdate u = plane_strain_compression_increment(p, d, state);
    state = u.trial;
    const Real s_xx = -state.stress(0);
    CAPTURE(k, s_xx);
    if (!u.yielded) {
      REQUIRE(s_xx == Approx(p.youngs_modulus / (1.0 - nu * nu) * (-d) * k).epsilon(1e-12));
      REQUIRE(s_xx <= first_yield);
    } else {
      REQUIRE(s_xx >= first_yield);
      REQUIRE(von_mises(state.stress) == Approx(sy).epsilon(1e-12));
    }
    REQUIRE(s_xx >= previous - 1e-14 * limit);  // monotone approach from below
    REQUIRE(s_xx <= limit * (1.0 + 1e-14));
    previous = s_xx;
  }
  CHECK(-state.stress(0) == Approx(limit).epsilon(1e-12));
  CHECK(state.stress(2) == Approx(0.5 * state.stress(0)).epsilon(1e-12));
  CHECK(std::abs(state.stress(1)) < 1e-11 * sy);
}

// ---- tangents -----------------------------------------------------------------------------------

TEST_CASE("consistent tangent matches central differences of the stress", "[material]") {
  const Real ratio = GENERATE(0.07, 0.0, 0.99);
  CAPTURE(ratio);
  const MaterialParams p = steel(ratio);
  const Real ey = yield_strain(p);

  SECTION("elastic state") {
    const MaterialState s = initial_state(p);
    const Vec4 de = ey * vec4(0.3, -0.1, 0.05, 0.2);
    const MaterialUpdate u = update_material(p, de, s);
    REQUIRE_FALSE(u.yielded);
    CHECK(u.tangent == elastic_matrix(p));
    CHECK(relative_error(u.tangent, fd_stress_derivative(p, de, s)) < 1e-7);
  }
  SECTION("first yield inside the increment") {
    const MaterialState s = initial_state(p);
    const Vec4 de = ey * vec4(3.0, -0.9, 0.2, 1.5);
    const MaterialUpdate u = update_material(p, de, s);
    REQUIRE(u.yielded);
    CHECK(relative_error(u.tangent, fd_stress_derivative(p, de, s)) < 1e-6);
  }
  SECTION("non-proportional plastic loading from a hardened state") {
    const MaterialState s = plastic_prestate(p);
    const Vec4 de = ey * vec4(0.5, -0.2, 0.1, 0.8);
    const MaterialUpdate u = update_material(p, de, s);
    REQUIRE(u.yielded);
    CHECK(relative_error(u.tangent, fd_stress_derivative(p, de, s)) < 1e-6);
    CHECK(relative_error(u.tangent, u.tangent.transpose()) < 1e-15);
  }
  SECTION("elastic unloading from a plastic state") {
    const MaterialState s = plastic_prestate(p);
    const Vec4 de = -0.5 * ey * vec4(0.3, 0.2, 0.0, 2.5);
    const MaterialUpdate u = update_material(p, de, s);
    REQUIRE_FALSE(u.yielded);
    CHECK(u.tangent == elastic_matrix(p));
    CHECK(relative_error(u.tangent, fd_stress_derivative(p, de, s)) < 1e-7);
  }
}

TEST_CASE("continuum tangent: hardening-limited along the flow direction, elastic across it", "[material]") {
  const Real ratio = GENERATE(0.07, 0.0, 0.99);
  CAPTURE(ratio);
  const MaterialParams p = steel(ratio);
  const MaterialState s = plastic_prestate(p);
  const Mat4 c = elastic_matrix(p);
  const Mat4 c_ep = continuum_tangent(p, s.stress, s.yield_stress);
  const Real g = p.shear_modulus(), h = p.plastic_modulus();
  const Real mean = s.stress.head<3>().sum() / 3.0;
  const Vec4 dev = s.stress - mean * vec4(1.0, 1.0, 1.0, 0.0);

  CHECK(relative_error(c_ep, c_ep.transpose()) < 1e-15);
  // The strain whose elastic stress is along s: C^EP C^-1 s = H'/(3G + H') s (0 for E_T = 0).
  const Vec4 response = c_ep * (c.inverse() * dev);
  CHECK((response - h / (3.0 * g + h) * dev).norm() < 1e-12 * dev.norm());
  // A volumetric strain and a deviatoric strain orthogonal to s (s:e = 0) stay elastic.
  const Vec4 volumetric = vec4(1e-3, 1e-3, 1e-3, 0.0);
  CHECK(relative_error(c_ep * volumetric, c * volumetric) < 1e-13);
  Vec4 orthogonal = vec4(0.0, 0.0, 0.0, 1e-3);
  const Vec4 axial_dev = vec4(2e-3, -1e-3, -1e-3, 0.0);
  orthogonal -= dev.dot(orthogonal) / dev.dot(axial_dev) * axial_dev;  // s:e = s_vec . e_vec
  REQUIRE(std::abs(dev.dot(orthogonal)) < 1e-14 * dev.norm() * orthogonal.norm());
  CHECK(relative_error(c_ep * orthogonal, c * orthogonal) < 1e-12);
  // The consistent tangent of a vanishing plastic increment is the continuum tangent.
  const MaterialUpdate u = update_material(p, 1e-9 * yield_strain(p) * c.inverse() * dev, s);
  REQUIRE(u.yielded);
  CHECK(relative_error(u.tangent, c_ep) < 1e-7);
}

TEST_CASE("continuum tangent on the surface is the general form of thesis (2.29)-(2.30)", "[material]") {
  const Real ratio = GENERATE(0.07, 0.0, 0.99);
  CAPTURE(ratio);
  const MaterialParams p = steel(ratio);
  const MaterialState s = plastic_prestate(p);
  const Mat4 c = elastic_matrix(p);
  // n_q = s (strain-like: shear doubled), n_p = 2/3 H' s, C^EP = C - C n (C n)^T / (n_p.n + n.C.n)
  const Vec4 dev = s.stress - s.stress.head<3>().mean() * vec4(1.0, 1.0, 1.0, 0.0);
  const Vec4 n = (Vec4() << dev.head<3>(), 2.0 * dev(3)).finished();
  const Real np_dot_n = 2.0 / 3.0 * p.plastic_modulus() * dev.dot(n);
  const Mat4 expected = c - (c * n) * (c * n).transpose() / (np_dot_n + n.dot(c * n));
  CHECK(relative_error(continuum_tangent(p, s.stress, s.yield_stress), expected) < 1e-13);
}

TEST_CASE("plastic tangent is the thesis's explicit C^EP with beta, also off the surface", "[material]") {
  const MaterialParams p = steel(GENERATE(0.07, 1.0 / 3.0, 0.0));
  const Real sigma_pl = GENERATE(5.0, 40.0, 105.0);
  const Vec4 stress = vec4(-150.0, 60.0, -30.0, 25.0);
  CAPTURE(p.tangent_modulus, sigma_pl);
  const Real e = p.youngs_modulus, nu = p.poisson_ratio, et = p.tangent_modulus;
  const Vec4 s = stress - stress.head<3>().mean() * vec4(1.0, 1.0, 1.0, 0.0);
  // The thesis's (2.29) (docs/model.md, Sub-stepping):
  //   beta = 3/(2 sigma^2) / (1 + 2/3 (E E_T/(E - E_T)) (1 + nu)/E), on [xx, yy, xy].
  const Real beta = 1.5 / (sigma_pl * sigma_pl) / (1.0 + 2.0 / 3.0 * e * et / (e - et) * (1.0 + nu) / e);
  const int idx[3] = {0, 1, 3};
  const Real diag[3] = {(1.0 - nu) / (1.0 - 2.0 * nu), (1.0 - nu) / (1.0 - 2.0 * nu), 0.5};
  const Mat4 c_ep = plastic_tangent(p, stress, sigma_pl);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const Real elastic = i == j ? diag[i] : (i < 2 && j < 2 ? nu / (1.0 - 2.0 * nu) : 0.0);
      const Real thesis = e / (1.0 + nu) * (elastic - beta * s(idx[i]) * s(idx[j]));
      CAPTURE(i, j);
      CHECK(c_ep(idx[i], idx[j]) == Approx(thesis).epsilon(1e-13).margin(1e-9));
    }
  }
  CHECK_THROWS_AS(plastic_tangent(p, stress, 0.0), std::logic_error);
}

TEST_CASE("continuum tangent is elastic inside the yield surface and for elastic material", "[material]") {
  const MaterialParams p = steel(0.07);
  const Vec4 inside = vec4(100.0, 0.0, 30.0, 10.0);
  REQUIRE(von_mises(inside) < p.yield_stress);
  CHECK(continuum_tangent(p, inside, p.yield_stress) == elastic_matrix(p));
  MaterialParams elastic = p;
  elastic.plastic = false;
  CHECK(continuum_tangent(elastic, vec4(900.0, 0.0, 0.0, 0.0), 1.0) == elastic_matrix(elastic));
  // Perfect plasticity: the tangent is singular, with the flow direction as its null vector.
  const MaterialParams perfect = steel(0.0);
  const Vec4 on_surface = vec4(perfect.yield_stress, 0.0, 0.0, 0.0);
  const Mat4 c_ep = continuum_tangent(perfect, on_surface, perfect.yield_stress);
  const Mat4 c = elastic_matrix(perfect);
  CHECK(std::abs(c_ep.determinant()) < 1e-12 * c.determinant());
  const Vec4 flow_strain = vec4(2.0, -1.0, -1.0, 0.0);
  CHECK((c_ep * flow_strain).norm() < 1e-12 * (c * flow_strain).norm());
}

// ---- energy -------------------------------------------------------------------------------------

TEST_CASE("energy density is the incremental potential: its gradient is the stress", "[material]") {
  const Real ratio = GENERATE(0.07, 0.0, 0.99);
  CAPTURE(ratio);
  const MaterialParams p = steel(ratio);
  const Real ey = yield_strain(p);
  struct Case {
    const char* name;
    MaterialState state;
    Vec4 de;
    bool plastic;
  };
  const std::vector<Case> cases = {
      {"elastic step", initial_state(p), ey * vec4(0.3, -0.1, 0.05, 0.2), false},
      {"first yield inside the step", initial_state(p), ey * vec4(3.0, -0.9, 0.2, 1.5), true},
      {"plastic step from a hardened state", plastic_prestate(p), ey * vec4(0.5, -0.2, 0.1, 0.8), true},
      {"unloading from a hardened state", plastic_prestate(p), -0.5 * ey * vec4(0.3, 0.2, 0.0, 2.5), false},
  };
  for (const Case& k : cases) {
    CAPTURE(k.name);
    const MaterialUpdate u = update_material(p, k.de, k.state);
    REQUIRE(u.yielded == k.plastic);
    CHECK(relative_error(fd_energy_gradient(p, k.de, k.state), u.stress) < 1e-7);
  }
}

TEST_CASE("radial return minimises the incremental energy over the plastic strain increment", "[material]") {
  const Real ratio = GENERATE(0.07, 0.0, 0.99);
  CAPTURE(ratio);
  const MaterialParams p = steel(ratio);
  const Mat4 c = elastic_matrix(p);
  const Mat4 compliance = c.inverse();
  const MaterialState s = plastic_prestate(p);
  const Vec4 de = yield_strain(p) * vec4(0.5, -0.2, 0.1, 0.8);
  const MaterialUpdate u = update_material(p, de, s);
  REQUIRE(u.yielded);

  // W(dE; dEp) = psi(eps_e_old + dE - dEp) - psi(eps_e_old) + int sigma_pl d eps_p over
  // deviatoric dEp (engineering vector), eps_p = sqrt(2/3 dEp:dEp).
  const Vec4 eps_e_old = compliance * s.stress;
  const auto energy_for = [&](const Vec4& d_plastic) {
    const Vec4 eps_e = eps_e_old + de - d_plastic;
    const Real dep = std::sqrt(2.0 / 3.0 * (d_plastic.head<3>().squaredNorm() + 0.5 * d_plastic(3) * d_plastic(3)));
    const Real eps_p = s.eq_plastic_strain;
    return 0.5 * eps_e.dot(c * eps_e) - 0.5 * eps_e_old.dot(c * eps_e_old) + p.yield_stress * dep +
           p.plastic_modulus() * (eps_p * dep + 0.5 * dep * dep);
  };
  const Vec4 d_plastic = de - compliance * (u.stress - s.stress);
  REQUIRE(std::abs(d_plastic.head<3>().sum()) < 1e-12 * d_plastic.norm());
  CHECK(energy_for(d_plastic) == Approx(u.energy).epsilon(1e-10));
  const Real scale = 0.05 * d_plastic.norm();
  const std::vector<Vec4> perturbations = {vec4(1.0, -1.0, 0.0, 0.0), vec4(1.0, 0.0, -1.0, 0.0),
                                           vec4(0.0, 0.0, 0.0, 1.0),  vec4(0.5, 0.5, -1.0, -0.7),
                                           -d_plastic / scale,        d_plastic / scale};
  for (const Vec4& dir : perturbations) {
    CAPTURE(dir.transpose());
    CHECK(energy_for(d_plastic + scale * dir) > u.energy);
  }
}

// ---- Substep ------------------------------------------------------------------------------------

TEST_CASE("Substep equals the radial return on radial paths, for any number of sub-steps", "[material]") {
  // With a fixed deviator direction forward Euler on C^EP is exact for linear hardening, and
  // the elastic fraction puts first yield exactly where it is.
  const Real ratio = GENERATE(0.07, 0.0, 0.99);
  const int n = GENERATE(1, 3, 10, 50);
  CAPTURE(ratio, n);
  MaterialParams rm = steel(ratio);
  MaterialParams sub = steel(ratio, StressIntegration::Substep);
  sub.n_substeps = n;
  const Real ey = yield_strain(rm);
  const std::vector<Vec4> radial_increments = {ey * vec4(4.0, 0.0, 0.0, 0.0), ey * vec4(0.0, 0.0, 0.0, 7.0)};
  for (const Vec4& de : radial_increments) {
    CAPTURE(de.transpose());
    const MaterialUpdate a = update_material(rm, de, initial_state(rm));
    const MaterialUpdate b = update_material(sub, de, initial_state(sub));
    REQUIRE(a.yielded);
    REQUIRE(b.yielded);
    CHECK(relative_error(b.stress, a.stress) < 1e-12);
    CHECK(b.trial.eq_plastic_strain == Approx(a.trial.eq_plastic_strain).epsilon(1e-10));
    CHECK(b.trial.plastic_work == Approx(a.trial.plastic_work).epsilon(1e-10));
    CHECK(b.trial.yield_stress == Approx(a.trial.yield_stress).epsilon(1e-12));
    CHECK(b.tangent == continuum_tangent(sub, b.stress, b.trial.yield_stress));
  }
}

TEST_CASE("Substep converges at first order on a non-radial path, to the fine return map", "[material]") {
  const Real ratio = GENERATE(0.07, 0.0, 0.99);
  CAPTURE(ratio);
  MaterialParams rm = steel(ratio);
  MaterialParams sub = steel(ratio, StressIntegration::Substep);
  const Real ey = yield_strain(rm);
  // Sheared to the surface, then pulled along x: the deviator turns from shear to tension.
  const MaterialState start = advance(rm, ey * vec4(0.0, 0.0, 0.0, 3.0), initial_state(rm));
  const Vec4 de = ey * vec4(3.0, -1.0, 0.0, 0.0);

  // Reference: the return map over many small increments (also first order, error ~ 1/N).
  const int n_fine = 200000;
  MaterialState fine = start;
  for (int k = 0; k < n_fine; ++k) fine = advance(rm, de / n_fine, fine);

  std::vector<Real> errors;
  for (int n = 1; n <= 256; n *= 4) {
    sub.n_substeps = n;
    const MaterialUpdate u = update_material(sub, de, start);
    errors.push_back((u.stress - fine.stress).norm() / rm.yield_stress);
    CAPTURE(n, errors.back());
    CHECK(von_mises(u.stress) == Approx(u.trial.yield_stress).epsilon(1e-12));
  }
  const Real rm_error = (update_material(rm, de, start).stress - fine.stress).norm() / rm.yield_stress;
  CAPTURE(errors, rm_error);
  for (std::size_t i = 1; i < errors.size(); ++i) {
    CHECK(errors[i] < errors[i - 1]);
  }
  // First order: 4x the sub-steps, 1/4 of the error (the reference is ~1e-5 x more accurate).
  CHECK(errors[3] / errors[2] == Approx(0.25).margin(0.03));
  CHECK(errors[4] / errors[3] == Approx(0.25).margin(0.03));
  CHECK(errors.back() < 1e-2 * errors.front());
  // The one-step return map is not exact here either; 256 sub-steps are far closer.
  CHECK(errors.back() < 1e-2 * rm_error);
}

TEST_CASE("Substep energy is exact for an elastic step and tends to the return-map potential", "[material]") {
  MaterialParams rm = steel(0.07);
  MaterialParams sub = steel(0.07, StressIntegration::Substep);
  const Real ey = yield_strain(rm);
  const Vec4 elastic_de = ey * vec4(0.3, -0.1, 0.05, 0.2);
  sub.n_substeps = 3;
  CHECK(update_material(sub, elastic_de, initial_state(sub)).energy ==
        Approx(update_material(rm, elastic_de, initial_state(rm)).energy).epsilon(1e-13));

  const Vec4 de = ey * vec4(4.0, 0.0, 0.0, 0.0);  // radial: the stress paths coincide
  const Real exact = update_material(rm, de, initial_state(rm)).energy;
  Real previous_error = std::numeric_limits<Real>::infinity();
  for (int n : {1, 4, 16, 64}) {
    sub.n_substeps = n;
    const Real error = std::abs(update_material(sub, de, initial_state(sub)).energy - exact) / exact;
    CAPTURE(n, error);
    CHECK(error < previous_error);
    previous_error = error;
  }
  CHECK(previous_error < 1e-4);
}

// ---- yield surface, errors --------------------------------------------------------------------

TEST_CASE("after plastic flow the stress lies on the hardened yield surface", "[material]") {
  const Real ratio = GENERATE(0.07, 0.0, 0.99);
  const StressIntegration integration = GENERATE(StressIntegration::ReturnMapping, StressIntegration::Substep);
  CAPTURE(ratio, static_cast<int>(integration));
  const MaterialParams p = steel(ratio, integration);
  const Real ey = yield_strain(p);
  const std::vector<Vec4> path = {ey * vec4(3.0, -0.9, 0.2, 1.5), ey * vec4(-0.5, 2.0, 0.0, -4.0),
                                  ey * vec4(0.1, 0.1, 0.1, 0.1), ey * vec4(-6.0, 1.0, 3.0, 0.0),
                                  ey * vec4(0.0, 0.0, 0.0, 20.0)};
  MaterialState state = initial_state(p);
  for (const Vec4& de : path) {
    const MaterialUpdate u = update_material(p, de, state);
    CAPTURE(de.transpose(), u.yielded);
    REQUIRE(u.trial.yield_stress ==
            Approx(p.yield_stress + p.plastic_modulus() * u.trial.eq_plastic_strain).epsilon(1e-14));
    if (u.yielded) {
      CHECK(std::abs(von_mises(u.stress) - u.trial.yield_stress) < 1e-10 * u.trial.yield_stress);
      CHECK(u.trial.eq_plastic_strain > state.eq_plastic_strain);
      CHECK(u.trial.plastic_work > state.plastic_work);
    } else {
      CHECK(von_mises(u.stress) <= u.trial.yield_stress);
    }
    state = u.trial;
  }
  CHECK(state.eq_plastic_strain > 0.0);
}

TEST_CASE("zero and volumetric increments from a state on the yield surface are elastic", "[material]") {
  const StressIntegration integration = GENERATE(StressIntegration::ReturnMapping, StressIntegration::Substep);
  CAPTURE(static_cast<int>(integration));
  const MaterialParams p = steel(0.07, integration);
  MaterialState s = plastic_prestate(steel(0.07));
  // Nudge the state just outside the surface, as round-off may leave it.
  s.stress += 1e-15 * s.stress.norm() * (s.stress - s.stress.head<3>().mean() * vec4(1, 1, 1, 0));
  REQUIRE(von_mises(s.stress) >= s.yield_stress);

  const MaterialUpdate zero = update_material(p, Vec4::Zero(), s);
  CHECK_FALSE(zero.yielded);
  CHECK(zero.stress == s.stress);
  CHECK(zero.energy == 0.0);
  CHECK(zero.trial.eq_plastic_strain == s.eq_plastic_strain);

  const Real dv = 1e-3;
  const MaterialUpdate volumetric = update_material(p, vec4(dv, dv, dv, 0.0), s);
  CHECK_FALSE(volumetric.yielded);
  CHECK(relative_error(volumetric.stress, s.stress + 3.0 * p.bulk_modulus() * dv * vec4(1, 1, 1, 0)) < 1e-14);
  CHECK(volumetric.trial.eq_plastic_strain == s.eq_plastic_strain);
}

TEST_CASE("inadmissible parameters give NumericalError, not NaN", "[material]") {
  MaterialParams p = steel(0.07);
  p.tangent_modulus = p.youngs_modulus;  // H' = infinity
  std::string why;
  REQUIRE_FALSE(p.is_valid(&why));
  CHECK_THROWS_WITH(update_material(p, vec4(1e-2, 0.0, 0.0, 0.0), initial_state(p)), Catch::Contains("is_valid"));
}

TEST_CASE("a non-finite strain increment throws NumericalError instead of spreading NaN", "[material]") {
  const Real bad = GENERATE(std::numeric_limits<Real>::quiet_NaN(), std::numeric_limits<Real>::infinity());
  for (const StressIntegration integration : {StressIntegration::ReturnMapping, StressIntegration::Substep}) {
    MaterialParams p = steel(0.07, integration);
    CHECK_THROWS_AS(update_material(p, vec4(1e-4, bad, 0.0, 0.0), initial_state(p)), NumericalError);
    p.plastic = false;
    CHECK_THROWS_WITH(update_material(p, vec4(bad, 0.0, 0.0, 0.0), initial_state(p)),
                      Catch::Contains("non-finite") && Catch::Contains("cut the step"));
  }
}
