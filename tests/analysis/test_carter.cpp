// Carter's traction (analysis/carter.hpp) against the closed forms it is built from: the creep law
// s = (mu a / R)(1 - c/a), Q = mu P (1 - c^2/a^2), Coulomb's bound, the slip zone's q = mu p, the
// stick zone at the leading edge, and work-equivalent nodal forces that sum to Q.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "roller/analysis/carter.hpp"
#include "roller/core/error.hpp"

using namespace roller;

namespace {

const HertzSolution kHertz = hertz_line_contact(7249.8, 100.0, 2.1e5 / (1.0 - 0.09));
constexpr Real kRadius = 100.0, kFriction = 0.2;

// The creep whose stick zone is the fraction `c_over_a` of the contact: s = (mu a / R)(1 - c/a).
Real creep_for(Real c_over_a) { return kFriction * kHertz.half_width / kRadius * (1.0 - c_over_a); }

}  // namespace

TEST_CASE("Carter: the stick zone's width and the traction's resultant follow the creep law", "[carter]") {
  const Real a = kHertz.half_width;
  for (const Real c_over_a : {0.1, 0.5, 0.9}) {
    const CarterTraction t = carter_traction(kHertz, creep_for(c_over_a), kRadius, kFriction);
    CHECK(t.stick_half_width == Approx(c_over_a * a).epsilon(1e-12));
    CHECK(t.stick_centre() == Approx(a - c_over_a * a).epsilon(1e-12));
    CHECK(t.ratio() == Approx(1.0 - c_over_a * c_over_a).epsilon(1e-12));
    // Q from the nodal forces on a fine, irregular chain straddling the contact: mu P (1 - c^2/a^2).
    std::vector<Real> x{-1.3 * a};
    for (Real step = 0.004 * a; x.back() < 1.2 * a; step *= 1.002) x.push_back(x.back() + step);
    Real q = 0.0;
    for (const Real f : carter_nodal_forces(t, x)) q += f;
    CHECK(q == Approx(kFriction * kHertz.load * (1.0 - c_over_a * c_over_a)).epsilon(1e-9));
  }
}

TEST_CASE("Carter: q = mu p where the contact slips, below it where it sticks, never above", "[carter]") {
  const Real a = kHertz.half_width;
  const CarterTraction t = carter_traction(kHertz, creep_for(0.5), kRadius, kFriction);
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
  // Continuous where the stick zone begins; at the leading edge both vanish.
  CHECK(t.traction(1e-9 * a) == Approx(kFriction * kHertz.pressure(0.0)).epsilon(1e-4));
  // The stick zone's traction is Carter's difference of two semi-ellipses.
  const Real x = 0.7 * a;
  CHECK(t.traction(x) ==
        Approx(kFriction *
               (kHertz.pressure(x) - 0.5 * kHertz.peak * std::sqrt(1.0 - std::pow((x - 0.5 * a) / (0.5 * a), 2))))
            .epsilon(1e-12));
}

TEST_CASE("Carter: free rolling carries nothing, a creep beyond mu a / R slides, a negative creep pulls back",
          "[carter]") {
  const Real a = kHertz.half_width;
  const CarterTraction free = carter_traction(kHertz, 0.0, kRadius, 0.0);
  CHECK(free.ratio() == 0.0);
  CHECK(free.traction(0.3 * a) == 0.0);
  const CarterTraction sliding = carter_traction(kHertz, creep_for(-0.5), kRadius, kFriction);  // s > mu a / R
  CHECK(sliding.stick_half_width == 0.0);
  CHECK(sliding.ratio() == 1.0);
  CHECK(sliding.traction(0.3 * a) == Approx(kFriction * kHertz.pressure(0.3 * a)).epsilon(1e-14));
  const CarterTraction back = carter_traction(kHertz, -creep_for(0.5), kRadius, kFriction);
  CHECK(back.ratio() == Approx(-0.75).epsilon(1e-12));
  CHECK(back.traction(0.7 * a) ==
        Approx(-carter_traction(kHertz, creep_for(0.5), kRadius, kFriction).traction(0.7 * a)));
  CHECK_THROWS_AS(carter_traction(kHertz, 0.001, kRadius, 0.0), InputError);
  CHECK_THROWS_AS(carter_traction(kHertz, std::nan(""), kRadius, kFriction), InputError);
}
