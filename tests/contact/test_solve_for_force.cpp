// The roller's height under a prescribed force: the root finder on synthetic force laws (a linear
// contact spring, Hertz's line-contact law, a roller that starts above the strip, loads nothing
// can carry, a failing solve).
#include <catch2/catch.hpp>

#include <cmath>

#include "roller/contact/force_control.hpp"

using namespace roller;
using Catch::Contains;

namespace {

ForceControlSettings settings(Real tolerance, Real guess) {
  ForceControlSettings s;
  s.force_tolerance = tolerance;
  s.stiffness_guess = guess;
  s.max_offset_change = 100.0;
  return s;
}

}  // namespace

TEST_CASE("force control: a linear contact spring is met in two solves with its stiffness as the guess",
          "[driver][force]") {
  // F = k (d - w) while d > w (the surface at w = d), 0 above it.
  const Real k = 2e5, d = 0.3;
  int calls = 0;
  auto force = [&](Real w) -> std::optional<Real> {
    ++calls;
    return k * std::max(d - w, 0.0);
  };
  for (const Real guess : {1e3, 2e5, 1e8}) {
    calls = 0;
    const ForceControlResult r = solve_for_force(1e4, 0.0, settings(1e-6, guess), force);
    REQUIRE(r.converged());
    CHECK(r.offset == Approx(d - 1e4 / k).epsilon(1e-12));
    CHECK(std::abs(r.force - 1e4) <= 1e-6);
    // The exact slope: one Newton step. A guess 200 times too soft lifts the roller off the strip
    // first (the bracket then closes by false position until two samples in contact give the
    // secant); 500 times too stiff creeps, then the secant is exact.
    CHECK(r.iterations <= (guess == k ? 2 : 10));
    CHECK(r.stiffness == Approx(k).epsilon(1e-9));
  }
}

TEST_CASE("force control: a roller above the strip is lowered onto it, Hertz's law is met", "[driver][force]") {
  // Line contact (plane strain): the approach grows like P (ln(4R/a) - 1/2) with a ~ sqrt(P):
  // a smooth, stiffening law; above the surface (approach <= 0) no force.
  const Real e_star = 2.3e5, radius = 100.0;
  auto approach = [&](Real p) {
    const Real a = std::sqrt(4.0 * p * radius / (M_PI * e_star));
    return 2.0 * p / (M_PI * e_star) * (2.0 * std::log(4.0 * radius / a) - 1.0);
  };
  auto force = [&](Real w) -> std::optional<Real> {
    const Real delta = -1.0 - w;  // the roller starts 1 mm above the surface: w = -1 touches
    if (delta <= 0.0) return 0.0;
    Real lo = 0.0, hi = 1e5;  // invert approach(p) = delta by bisection (a < 4R/sqrt(e) up to hi)
    for (int i = 0; i < 200; ++i) (approach(0.5 * (lo + hi)) < delta ? lo : hi) = 0.5 * (lo + hi);
    return 0.5 * (lo + hi);
  };
  const Real target = 1500.0;
  const ForceControlResult r = solve_for_force(target, 0.0, settings(1e-6 * target, e_star), force);
  REQUIRE(r.converged());
  CHECK(std::abs(r.force - target) <= 1e-6 * target);
  CHECK(-1.0 - r.offset == Approx(approach(target)).epsilon(1e-6));
  CHECK(r.iterations <= 20);  // 8 searching down, 7 in contact (measured: 15)
}

