// Carter's traction (analysis/carter.hpp) against the closed forms it is built from:
// c/a = sqrt(1 - Q/(mu P)), the creep law s = (mu a / R)(1 - c/a) of an uncoupled elastic strip,
// Coulomb's bound, the slip zone's q = mu p, the stick zone at the leading edge, and
// work-equivalent nodal forces that sum to Q.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "roller/analysis/carter.hpp"
#include "roller/core/error.hpp"

using namespace roller;

namespace {

const HertzSolution kHertz = hertz_line_contact(7249.8, 100.0, 2.1e5 / (1.0 - 0.09));
constexpr Real kRadius = 100.0, kFriction = 0.2;

// Q/P whose stick zone is the fraction `c_over_a` of the contact.
Real ratio_for(Real c_over_a) { return kFriction * (1.0 - c_over_a * c_over_a); }

}  // namespace

TEST_CASE("Carter: the stick zone's width, the creep and the traction's resultant", "[carter]") {
  const Real a = kHertz.half_width;
  for (const Real c_over_a : {0.1, 0.5, 0.9}) {
    const CarterTraction t = carter_traction(kHertz, ratio_for(c_over_a), kFriction);
    CHECK(t.stick_half_width == Approx(c_over_a * a).epsilon(1e-12));
    CHECK(t.stick_centre() == Approx(a - c_over_a * a).epsilon(1e-12));
    CHECK(t.elastic_creep(kRadius) == Approx(kFriction * a / kRadius * (1.0 - c_over_a)).epsilon(1e-12));
    // Q from the nodal forces on a fine, irregular chain straddling the contact: mu P (1 - c^2/a^2).
    std::vector<Real> x{-1.3 * a};
    for (Real step = 0.004 * a; x.back() < 1.2 * a; step *= 1.002) x.push_back(x.back() + step);
    Real q = 0.0;
    for (const Real f : carter_nodal_forces(t, x)) q += f;
    CHECK(q == Approx(ratio_for(c_over_a) * kHertz.load).epsilon(1e-9));
  }
}

TEST_CASE("Carter: q = mu p where the contact slips, below it where it sticks, never above", "[carter]") {
  const Real a = kHertz.half_width;
  const CarterTraction t = carter_traction(kHertz, ratio_for(0.5), kFriction);
  for (int i = -99; i <= 99; ++i) {
    const Real x = a * i / 100.0;
    const Real mu_p = kFriction * kHertz.pressure(x);
    INFO("x/a = " << x / a);
    CHECK(t.traction(x) >= 0.0);
    CHECK(t.traction(x) <= mu_p * (1.0 + 1e-14));
    if (x < 0.0) {  // the trailing half slips (the stick zone is [0, a] here)
      CHECK_FALSE(t.sticks(x));
      CHECK(t.traction(x) == Approx(mu_p).epsilon(1e-14));
    } else if (x > 0.01 * a && x < 0.99 * a) {
      CHECK(t.sticks(x));
      CHECK(t.traction(x) < mu_p);
    }
  }
  // Continuous where the stick zone begins.
  CHECK(t.traction(1e-9 * a) == Approx(kFriction * kHertz.pressure(0.0)).epsilon(1e-4));
  // The stick zone's traction is Carter's difference of two semi-ellipses.
  const Real x = 0.7 * a;
  const Real relief = 0.5 * kHertz.peak * std::sqrt(1.0 - std::pow((x - 0.5 * a) / (0.5 * a), 2));
  CHECK(t.traction(x) == Approx(kFriction * (kHertz.pressure(x) - relief)).epsilon(1e-12));
}

TEST_CASE("Carter: no force carries nothing, Q = mu P slides, a negative Q pulls back, beyond mu P is an error",
          "[carter]") {
  const Real a = kHertz.half_width;
  const CarterTraction free = carter_traction(kHertz, 0.0, 0.0);
  CHECK(free.stick_half_width == a);
  CHECK(free.traction(0.3 * a) == 0.0);
  CHECK(free.elastic_creep(kRadius) == 0.0);
  const CarterTraction sliding = carter_traction(kHertz, kFriction, kFriction);
  CHECK(sliding.stick_half_width == 0.0);
  CHECK(sliding.traction(0.3 * a) == Approx(kFriction * kHertz.pressure(0.3 * a)).epsilon(1e-14));
  const CarterTraction back = carter_traction(kHertz, -ratio_for(0.5), kFriction);
  CHECK(back.traction(0.7 * a) == Approx(-carter_traction(kHertz, ratio_for(0.5), kFriction).traction(0.7 * a)));
  CHECK(back.elastic_creep(kRadius) < 0.0);
  CHECK_THROWS_AS(carter_traction(kHertz, 0.201, kFriction), InputError);
  CHECK_THROWS_AS(carter_traction(kHertz, std::nan(""), kFriction), InputError);
}
