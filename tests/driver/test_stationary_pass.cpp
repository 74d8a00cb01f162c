// The stationary pass (driver/stationary_pass.hpp): an elastic strip's solution is the elastic
// one; an unloaded strip keeps its upstream state; the pass of a shakedown scene converges.
#include <catch2/catch.hpp>

#include <chrono>
#include <iostream>

#include <fmt/format.h>

#include "roller/analysis/hertz.hpp"
#include "roller/driver/simulation.hpp"
#include "roller/driver/stationary_pass.hpp"
#include "roller/io/scene_loader.hpp"

using namespace roller;

namespace {

ElementMaterials elastic_copy(ElementMaterials m) {
  for (MaterialParams& p : m.table) p.plastic = false;
  return m;
}

struct Setup {
  Simulation sim;
  StationaryStrip strip;
  StripModel twin;
  SparseSolver solver{MumpsSolver::Symmetry::Symmetric};
  VecX load;
  explicit Setup(const std::string& scene, Real x_centre, Real load_p)
      : sim(load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/" + scene + ".toml")),
        strip(sim.model().mesh(), sim.model().materials(), sim.model().options(), 1.0),
        twin(sim.model().mesh(), elastic_copy(sim.model().materials()), sim.model().options()) {
    twin.set_dof_map(sim.model().dof_map());
    SparseMatrix k;
    twin.evaluate(VecX::Zero(twin.n_dofs()), nullptr, &k);
    REQUIRE(solver.factorize(k));
    const Mesh& mesh = sim.model().mesh();
    const std::vector<Index>& top = mesh.node_set("top");
    std::vector<Real> x;
    for (const Index a : top) x.push_back(mesh.nodes[a].x() - x_centre);
    const HertzSolution h =
        hertz_line_contact(load_p, sim.scene().roller->radius, sim.model().material(0).plane_strain_modulus());
    const std::vector<Real> f = hertz_nodal_forces(h, x);
    load = VecX::Zero(mesh.n_dofs());
    for (std::size_t i = 0; i < top.size(); ++i) load[2 * top[i] + 1] = -f[i];
  }
};

}  // namespace

TEST_CASE("stationary pass of shakedown_p45 (explore)", "[.explore]") {
  Setup s("shakedown_p45", 100.0, 7249.8292);
  StationarySettings settings;
  settings.progress = &std::cout;
  const auto t0 = std::chrono::steady_clock::now();
  const StationaryPassResult r =
      solve_stationary_pass(s.strip, s.sim.model().dof_map(), s.solver, s.load, s.strip.virgin_upstream(), settings);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << fmt::format("status {} after {} iterations, |r|/F {:.3g}, {:.2f} s\n", enum_name(r.status),
                           r.iterations, r.residual, wall);
  // Plastic strain leaving the strip downstream, by depth.
  const Real top = 100.0;
  for (const Streamline& line : s.strip.streamlines())
    if (top - line.y < 6.0)
      std::cout << fmt::format("depth {:.3f}: eps_p {:.4e}  stress xx {:.1f} zz {:.1f}\n", top - line.y,
                               r.states[line.points.back()].eq_plastic_strain, r.states[line.points.back()].stress[0],
                               r.states[line.points.back()].stress[2]);
}