TEST_CASE("force control: loads nothing carries and failing solves stop with a message", "[driver][force]") {
  // A strip that gives way: the force saturates below the load.
  auto collapsing = [](Real w) -> std::optional<Real> { return 900.0 * std::tanh(std::max(-w, 0.0)); };
  const ForceControlResult c = solve_for_force(1000.0, 0.0, settings(1e-6, 1e3), collapsing);
  CHECK_FALSE(c.converged());
  CHECK_THAT(c.message, Contains("nothing carries the load"));
  CHECK(std::isfinite(c.offset));
  // A pull: contact only pushes.
  auto contact = [](Real w) -> std::optional<Real> { return 1e3 * std::max(-w, 0.0); };
  const ForceControlResult pull = solve_for_force(-10.0, 0.0, settings(1e-6, 1e3), contact);
  CHECK_FALSE(pull.converged());
  CHECK_THAT(pull.message, Contains("nothing carries the load"));
  // Zero load with the roller off the strip: already there.
  const ForceControlResult zero = solve_for_force(0.0, 0.5, settings(1e-6, 1e3), contact);
  CHECK(zero.converged());
  CHECK(zero.iterations == 1);
  // A solve that fails is reported, with where.
  auto failing = [](Real) -> std::optional<Real> { return std::nullopt; };
  const ForceControlResult f = solve_for_force(10.0, 0.25, settings(1e-6, 1e3), failing);
  CHECK_FALSE(f.converged());
  CHECK_THAT(f.message, Contains("contact solve failed") && Contains("0.25 mm"));
}

TEST_CASE("force control: a horizontal force of either sign is met on a frictional law, beyond it the roller slides",
          "[driver][force]") {
  // Cattaneo-like: the strip's horizontal force on the roller falls from 0 as the centre moves on
  // (w > 0) and saturates at -mu P in gross sliding, symmetrically backwards.
  const Real mu_p = 900.0, k = 2e5;
  auto friction = [&](Real w) -> std::optional<Real> { return -mu_p * std::tanh(k * w / mu_p); };
  for (const Real target : {-450.0, 450.0, -850.0}) {
    ForceControlSettings s = settings(1e-6 * mu_p, k);
    s.axis = ForceAxis::Horizontal;
    const ForceControlResult r = solve_for_force(target, 0.0, s, friction);
    REQUIRE(r.converged());
    CHECK(std::abs(r.force - target) <= 1e-6 * mu_p);
    CHECK(r.offset == Approx(-mu_p / k * std::atanh(target / mu_p)).epsilon(1e-5));
  }
  ForceControlSettings s = settings(1e-6 * mu_p, k);
  s.axis = ForceAxis::Horizontal;
  const ForceControlResult slide = solve_for_force(-1000.0, 0.0, s, friction);
  CHECK_FALSE(slide.converged());
  CHECK_THAT(slide.message, Contains("the roller slides") && Contains("dx"));
  CHECK(std::isfinite(slide.offset));
}

TEST_CASE(
    "force control: a force that jumps across the target by less than the jump tolerance is met at the "
    "bracket's better end, a larger jump stops with a message",
    "[driver][force]") {
  // F = k (d - w) + a step of `jump` at w = w_jump: the law a stick-slip flip makes, where no w
  // meets the target within force_tolerance. The target lies inside the step, nearer its top.
  const Real k = 2e5, d = 0.3, w_jump = 0.25;
  Real jump = 0.0;
  Real last_w = 0.0;
  auto force = [&](Real w) -> std::optional<Real> {
    last_w = w;
    return k * (d - w) + (w < w_jump ? jump : 0.0);
  };
  const Real top = k * (d - w_jump) + 0.0;  // F just above w_jump; below it F = top + jump
  ForceControlSettings s = settings(1e-6, k);
  s.jump_tolerance = 1e-3;
  SECTION("within the tolerance") {
    jump = 1e-3;
    const Real target = top + 0.3e-3;
    const ForceControlResult r = solve_for_force(target, 0.0, s, force);
    REQUIRE(r.converged());
    CHECK(r.offset == Approx(w_jump).margin(1e-12));
    CHECK(std::abs(r.force - target) == Approx(0.3e-3).epsilon(1e-3));
    CHECK(last_w == r.offset);  // the increment keeps the last solve: it is the one returned
  }
  SECTION("beyond it") {
    jump = 1e-2;
    const ForceControlResult r = solve_for_force(top + 4e-3, 0.0, s, force);
    REQUIRE_FALSE(r.converged());
    CHECK_THAT(r.message, Contains("jumps across the prescribed"));
  }
}
