// Two strip layers whose stiffnesses differ by 1e6 (docs/stability.md, cases layers and
// layers_soft): Z1 (finite strain, friction, rolling with slip) with its top row of elements one
// material and the rest another. Both backends converge, or the penalty backend stops with a
// message whose fix works, and their roller forces agree within what the penalty's penetration
// explains.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "roller/driver/simulation.hpp"
#include "roller/io/scene_loader.hpp"

using namespace roller;

namespace {

// Z1's top row of elements (20 mm / 3 rows) as the layer.
const Real kTopRow = 20.0 / 3.0;

// `[[layer]]` of Z1's top row with the given material keys.
SceneOverride top_row_layer(const std::string& material) {
  return {"layer", fmt::format("[{{thickness={:.17g}, {}}}]", kTopRow, material)};
}

struct Run {
  std::vector<Vec2> forces;  // the roller's, per step
  Real max_penetration = 0.0;
  Simulation::StepRecord last;  // the last step tried
};

Run run_z1(const std::vector<SceneOverride>& overrides) {
  Simulation sim(load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/z1_outf05.toml", overrides));
  Run run;
  for (int step = 1; step <= sim.scene().total_steps(); ++step) {
    run.last = sim.advance_step(step);
    if (!run.last.converged()) break;
    run.forces.push_back(force_on_roller(sim.state().contact));
    run.max_penetration = std::max(run.max_penetration, run.last.max_penetration);
  }
  return run;
}

// Z1 presses its roller 0.6 mm and rolls it along a harmonic path of amplitude 0.1 mm: the
// indentation stays above 0.5 mm. The penalty backend's roller stands its penetration less deep,
// and a cylinder's force grows at most as the indentation to the power 1.5 (a thin bonded layer's
// P ~ g^1.5; Hertz's is slower), so its force may be lower by up to 1.5 * penetration / 0.5 mm.
void check_agreement(const Run& ipopt, const Run& penalty) {
  REQUIRE(ipopt.forces.size() == 13);
  REQUIRE(penalty.forces.size() == 13);
  CHECK(ipopt.max_penetration == 0.0);
  REQUIRE(penalty.max_penetration > 0.0);
  const Real bound = 1.5 * penalty.max_penetration / 0.5;
  for (std::size_t k = 0; k < ipopt.forces.size(); ++k) {
    const Vec2 a = ipopt.forces[k], b = penalty.forces[k];
    const Real fy_gap = std::abs(b.y() - a.y()) / std::abs(a.y());
    const Real fx_gap = std::abs(b.x() - a.x()) / std::abs(a.y());
    std::cout << fmt::format("step {:2}: Fy ipopt {:.5g}, penalty {:.5g} ({:+.2e}); Fx gap / Fy {:.2e}\n", k + 1, a.y(),
                             b.y(), (b.y() - a.y()) / a.y(), fx_gap);
    CHECK(a.y() > 0.0);
    CHECK(fy_gap <= bound);
    CHECK(fx_gap <= bound);
  }
}

}  // namespace

TEST_CASE("layered strips: a stiffness ratio of 1e6 between two layers converges on both backends and they agree",
          "[scenes][layers][slow]") {
  SECTION("a soft top layer (E = 0.21 MPa) over steel") {
    const std::vector<SceneOverride> soft = {top_row_layer("E=0.21, kappa=0.07")};
    std::vector<SceneOverride> penalty = soft;
    penalty.push_back({"contact.backend", "\"penalty\""});
    const Run ipopt = run_z1(soft);
    check_agreement(ipopt, run_z1(penalty));
    // The layer carries the roller: pressed g = 0.6 mm (step 3) into a layer of thickness h on a
    // substrate 1e6 stiffer, a thin layer is a bed of springs of the constrained modulus E' =
    // E (1 - nu) / ((1 + nu)(1 - 2 nu)) over h: P = 4/3 E' g sqrt(2 R g) / h. Its error grows as
    // (h/a)^2 (here h/a = 0.35, and the layer strains 9 %); a steel strip would carry 1e6 times more.
    const Real E = 0.21, nu = 0.3, R = 300.0, g = 0.6, h = kTopRow;
    const Real thin_layer = 4.0 / 3.0 * E * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) * g * std::sqrt(2 * R * g) / h;
    std::cout << fmt::format("pressed 0.6 mm: Fy {:.4g}, thin-layer estimate {:.4g}\n", ipopt.forces[2].y(),
                             thin_layer);
    CHECK(ipopt.forces[2].y() == Approx(thin_layer).epsilon(0.1));
  }
  SECTION("a steel top layer over a core of E = 0.21 MPa") {
    const std::vector<SceneOverride> stiff = {{"material.E", "0.21"}, top_row_layer("E=2.1e5, kappa=0.07")};
    const Run ipopt = run_z1(stiff);
    // The penalty factor is scaled by the surface's E*, the steel's, where the contact's
    // stiffness is the soft core's: at the default factor the penalty Newton cannot settle the
    // plate on its core, and the message names the fixes.
    std::vector<SceneOverride> penalty = stiff;
    penalty.push_back({"contact.backend", "\"penalty\""});
    const Run stopped = run_z1(penalty);
    REQUIRE_FALSE(stopped.last.converged());
    CHECK(stopped.last.step == 4);
    CHECK_THAT(stopped.last.message,
               Catch::Contains("a smaller contact.penalty.factor") && Catch::Contains("the ipopt backend"));
    // The remedy that works: a factor scaled towards the core (0.01 of the steel's E* is 1e4 of the core's).
    penalty.push_back({"contact.penalty.factor", "0.01"});
    check_agreement(ipopt, run_z1(penalty));
  }
}
