// The rolling predictor (contact/rolling_predictor.hpp): the previous increment carried along
// with the roller reproduces a translated field exactly where linear interpolation along the
// strip's rows is exact, and the rolling scenes reach the same states as with the default.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "../support/strip_spec.hpp"
#include "roller/contact/rolling_predictor.hpp"
#include "roller/driver/simulation.hpp"
#include "roller/io/scene_loader.hpp"
#include "roller/mesh/strip_mesher.hpp"

using namespace roller;

namespace {

// A smooth "contact bump" travelling with the roller, sampled at the nodes: u(x, y) = f(x - c, y).
VecX bump(const Mesh& mesh, Real centre) {
  VecX u(mesh.n_dofs());
  for (Index a = 0; a < mesh.n_nodes(); ++a) {
    const Real s = mesh.nodes[a].x() - centre, y = mesh.nodes[a].y();
    u(2 * a) = 1e-3 * s * std::exp(-s * s / 4.0) * (1.0 + 0.1 * y);
    u(2 * a + 1) = -1e-2 * std::exp(-s * s / 4.0) * (1.0 + 0.2 * y);
  }
  return u;
}

}  // namespace

TEST_CASE("rolling predictor: a shift by whole columns reproduces the translated field exactly", "[contact][rolling]") {
  for (const ElementType type : {ElementType::Q4, ElementType::T3}) {
    const Mesh mesh = make_strip_mesh(test::strip_spec(type, 40.0, 4.0, 40, 4));  // 1 mm columns
    const VecX before = bump(mesh, 15.0);
    const VecX moved = translate_increment(mesh, mesh.nodes, before, 3.0);
    const VecX expected = bump(mesh, 18.0);
    // Exact at every node whose source (x - 3) lies on the strip; the first three columns keep
    // their own values.
    for (Index a = 0; a < mesh.n_nodes(); ++a) {
      INFO("node " << a << " at x = " << mesh.nodes[a].x());
      const Vec2 got(moved(2 * a), moved(2 * a + 1));
      const Vec2 want = mesh.nodes[a].x() >= 3.0 ? Vec2(expected(2 * a), expected(2 * a + 1))
                                                 : Vec2(before(2 * a), before(2 * a + 1));
      CHECK((got - want).norm() <= 1e-15);
    }
  }
}

TEST_CASE("rolling predictor: a field linear in x is translated exactly by any shift, on a graded mesh",
          "[contact][rolling]") {
  StripMeshSpec spec = test::strip_spec(ElementType::Q4, 100.0, 10.0, 30, 5);
  spec.grading_x = Grading{Grading::Kind::Geometric, 20.0, 50.0};
  const Mesh mesh = make_strip_mesh(spec);
  auto linear = [&](Real shift) {
    VecX u(mesh.n_dofs());
    for (Index a = 0; a < mesh.n_nodes(); ++a) {
      const Real x = mesh.nodes[a].x() - shift, y = mesh.nodes[a].y();
      u(2 * a) = 0.01 * x + 0.002 * y;
      u(2 * a + 1) = -0.03 * x + 0.5;
    }
    return u;
  };
  const Real dx = 7.3;
  const VecX moved = translate_increment(mesh, mesh.nodes, linear(0.0), dx);
  const VecX expected = linear(dx);
  Index inside = 0;
  for (Index a = 0; a < mesh.n_nodes(); ++a) {
    if (mesh.nodes[a].x() - dx < 0.0) continue;
    ++inside;
    CHECK(std::abs(moved(2 * a) - expected(2 * a)) <= 1e-12);
    CHECK(std::abs(moved(2 * a + 1) - expected(2 * a + 1)) <= 1e-12);
  }
  CHECK(inside > mesh.n_nodes() / 2);
  // No advance: the field itself (the press-in and the lift).
  CHECK(translate_increment(mesh, mesh.nodes, expected, 0.0) == expected);
}

TEST_CASE("rolling predictor: rolling with friction reaches the default predictor's states",
          "[contact][rolling][slow]") {
  for (const char* backend : {"ipopt", "penalty"}) {
    INFO(backend);
    auto load = [&](const char* predictor) {
      return Simulation(load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/rolling_friction.toml",
                                   {{"contact.backend", std::string("\"") + backend + "\""},
                                    {"contact.predictor", std::string("\"") + predictor + "\""}}));
    };
    Simulation rolling = load("rolling");
    Simulation plain = load("extrapolate");
    for (int step = 1; step <= plain.scene().total_steps(); ++step) {
      INFO("step " << step);
      const auto a = rolling.advance_step(step);
      const auto b = plain.advance_step(step);
      REQUIRE(a.converged());
      REQUIRE(b.converged());
      CHECK((force_on_roller(rolling.state().contact) - force_on_roller(plain.state().contact)).norm() <=
            1e-4 * force_on_roller(plain.state().contact).norm());
    }
  }
}
