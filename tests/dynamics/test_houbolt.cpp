// Houbolt integration (docs/model.md, Houbolt scheme): the single-dof oscillator integrated by
// the same history code the strip and the suspension use must show exactly the scheme's own
// period elongation and amplitude decay (roots of its characteristic polynomial), converge at
// second order, and the starting procedure must reproduce a given initial velocity.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "roller/dynamics/houbolt.hpp"
#include "roller/dynamics/suspension.hpp"

using namespace roller;

namespace {

// m u'' + k u = 0 with m = 1, k = omega^2, integrated for n steps; returns u_0..u_n.
std::vector<Real> oscillate(Real omega, Real dt, Real u0, Real v0, int n) {
  const VecX one = VecX::Constant(1, 1.0);
  HouboltHistory h = HouboltHistory::start(u0 * one, v0 * one, -omega * omega * u0 * one, dt);
  std::vector<Real> u{u0};
  for (int i = 0; i < n; ++i) {
    // (c_a + k) u_{n+1} = -a_offset
    const Real next = -h.acceleration_offset()(0) / (h.acceleration_coefficient() + omega * omega);
    h.advance(VecX::Constant(1, next));
    u.push_back(next);
  }
  return u;
}

// Times of the downward zero crossings (linear interpolation between steps).
std::vector<Real> down_crossings(const std::vector<Real>& u, Real dt) {
  std::vector<Real> t;
  for (std::size_t i = 1; i < u.size(); ++i)
    if (u[i - 1] > 0.0 && u[i] <= 0.0) t.push_back(dt * (static_cast<Real>(i) - 1.0 + u[i - 1] / (u[i - 1] - u[i])));
  return t;
}

}  // namespace

TEST_CASE("Houbolt characteristic roots: consistent limits and growing dissipation", "[dynamics][houbolt]") {
  const HouboltSpectrum small = houbolt_spectrum(1e-3);
  CHECK(small.period_ratio == Approx(1.0).margin(1e-5));
  CHECK(small.modulus == Approx(1.0).margin(1e-8));
  Real last_damping = 0.0, last_period = 1.0;
  for (Real w : {0.05, 0.1, 0.2, 0.4, 0.8}) {
    const HouboltSpectrum s = houbolt_spectrum(w);
    CHECK(s.modulus < 1.0);  // unconditionally stable, dissipative
    CHECK(s.damping_ratio > last_damping);
    CHECK(s.period_ratio > last_period);
    last_damping = s.damping_ratio;
    last_period = s.period_ratio;
  }
}

TEST_CASE("Houbolt single-dof oscillator matches the scheme's period elongation and amplitude decay",
          "[dynamics][houbolt]") {
  const Real omega = 2.0 * M_PI;  // T = 1 s
  for (Real omega_dt : {0.1, 0.3, 0.6}) {
    const Real dt = omega_dt / omega;
    const int n = static_cast<int>(std::ceil(12.0 / dt));  // twelve periods
    const std::vector<Real> u = oscillate(omega, dt, 1.0, 0.0, n);
    const HouboltSpectrum s = houbolt_spectrum(omega_dt);
    const std::vector<Real> t = down_crossings(u, dt);
    REQUIRE(t.size() >= 6);
    // Period from crossings 2..last (the start transient of the spurious roots has died out).
    const Real period = (t.back() - t[1]) / static_cast<Real>(t.size() - 2);
    CHECK(period == Approx(s.period_ratio).epsilon(2e-3));
    // Amplitude decay between the 3rd and the 10th maximum (each refined by the parabola
    // through the three samples around it).
    std::vector<Real> peaks;
    for (std::size_t i = 1; i + 1 < u.size(); ++i)
      if (u[i] > u[i - 1] && u[i] >= u[i + 1]) {
        const Real a = 0.5 * (u[i - 1] + u[i + 1]) - u[i], b = 0.5 * (u[i + 1] - u[i - 1]);
        peaks.push_back(u[i] - b * b / (4.0 * a));
      }
    REQUIRE(peaks.size() >= 10);
    const Real steps_per_period = s.period_ratio / dt;
    const Real expected = std::pow(s.modulus, 7.0 * steps_per_period);
    CHECK(peaks[9] / peaks[2] == Approx(expected).epsilon(0.02));
    INFO("omega dt = " << omega_dt << ": period ratio " << s.period_ratio << ", decay per period "
                       << std::pow(s.modulus, steps_per_period));
  }
}

