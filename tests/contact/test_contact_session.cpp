// The contact session from typed values alone (no scene, no run): Hertz's press under a
// prescribed force, the force reached and Hertz's contact; the run's increment is the same solve;
// the condensed contact of the stationary pass solves the same press alike.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "../support/run_scene.hpp"
#include "roller/analysis/hertz.hpp"
#include "roller/analysis/pressure_profile.hpp"
#include "roller/assembly/increment_energy.hpp"
#include "roller/contact/backend_factory.hpp"
#include "roller/contact/condensed_contact.hpp"
#include "roller/contact/contact_records.hpp"
#include "roller/contact/contact_session.hpp"
#include "roller/io/load_program.hpp"
#include "roller/io/scene_strip.hpp"

using namespace roller;

TEST_CASE("contact session: Hertz's press under a prescribed force from typed values alone, as a run solves it",
          "[contact][session]") {
  // The strip, its dofs and candidates of problems/hertz.toml; the rest typed by hand.
  const Scene scene = load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/hertz.toml");
  const std::unique_ptr<StripModel> strip = make_scene_strip(scene);
  strip->set_dof_map(LoadProgram(scene, strip->mesh()).dof_map());
  const Real e = 2.1e5, nu = 0.3, e_star = e / (1.0 - nu * nu), radius = 100.0, load = 7250.0;
  ContactSessionSettings settings;
  settings.surface_youngs_modulus = e;
  settings.surface_poisson_ratio = nu;
  settings.contact_modulus = e_star;
  settings.body_size = 200.0;
  settings.largest_force = Vec2(0.0, load);
  const std::unique_ptr<ContactBackend> backend = make_increment_backend(true, scene.contact, scene.newton);
  ContactSession session(settings, *backend, contact_candidate_nodes(scene, strip->mesh()));

  FrictionHistory friction;
  IncrementStart start;
  start.friction = &friction;
  start.motion.radius = radius;
  start.motion.start.centre = Vec2(100.0, 200.0);  // touching the top at x = 100
  start.motion.end = start.motion.start;
  start.force.fy = load;
  const VecX none = VecX::Zero(strip->n_dofs());
  IncrementEnergy energy(*strip, none, none);
  IncrementReport report;
  const IncrementSolution solution = session.solve(energy, none, none, start, report);
  REQUIRE(report.converged());
  // The roller ends where force control put it.
  const std::vector<NodeContactRecord> contact = contact_records(solution, start.motion.end.centre);

  // The force: within force control's tolerance, 1e-6 of the largest prescribed force.
  const Real p = force_on_roller(contact).y();
  CHECK(std::abs(p - load) <= 1e-6 * load);
  // Hertz's contact on this mesh (docs/validation.md, Hertz: refine 1 gives a within -2.1 %, p0
  // within +0.3 %, the exact gap's coupling).
  RollerPose pose;
  pose.centre = start.motion.end.centre;
  std::vector<PressureSample> samples = pressure_profile(contact, pose);
  std::sort(samples.begin(), samples.end(), [](const auto& a, const auto& b) { return a.x < b.x; });
  const HertzComparison hertz = compare_with_hertz(samples, p, radius, e_star);
  CHECK(std::abs(hertz.half_width_error) < 0.03);
  CHECK(std::abs(hertz.peak_error) < 0.005);

  // A run of the same press (one step of fy on the scene) is the same solve, to the bit.
  const Simulation run =
      test::run_scene("hertz", {{"steps.count", "1"}, {"roller.path", fmt::format("[{{steps=[1,1], fy={}}}]", load)}});
  REQUIRE(run.state().contact.size() == contact.size());
  for (std::size_t i = 0; i < contact.size(); ++i) CHECK(run.state().contact[i].force == contact[i].force);
  CHECK(run.state().pose.centre == pose.centre);
  CHECK(run.state().load_offset == solution.load_offset);
}

namespace {

// hertz.toml's top nodes within 4a of the roller (x = 100 mm), by x, and the strip's stiffness.
struct UnderRoller {
  std::vector<Index> nodes;
  std::vector<Vec2> positions;
  SparseMatrix stiffness;
};
UnderRoller under_roller(const Scene& scene, const StripModel& strip) {
  UnderRoller out;
  for (const Index a : contact_candidate_nodes(scene, strip.mesh()))
    if (std::abs(strip.mesh().nodes[a].x() - 100.0) <= 8.0) out.nodes.push_back(a);
  std::sort(out.nodes.begin(), out.nodes.end(),
            [&](Index a, Index b) { return strip.mesh().nodes[a].x() < strip.mesh().nodes[b].x(); });
  for (const Index a : out.nodes) out.positions.push_back(strip.mesh().nodes[a]);
  StripModel elastic(strip.mesh(), strip.materials(), strip.options());
  elastic.set_dof_map(strip.dof_map());
  elastic.evaluate(VecX::Zero(strip.n_dofs()), nullptr, &out.stiffness);
  return out;
}

}  // namespace

