// The thesis's contact strategy (4.25) as a predictor (docs/model.md, Arc predictor): geometry of
// the arc rule, and the same converged answer as the default predictor (it only moves the
// solver's starting point).
#include <catch2/catch.hpp>

#include <cmath>

#include "../support/run_scene.hpp"
#include "roller/contact/arc_predictor.hpp"

using namespace roller;

TEST_CASE("arc predictor: entering nodes land on the circle after the arc R dphi W_IN/(W_FR+W_IN)", "[contact][arc]") {
  const Vec2 centre(0.0, 10.0);
  const Real radius = 10.0, dphi = 0.05;
  // Outside at the end: unchanged.
  CHECK(arc_predicted_position(Vec2(5, -1), Vec2(5, -0.5), centre, radius, dphi) == Vec2(5, -0.5));
  // From outside (below the circle) straight up into it: enters at C = (2, 10 - sqrt(96)).
  const Vec2 start(2.0, -1.0), end(2.0, 1.0);
  const Vec2 c(2.0, 10.0 - std::sqrt(96.0));
  const Real w_fr = c.y() - start.y(), w_in = end.y() - c.y();
  const Vec2 c1 = arc_predicted_position(start, end, centre, radius, dphi);
  CHECK((c1 - centre).norm() == Approx(radius).epsilon(1e-14));
  const Real arc =
      radius * (std::atan2((c1 - centre).y(), (c1 - centre).x()) - std::atan2((c - centre).y(), (c - centre).x()));
  CHECK(arc == Approx(radius * dphi * w_in / (w_fr + w_in)).epsilon(1e-12));
  // Already inside at the start: from the radial projection, the whole rotation.
  const Vec2 in0(0.0, 0.5), in1(0.0, 0.6);
  const Vec2 r = arc_predicted_position(in0, in1, centre, radius, dphi);
  CHECK((r - centre).norm() == Approx(radius).epsilon(1e-14));
  CHECK(std::atan2((r - centre).y(), (r - centre).x()) == Approx(-M_PI / 2 + dphi).epsilon(1e-12));
}

// The predictor changes where each increment's solver starts, and one thing more: the tangent
// t_i of a candidate is taken at its predicted position and held fixed in the increment
// (increment_problem.hpp), so the friction direction differs by the angle between the two
// predicted positions seen from the roller centre, O(|dc|/R) = 0.013 rad per Z1 step: a friction
// force mu F ~ 0.15 F turned by that moves F by ~2e-3 F at most. Both backends show the same
// shift (measured up to 7e-4 F on Z1, 0 on Z2 before the first cut). As long as neither run cuts a
// step (a cut changes the friction history, hence the problem), the states agree within 1e-3 F.
TEST_CASE("arc predictor: Z2 and Z1 reach the same states as the default predictor", "[contact][arc][slow]") {
  for (const char* backend : {"penalty", "ipopt"}) {
    for (const char* scene : {"z2_large", "z1_outf05"}) {
      INFO(backend << " " << scene);
      auto load = [&](const char* predictor) {
        return Simulation(load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/" + scene + ".toml",
                                     {{"contact.backend", std::string("\"") + backend + "\""},
                                      {"contact.predictor", std::string("\"") + predictor + "\""}}));
      };
      Simulation arc = load("arc");
      Simulation plain = load("extrapolate");
      int compared = 0;
      for (int step = 1; step <= plain.scene().steps.n_steps; ++step) {
        INFO("step " << step);
        const auto a = arc.advance_step(step);
        const auto b = plain.advance_step(step);
        REQUIRE(a.converged());
        REQUIRE(b.converged());
        if (a.cuts > 0 || b.cuts > 0) break;
        CHECK((force_on_roller(arc.state().contact) - force_on_roller(plain.state().contact)).norm() <=
              1e-3 * force_on_roller(plain.state().contact).norm());
        ++compared;
      }
      CHECK(compared >= 3);
    }
  }
}
