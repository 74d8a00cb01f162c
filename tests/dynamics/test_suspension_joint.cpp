// A roller whose height is not prescribed, solved with the strip (contact.roller_coupling =
// "joint": its height an unknown of the condensed NLP, contact/ipopt/ipopt_condensed.cpp), against the
// driver's coupling passes (dynamics/suspension.hpp, contact/force_control.hpp): the thesis's Z4
// impact (suspended) and burnishing (force-loaded) at refine 1 give the same answers step by step
// with one contact solve per step instead of two to four, and fewer linearisations.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "roller/driver/simulation.hpp"
#include "roller/io/scene_loader.hpp"

using namespace roller;

namespace {

// One scene run twice side by side: the roller's height joint (the default) and by passes.
struct JointAndPasses {
  JointAndPasses(const std::string& scene, std::vector<SceneOverride> overrides)
      : joint(load_scene(scene, overrides)), passes(load_scene(scene, with_passes(overrides))) {}
  static std::vector<SceneOverride> with_passes(std::vector<SceneOverride> o) {
    o.push_back({"contact.roller_coupling", "\"passes\""});
    return o;
  }
  // Advances both through `step` (each must converge) and counts their linearisations.
  std::pair<Simulation::StepRecord, Simulation::StepRecord> advance(int step) {
    auto a = joint.advance_step(step);
    auto b = passes.advance_step(step);
    REQUIRE(a.converged());
    REQUIRE(b.converged());
    joint_linearisations += a.details.get<IpoptDetails>().linearisations;
    passes_linearisations += b.details.get<IpoptDetails>().linearisations;
    return {a, b};
  }
  Simulation joint, passes;
  int joint_linearisations = 0, passes_linearisations = 0;
};

}  // namespace

TEST_CASE("Suspended roller: one joint solve per step equals the coupling passes", "[dynamics][suspension]") {
  const std::string scene = std::string(ROLLER_SOURCE_DIR) + "/problems/z4_v25.toml";
  JointAndPasses run(scene, {});
  const Simulation& joint = run.joint;
  const Simulation& passes = run.passes;
  REQUIRE(joint.scene().contact.roller_coupling == RollerCoupling::Joint);
  // The passes stop when w changes by less than 1e-10 R: that, and the contact forces' own
  // accuracy (the solver's tol), bound the difference.
  const Real w_tol = 10.0 * 1e-10 * joint.scene().roller->radius;
  int touching_steps = 0;
  for (int step = 1; step <= joint.scene().steps.n_steps; ++step) {
    INFO("step " << step);
    const auto [a, b] = run.advance(step);
    const Real fy = force_on_roller(passes.state().contact).y();
    CHECK(a.last.suspension_passes == 1);
    if (fy > 1.0) {  // before contact the first pass already balances the suspension
      ++touching_steps;
      CHECK(b.last.suspension_passes >= 2);
    }
    CHECK(std::abs(joint.dynamics().suspension()->deflection() - passes.dynamics().suspension()->deflection()) <=
          w_tol);
    CHECK(std::abs(force_on_roller(joint.state().contact).y() - fy) <= 1e-5 * std::max(std::abs(fy), 1.0));
    CHECK(std::abs(force_on_roller(joint.state().contact).x() - force_on_roller(passes.state().contact).x()) <=
          1e-5 * std::max(std::abs(fy), 1.0));
    // The strip (plastic, with inertia) carries the solves' differences on from step to step:
    // measured 2.4e-6 of the largest displacement at most.
    CHECK((joint.model().total_displacement() - passes.model().total_displacement()).lpNorm<Eigen::Infinity>() <=
          1e-5 * std::max(0.1, passes.model().total_displacement().lpNorm<Eigen::Infinity>()));
  }
  CHECK(touching_steps >= 10);
  INFO("linearisations: joint " << run.joint_linearisations << ", passes " << run.passes_linearisations);
  CHECK(run.joint_linearisations < run.passes_linearisations);
}

TEST_CASE("Suspended roller: the penalty backend couples by passes whatever the option says",
          "[dynamics][suspension]") {
  const std::string scene = std::string(ROLLER_SOURCE_DIR) + "/problems/z4_v25.toml";
  Simulation penalty(load_scene(scene, {{"contact.backend", "\"penalty\""}}));
  REQUIRE(penalty.scene().contact.roller_coupling == RollerCoupling::Joint);
  for (int step = 1; step <= 6; ++step) {
    const Simulation::StepRecord r = penalty.advance_step(step);
    REQUIRE(r.converged());
    if (step >= 5) CHECK(r.last.suspension_passes >= 2);  // in contact from step 4 on
  }
}

TEST_CASE("Force-loaded roller: one joint solve per increment on the strip equals the force passes",
          "[contact][force][slow]") {
  // Burnishing's first pass at refine 1: pressed to P = 420 N/mm (steps 1-3, frictionless), then
  // rolled under P with mu = 0.1. From the second increment on the strip the height is an unknown
  // of the contact solve; the passes find it by a root search to 1e-6 of P.
  const std::string scene = std::string(ROLLER_SOURCE_DIR) + "/problems/burnishing.toml";
  JointAndPasses run(scene, {{"mesh.refine", "1"}});
  const Simulation& joint = run.joint;
  const Simulation& passes = run.passes;
  const Real p = 420.0;
  for (int step = 1; step <= 10; ++step) {
    INFO("step " << step);
    const auto [a, b] = run.advance(step);
    if (step >= 2) {
      CHECK(a.last.load_passes == 1);
      CHECK(b.last.load_passes >= 2);
    }
    const Real p_step = p * std::min(step, 3) / 3.0;  // the press ramps P over steps 1-3
    if (step >= 2) CHECK(std::abs(force_on_roller(joint.state().contact).y() - p_step) <= 1e-7 * p);
    CHECK(std::abs(force_on_roller(passes.state().contact).y() - force_on_roller(joint.state().contact).y()) <=
          2e-6 * p);
    // The friction force follows the path of the load: within 1e-3 of it.
    CHECK(std::abs(force_on_roller(passes.state().contact).x() - force_on_roller(joint.state().contact).x()) <=
          1e-3 * std::max(1.0, std::abs(force_on_roller(passes.state().contact).x())));
    CHECK(std::abs(joint.state().pose.centre.y() - passes.state().pose.centre.y()) <= 1e-5);
  }
  INFO("linearisations: joint " << run.joint_linearisations << ", passes " << run.passes_linearisations);
  CHECK(run.joint_linearisations < run.passes_linearisations);
}
