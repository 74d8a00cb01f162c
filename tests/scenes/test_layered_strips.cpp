// Layered strips and yield profiles against what they must reproduce (docs/validation.md,
// "Layered strips"): bands of one material are the homogeneous strip to round-off, and a yield
// stress falling with depth moves first yield to the depth an elastic run predicts.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

#include <fmt/format.h>

#include "roller/assembly/element_materials.hpp"
#include "roller/driver/simulation.hpp"
#include "roller/io/scene_loader.hpp"
#include "roller/material/j2_plasticity.hpp"

using namespace roller;

namespace {

// A 50 mm roller pressed 0.02 mm into an 8 x 4 mm steel strip (Hertz a ~ 1 mm, p0 ~ 2.3 GPa),
// then rolled 0.6 mm with friction 0.1: plastic from the first step at sigma_y = 800 MPa.
std::string rolling_scene(const std::string& material_extra, const std::string& layers,
                          const std::string& mesh_extra = "") {
  return fmt::format(R"(
name = "layers"
kinematics = "small"
[mesh]
element = "Q4"
length = 8.0
height = 4.0
nx = 32
ny = 16
{}
[material]
E = 2.1e5
nu = 0.3
yield_stress = 800.0
tangent_modulus = 2100.0
{}
{}
[steps]
count = 5
[output]
monitor = false
[[displacement]]
nodes = "bottom"
x = 0.0
y = 0.0
[roller]
radius = 50.0
centre = [3.0, 54.0]
[[roller.path]]
steps = [1, 2]
dy = -0.02
friction = 0.0
[[roller.path]]
steps = [3, 5]
dx = 0.6
[contact]
friction = 0.1
)",
                     mesh_extra, material_extra, layers);
}

Simulation run(const std::string& text) {
  Simulation sim(parse_scene(text, "layers.toml"));
  for (int step = 1; step <= sim.scene().total_steps(); ++step) REQUIRE(sim.advance_step(step).converged());
  return sim;
}

// max |a - b| over displacements, stresses and plastic strains, each relative to b's largest.
struct Difference {
  Real displacement = 0.0, stress = 0.0, plastic_strain = 0.0;
};

Difference difference(const StripModel& a, const StripModel& b) {
  Difference d;
  d.displacement = (a.total_displacement() - b.total_displacement()).cwiseAbs().maxCoeff() /
                   b.total_displacement().cwiseAbs().maxCoeff();
  Real s_max = 0.0, e_max = 0.0;
  for (std::size_t k = 0; k < b.states().size(); ++k) {
    s_max = std::max(s_max, b.states()[k].stress.cwiseAbs().maxCoeff());
    e_max = std::max(e_max, b.states()[k].eq_plastic_strain);
    d.stress = std::max(d.stress, (a.states()[k].stress - b.states()[k].stress).cwiseAbs().maxCoeff());
    d.plastic_strain =
        std::max(d.plastic_strain, std::abs(a.states()[k].eq_plastic_strain - b.states()[k].eq_plastic_strain));
  }
  d.stress /= s_max;
  d.plastic_strain /= e_max;
  std::cout << fmt::format("relative differences: displacement {:.3g}, stress {:.3g}, plastic strain {:.3g}\n",
                           d.displacement, d.stress, d.plastic_strain);
  return d;
}

}  // namespace

TEST_CASE("layered strips: bands of the strip's own material give the homogeneous strip's answers",
          "[scenes][layers]") {
  const Simulation homogeneous = run(rolling_scene("", ""));
  const StripModel& h = homogeneous.model();
  Real eps_max = 0.0;
  for (const MaterialState& s : h.states()) eps_max = std::max(eps_max, s.eq_plastic_strain);
  std::cout << fmt::format("homogeneous strip: largest equivalent plastic strain {:.3g}\n", eps_max);
  REQUIRE(eps_max > 1e-4);  // the comparison covers plastic flow

  SECTION("two [[layer]] blocks that repeat nothing of [material]") {
    const Simulation layered = run(rolling_scene("", "[[layer]]\nthickness = 0.6\n[[layer]]\nthickness = 1.1\n"));
    CHECK(layered.model().materials().table.size() == 3);
    const Difference d = difference(layered.model(), h);
    CHECK(d.displacement <= 1e-12);
    CHECK(d.stress <= 1e-12);
    CHECK(d.plastic_strain <= 1e-12);
  }
  SECTION("two layers that give [material]'s values again, on grid lines (follow_layers)") {
    // Boundaries at depths 0.5 and 1.5 mm lie on grid lines (rows of 0.25 mm): the mesh is the same.
    const Simulation layered =
        run(rolling_scene("",
                          "[[layer]]\nthickness = 0.5\nE = 2.1e5\nyield_stress = 800.0\n[[layer]]\nthickness = "
                          "1.0\nnu = 0.3\n",
                          "follow_layers = true"));
    REQUIRE(layered.model().mesh().nodes == h.mesh().nodes);
    const Difference d = difference(layered.model(), h);
    CHECK(d.displacement <= 1e-12);
    CHECK(d.stress <= 1e-12);
    CHECK(d.plastic_strain <= 1e-12);
  }
  SECTION("a constant yield profile equal to yield_stress") {
    const Simulation profiled = run(rolling_scene("yield_profile = [[0.0, 800.0], [2.0, 800.0]]", ""));
    const Difference d = difference(profiled.model(), h);
    CHECK(d.displacement <= 1e-12);
    CHECK(d.stress <= 1e-12);
    CHECK(d.plastic_strain <= 1e-12);
  }
}
