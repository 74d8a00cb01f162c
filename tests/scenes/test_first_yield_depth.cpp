// A yield stress that falls with depth (a case-hardened surface) moves first yield below the
// case: to the depth where the elastic stress first meets the local yield stress
// (docs/validation.md, "Layered strips: first yield under a hardened case").
//
// An elastic press gives sigma_vm at every integration point; with sigma_y(z) the profile at
// the point's element centroid, the load factor of first yield is lambda* = min sigma_y/sigma_vm
// and its depth z* that point's. For a linear elastic strip a load factor lambda is the yield
// stresses divided by lambda at the same load; the roller's contact widens with the load, so the
// factor is applied that way: plastic presses with sigma_y(z)/(1.02 lambda*) yield, at z*, and
// with sigma_y(z)/(0.98 lambda*) stay elastic.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "roller/assembly/element_materials.hpp"
#include "roller/driver/simulation.hpp"
#include "roller/io/scene_loader.hpp"
#include "roller/material/j2_plasticity.hpp"

using namespace roller;

namespace {

// The case of problems/case_hardened.toml: 1600 MPa at the surface, 800 MPa in the core.
const std::vector<std::pair<Real, Real>> kProfile{
    {0.0, 1600.0}, {0.5, 1550.0}, {1.0, 1200.0}, {1.5, 850.0}, {2.0, 800.0}};
constexpr Real kRow = 0.1;  // mm: the rows of the mesh below

// A 50 mm roller pressed 0.03 mm into a 6 x 4 mm strip in one step, frictionless (Hertz
// a ~ 1.2 mm); `material` the [material] table's extra lines.
std::string press_scene(const std::string& material) {
  return fmt::format(R"(
name = "first_yield"
kinematics = "small"
[mesh]
element = "Q4"
length = 6.0
height = 4.0
nx = 60
ny = 40
q4_formulation = "bbar"
[material]
E = 2.1e5
nu = 0.3
{}
[steps]
count = 1
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
steps = [1, 1]
dy = -0.03
[contact]
friction = 0.0
)",
                     material);
}

std::string profile_text(Real factor) {
  std::string rows;
  for (const auto& [z, s] : kProfile)
    rows += fmt::format("{}[{:.17g}, {:.17g}]", rows.empty() ? "" : ", ", z, s / factor);
  return fmt::format("yield_stress = {:.17g}\ntangent_modulus = 0.0\nyield_profile = [{}]",
                     kProfile.back().second / factor, rows);
}

Simulation press(const std::string& material) {
  Simulation sim(parse_scene(press_scene(material), "first_yield.toml"));
  REQUIRE(sim.advance_step(1).converged());
  return sim;
}

struct Prediction {
  Real lambda = 0.0;          // smallest sigma_y / sigma_vm
  Real depth = 0.0;           // of its element's centroid
  Real lambda_surface = 0.0;  // the same over the top row of elements
};

Prediction predict(const StripModel& elastic) {
  YieldProfile profile{kProfile};
  const Mesh& mesh = elastic.mesh();
  const Real top = mesh_top(mesh);
  Prediction p{1e300, 0.0, 1e300};
  for (Index e = 0; e < mesh.n_elements(); ++e) {
    const Real z = centroid_depth(mesh, e, top);
    for (int q = 0; q < elastic.points_per_element(); ++q) {
      const Real ratio = profile.at(z) / von_mises(elastic.state(e, q).stress);
      if (ratio < p.lambda) p = {ratio, z, p.lambda_surface};
      if (z < kRow) p.lambda_surface = std::min(p.lambda_surface, ratio);
    }
  }
  return p;
}

}  // namespace

TEST_CASE("a yield stress falling with depth: first yield where the elastic stress meets it, below the case",
          "[scenes][layers]") {
  const Simulation elastic = press("");
  const Prediction p = predict(elastic.model());
  // A homogeneous strip yields first where sigma_vm peaks (about 0.7 a).
  Real peak_depth = 0.0, peak = 0.0;
  const Mesh& mesh = elastic.model().mesh();
  for (Index e = 0; e < mesh.n_elements(); ++e)
    for (int q = 0; q < elastic.model().points_per_element(); ++q)
      if (const Real vm = von_mises(elastic.model().state(e, q).stress); vm > peak) {
        peak = vm;
        peak_depth = centroid_depth(mesh, e, mesh_top(mesh));
      }
  std::cout << fmt::format(
      "first yield: lambda* = {:.4f} at depth {:.3f} mm (surface row: {:.4f}); peak von Mises {:.1f} MPa at "
      "{:.3f} mm\n",
      p.lambda, p.depth, p.lambda_surface, peak, peak_depth);
  REQUIRE(p.depth > 2 * kRow);         // the prediction itself lies below the surface...
  CHECK(p.depth > peak_depth + kRow);  // ...and below where a homogeneous strip yields
  CHECK(p.lambda_surface > 1.1 * p.lambda);

  SECTION("just above lambda*: yields at z*, within a row, and not at the surface") {
    const Simulation plastic = press(profile_text(1.02 * p.lambda));
    const StripModel& m = plastic.model();
    Real worst = 0.0, worst_depth = 0.0, shallowest = 1e300;
    for (Index e = 0; e < mesh.n_elements(); ++e)
      for (int q = 0; q < m.points_per_element(); ++q) {
        const Real eps = m.state(e, q).eq_plastic_strain;
        if (eps <= 0.0) continue;
        const Real z = centroid_depth(mesh, e, mesh_top(mesh));
        shallowest = std::min(shallowest, z);
        if (eps > worst) {
          worst = eps;
          worst_depth = z;
        }
      }
    std::cout << fmt::format(
        "at 1.02 lambda*: largest plastic strain {:.3g} at depth {:.3f} mm, shallowest yield {:.3f} mm\n", worst,
        worst_depth, shallowest);
    REQUIRE(worst > 0.0);
    CHECK(std::abs(worst_depth - p.depth) <= kRow * 1.0001);
    CHECK(shallowest > kRow);  // nothing in the top row of elements
  }
  SECTION("just below lambda*: no point yields") {
    const Simulation plastic = press(profile_text(0.98 * p.lambda));
    Real eps = 0.0;
    for (const MaterialState& s : plastic.model().states()) eps = std::max(eps, s.eq_plastic_strain);
    CHECK(eps == 0.0);
  }
}
