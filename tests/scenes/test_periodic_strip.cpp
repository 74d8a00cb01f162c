// A periodic strip ([mesh] periodic, docs/model.md, Periodic strip): the right edge is the left
// edge. On a uniform mesh a shift by whole elements is an exact symmetry, so a roller rolling over
// the seam carries the same force at every node it stands on; the strip with two free ends does not.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "roller/assembly/dof_map.hpp"
#include "roller/core/error.hpp"
#include "roller/driver/simulation.hpp"
#include "roller/io/scene_loader.hpp"
#include "roller/mesh/strip_mesher.hpp"

using namespace roller;

namespace {

const std::string kScene = std::string(ROLLER_SOURCE_DIR) + "/problems/periodic_rolling.toml";

// The vertical force on the roller at the end of each step (steps 1..26).
std::vector<Real> roller_forces(const std::vector<SceneOverride>& overrides) {
  Simulation sim(load_scene(kScene, overrides));
  std::vector<Real> fy;
  for (int step = 1; step <= sim.scene().total_steps(); ++step) {
    const Simulation::StepRecord r = sim.advance_step(step);
    REQUIRE(r.converged());
    REQUIRE(r.roller);
    fy.push_back(r.roller->force.y());
  }
  return fy;
}

}  // namespace

TEST_CASE("periodic strip: the right edge is the left edge, its dofs the left edge's", "[periodic]") {
  Scene scene = load_scene(kScene);
  const Mesh mesh = make_strip_mesh(scene.strip_mesh_spec());
  REQUIRE(mesh.period == 40.0);
  const std::vector<Index> masters = node_masters(mesh);
  const std::vector<Index>& left = mesh.node_set("left");
  const std::vector<Index>& right = mesh.node_set("right");
  for (std::size_t k = 0; k < right.size(); ++k) {
    CHECK(masters[right[k]] == left[k]);
    CHECK(mesh.nodes[right[k]].y() == mesh.nodes[left[k]].y());
    CHECK(mesh.nodes[right[k]].x() == mesh.nodes[left[k]].x() + 40.0);
  }
  CHECK(nearest_image_x(mesh, 1.0, 39.0) == 41.0);
  CHECK(nearest_image_x(mesh, 39.0, 1.0) == -1.0);
  CHECK(nearest_image_x(mesh, 12.0, 20.0) == 12.0);

  // The dofs: the right edge's share its master's free index; forces add, displacements copy.
  const DofMap dofs(std::vector<bool>(mesh.n_dofs(), false), masters);
  CHECK(dofs.has_masters());
  CHECK(dofs.n_free() == mesh.n_dofs() - 2 * static_cast<Index>(right.size()));
  VecX force = VecX::Zero(mesh.n_dofs());
  force(2 * left[3]) = 1.5;
  force(2 * right[3]) = 2.0;
  const VecX gathered = dofs.gather_free(force);
  CHECK(gathered(dofs.free_index(2 * left[3])) == 3.5);
  CHECK(gathered.sum() == 3.5);
  VecX u = VecX::Zero(mesh.n_dofs());
  dofs.scatter_free(VecX::Constant(dofs.n_free(), 0.25), u);
  CHECK(u(2 * right[3] + 1) == 0.25);
}

TEST_CASE("periodic strip: rolling over the seam, the roller carries the same force on every node", "[periodic]") {
  const std::vector<Real> fy = roller_forces({});
  // Steps 10..26: the roller over x = 38..54, past the seam at 40 (the interior-point solutions of
  // the first rolling steps still settle, by 1e-5 of the force, as on any strip).
  REQUIRE(fy[9] > 1000.0);
  for (std::size_t k = 9; k < fy.size(); ++k) CHECK(std::abs(fy[k] - fy[9]) <= 1e-8 * fy[9]);
  // The same strip with two free ends: the roller runs off its end.
  const std::vector<Real> open = roller_forces({{"mesh.periodic", "false"}});
  CHECK(open[12] < 0.9 * fy[12]);
  CHECK(open.back() == 0.0);
}

TEST_CASE("periodic strip: a displacement on the right edge alone is an input error naming the left edge's node",
          "[periodic]") {
  std::ifstream file(kScene);
  std::stringstream text;
  text << file.rdbuf() << "\n[[displacement]]\nnodes = \"right\"\nx = 0.0\n";
  std::string message;
  try {
    Simulation sim(parse_scene(text.str(), kScene, {}));
  } catch (const InputError& e) {
    message = e.what();
  }
  CHECK_THAT(message, Catch::Contains("right edge of a periodic strip"));
  CHECK_THAT(message, Catch::Contains("of the left edge; prescribe x there"));
  // The stationary method needs the strip's two ends.
  message.clear();
  try {
    load_scene(kScene, {{"passes.method", "\"stationary\""}});
  } catch (const InputError& e) {
    message = e.what();
  }
  CHECK_THAT(message, Catch::Contains("mesh.periodic = false"));
}

TEST_CASE("periodic strip: the roller's start sees the strip at its images, past the mesh's ends too", "[periodic]") {
  // Centred 30 mm past the right end, the roller stands over x = 30 of the strip (one period on).
  auto start = [](const char* centre, bool touch) {
    return Simulation(load_scene(kScene, {{"roller.centre", centre}, {"roller.touch_strip", touch ? "true" : "false"}}))
        .state()
        .pose.centre;
  };
  // Touching: the same height as over x = 30 (the top at y = 20, R = 100), not the 115.4 of the
  // nearest node of the mesh as it lies (x = 40).
  CHECK(start("[70.0, 200.0]", true).y() == Approx(start("[30.0, 200.0]", true).y()).epsilon(1e-12));
  CHECK(start("[70.0, 200.0]", true).y() == Approx(120.0).epsilon(1e-12));
  CHECK(start("[-10.0, 200.0]", true).y() == Approx(120.0).epsilon(1e-12));
  // 0.01 mm inside the strip there is an input error, as over x = 30.
  CHECK_THROWS_WITH(start("[70.0, 119.99]", false), Catch::Contains("the roller starts inside the strip"));
  CHECK_THROWS_WITH(start("[30.0, 119.99]", false), Catch::Contains("the roller starts inside the strip"));
}