TEST_CASE("condensed contact: Hertz's press solved on the strip's condensed stiffness is the contact session's",
          "[contact][session]") {
  // The same problem two ways: the session's force-controlled increment (interior point) and the
  // dense active set on K's Schur complement under the roller (the stationary pass's).
  const Scene scene = load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/hertz.toml");
  const Real load = 7250.0;
  const Simulation run =
      test::run_scene("hertz", {{"steps.count", "1"}, {"roller.path", fmt::format("[{{steps=[1,1], fy={}}}]", load)}});
  const StripModel& strip = run.model();
  const auto [nodes, positions, k] = under_roller(scene, strip);
  CondensedContact condensed(k, strip.dof_map(), nodes, positions, 100.0, 100.0, scene.newton.linear);
  CondensedLoad frictionless;
  frictionless.force = load;
  const CondensedContact::Press pressed =
      condensed.solve(VecX::Zero(strip.n_dofs()), VecX::Zero(strip.dof_map().n_free()), frictionless);
  REQUIRE(pressed.message.empty());
  // The roller's height and every node's force agree within force control's tolerance (1e-6 of
  // the load; the session's interior point solves to it).
  CHECK(pressed.pose.centre.y() == Approx(run.state().pose.centre.y()).margin(1e-6));
  CHECK(std::abs(force_on_roller(pressed.contact).y() - load) <= 1e-9 * load);
  for (const NodeContactRecord& c : pressed.contact) {
    const auto same = std::find_if(run.state().contact.begin(), run.state().contact.end(),
                                   [&](const NodeContactRecord& r) { return r.node == c.node; });
    const Vec2 f = same == run.state().contact.end() ? Vec2::Zero() : same->force;
    INFO("node " << c.node << " at x = " << c.position.x());
    CHECK((c.force - f).norm() <= 1e-6 * load);
  }
}

TEST_CASE("condensed contact: a general tangent with unknowns after the free dofs condenses to the same contact",
          "[contact][session][friction]") {
  // The steady Jacobian's contact: the same K declared general and bordered by unknowns of their
  // own ([K 0; 0 I]) gives the symmetric condensation's press, frictionless and rolling with creep.
  const Scene scene = load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/hertz.toml");
  const Simulation run =
      test::run_scene("hertz", {{"steps.count", "1"}, {"roller.path", "[{steps=[1,1], fy=7250.0}]"}});
  const StripModel& strip = run.model();
  const auto [nodes, positions, k] = under_roller(scene, strip);
  const Index extra = 7;
  std::vector<Eigen::Triplet<Real>> t;
  for (Index c = 0; c < k.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(k, c); it; ++it) t.emplace_back(it.row(), it.col(), it.value());
  for (Index i = 0; i < extra; ++i) t.emplace_back(k.rows() + i, k.rows() + i, 1.0);
  SparseMatrix bordered(k.rows() + extra, k.cols() + extra);
  bordered.setFromTriplets(t.begin(), t.end());
  CondensedContact symmetric(k, strip.dof_map(), nodes, positions, 100.0, 100.0, scene.newton.linear);
  CondensedContact general(bordered, strip.dof_map(), nodes, positions, 100.0, 100.0, scene.newton.linear,
                           MumpsSolver::Symmetry::General);
  const auto [friction, creep] = GENERATE(table<Real, Real>({{0.0, 0.0}, {0.3, 0.002}, {0.3, 1.0}}));
  INFO("mu = " << friction << ", creep " << creep);
  CondensedLoad load;
  load.force = 7250.0;
  load.friction = friction;
  load.creep = creep;
  const VecX u = VecX::Zero(strip.n_dofs()), b = VecX::Zero(strip.dof_map().n_free());
  const CondensedContact::Press a = symmetric.solve(u, b, load), g = general.solve(u, b, load);
  REQUIRE(a.message.empty());
  REQUIRE(g.message.empty());
  REQUIRE(g.du.size() == a.du.size());
  CHECK((g.du - a.du).cwiseAbs().maxCoeff() <= 1e-9 * a.du.cwiseAbs().maxCoeff());
  REQUIRE(g.contact.size() == a.contact.size());
  for (std::size_t i = 0; i < a.contact.size(); ++i) {
    CHECK(g.contact[i].contact.status == a.contact[i].contact.status);
    CHECK((g.contact[i].force - a.contact[i].force).norm() <= 1e-8 * load.force);
  }
  if (friction > 0.0 && creep < 1.0)  // rolling with a small creep: a stick zone and slip behind it
    CHECK(std::count_if(a.contact.begin(), a.contact.end(),
                        [](const NodeContactRecord& c) { return c.contact.status == ContactStatus::Stick; }) >= 3);
}