TEST_CASE("Houbolt with the Taylor start converges at second order from a given initial velocity",
          "[dynamics][houbolt]") {
  // u = sin(omega t) from u0 = 0, v0 = omega: the error at t = 1 s falls 4x per halving of dt.
  const Real omega = 2.0 * M_PI;
  std::vector<Real> errors;
  for (int n : {200, 400, 800, 1600}) {
    const std::vector<Real> u = oscillate(omega, 1.0 / n, 0.0, omega, n + n / 4);
    errors.push_back(std::abs(u[n + n / 4] - std::sin(omega * 1.25)));
  }
  for (std::size_t i = 1; i < errors.size(); ++i) {
    const Real order = std::log2(errors[i - 1] / errors[i]);
    CHECK(order == Approx(2.0).margin(0.2));
  }
}

TEST_CASE("Houbolt history resampled for a cut step is exact on quadratic motion", "[dynamics][houbolt]") {
  auto u = [](Real t) { return VecX::Constant(2, 1.0 + 2.0 * t - 3.0 * t * t); };
  const Real dt = 0.1;
  const HouboltHistory h = HouboltHistory::from_values(u(0.0), u(-dt), u(-2 * dt), dt);
  const HouboltHistory r = h.resampled(dt / 4);
  CHECK(r.dt() == dt / 4);
  CHECK((r.u_nm1() - u(-dt / 4)).norm() < 1e-14);
  CHECK((r.u_nm2() - u(-dt / 2)).norm() < 1e-14);
  // Houbolt's acceleration is exact for a cubic, hence for this quadratic: -6 everywhere.
  CHECK(r.acceleration(u(dt / 4))(0) == Approx(-6.0).epsilon(1e-9));
  CHECK(h.velocity(u(dt))(0) == Approx(2.0 - 6.0 * dt).epsilon(1e-9));
}

TEST_CASE("Suspension coupling converges to the equilibrium with a linear contact spring", "[dynamics][suspension]") {
  // Static spring k against a contact that pushes up with F = k_c (d - w) while pressed (d: the
  // anchor's indentation): w = k_c d / (k + k_c) at rest (m, c = 0 except a small mass).
  SuspensionSpec spec;
  spec.mass = 1e-4;
  spec.stiffness = 1e6;
  const Real dt = 1e-3;  // m c_a = 200: quasi-static
  Suspension s(spec, HouboltHistory::at_rest(VecX::Zero(1), dt));
  const Real k_c = 3e5, d = 0.5;
  int calls = 0;
  auto force = [&](Real w) -> std::optional<Real> {
    ++calls;
    return k_c * std::max(d - w, 0.0);
  };
  const CouplingResult r = couple_suspension(s, 0.0, force, 1e-12, 1e3, 40);
  REQUIRE(r.converged());
  const Real k_eff = s.effective_stiffness();
  CHECK(r.deflection == Approx(k_c * d / (k_eff + k_c)).epsilon(1e-10));
  CHECK(r.iterations <= 4);  // the secant is exact on a linear residual after the first step
  // A contact that fails is reported, not hidden.
  auto failing = [](Real) -> std::optional<Real> { return std::nullopt; };
  const CouplingResult f = couple_suspension(s, 0.0, failing, 1e-12, 1e3, 40);
  CHECK_FALSE(f.converged());
  CHECK(f.message.find("contact solve failed") != std::string::npos);
  // A suspension far too soft for the force stops with a message instead of w = inf (a fuzzed
  // stiffness of 1e-308 gave "deflection w = inf").
  SuspensionSpec soft;
  soft.stiffness = 1e-308;
  const Suspension limp(soft, HouboltHistory::at_rest(VecX::Zero(1), dt));
  const CouplingResult g = couple_suspension(limp, 0.0, force, 1e-12, 1e3, 40);
  CHECK_FALSE(g.converged());
  CHECK(std::isfinite(g.deflection));
  CHECK(g.message.find("too soft") != std::string::npos);
}

TEST_CASE("Suspension coupling starts from the deflection's last increment carried on", "[dynamics][suspension]") {
  // Linear motion w = 0.2 + 0.05 n: the prediction of step n + 1 is exact.
  const Real dt = 1e-3;
  auto w = [](Real n) { return VecX::Constant(1, 0.2 + 0.05 * n); };
  const Suspension s(SuspensionSpec{}, HouboltHistory::from_values(w(0), w(-1), w(-2), dt));
  CHECK(s.predicted_deflection() == Approx(w(1)(0)).epsilon(1e-14));
  // At rest it stays where it is.
  const Suspension rest(SuspensionSpec{}, HouboltHistory::at_rest(VecX::Constant(1, 0.3), dt));
  CHECK(rest.predicted_deflection() == Approx(0.3).epsilon(1e-14));
}
