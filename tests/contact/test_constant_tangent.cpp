// A constant strip tangent (linear elastic, small kinematics) is factorised once per run: the
// condensed ipopt backend keeps its factors with the Schur complement on every candidate and
// reduces each increment's working set from them (solver/schur_condenser.hpp, whose own test
// checks the reduction against dense algebra). Here, on Hertz: the counters say what was done,
// the strip is in equilibrium with the contact forces (a wrong interior solve leaves 4e-4, the
// exact one 1e-13), and the forces are those of the full formulation, which condenses nothing
// (to the solvers' tolerance; the golden values hold them to 1e-6 of the peak).
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "../support/temp_files.hpp"

#include "roller/driver/simulation.hpp"
#include "roller/driver/step_monitor.hpp"
#include "roller/io/scene_loader.hpp"

using namespace roller;

TEST_CASE("constant tangent: one factorisation for the run, the answers of the uncondensed NLP",
          "[contact][ipopt][counters]") {
  const std::string scene = std::string(ROLLER_SOURCE_DIR) + "/problems/hertz.toml";
  Simulation condensed(load_scene(scene));
  Simulation full(load_scene(scene, {{"contact.ipopt.formulation", "\"full\""}}));
  for (int step = 1; step <= condensed.scene().total_steps(); ++step) {
    const Simulation::StepRecord r = condensed.advance_step(step);
    INFO("step " << step << ": " << r.details.brief());
    REQUIRE(r.converged());
    REQUIRE(full.advance_step(step).converged());
    CHECK(r.counters.factorizations == (step == 1 ? 1 : 0));  // reused after the first
    // Hertz is linear but for the contact: one linearisation solves an increment.
    CHECK(r.details.get<IpoptDetails>().linearisations == 1);
    CHECK(r.last.residual <= 1e-10);
    const Vec2 force = force_on_roller(condensed.state().contact), reference = force_on_roller(full.state().contact);
    CHECK(reference.y() > 0.0);
    CHECK((force - reference).norm() <= 1e-4 * reference.norm());
  }
}

TEST_CASE("constant tangent: the run-time monitor takes the inertia of the contact solve's factors",
          "[contact][ipopt][monitor]") {
  // After a step the backend holds the factors of the very K the monitor checks: its verdict
  // comes from them, and equals the monitor's own LDL^T. A plastic strip's tangent changes, the
  // backend frees its factors, and the monitor factorises K itself.
  for (const bool plastic : {false, true}) {
    INFO((plastic ? "plastic" : "elastic"));
    std::vector<SceneOverride> overrides;
    if (plastic) overrides = {{"material.yield_stress", "300.0"}, {"material.tangent_modulus", "2100.0"}};
    Simulation sim(load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/hertz.toml", overrides));
    REQUIRE(sim.advance_step(1).converged());
    StepMonitor borrowing(true, sim.scene().steps.dt, nullptr, sim.contact_backend(), nullptr);
    StepMonitor own(true, sim.scene().steps.dt, nullptr, nullptr, nullptr);
    const MonitorReport held = borrowing.check(1, sim.model()), computed = own.check(1, sim.model());
    CHECK(held.from_contact_solve == !plastic);
    CHECK_FALSE(computed.from_contact_solve);
    CHECK(held.assembled.factorized);
    CHECK(held.assembled.positive_definite());
    CHECK(held.assembled.n_negative == computed.assembled.n_negative);
    CHECK(held.assembled.n_zero == computed.assembled.n_zero);
  }
}

TEST_CASE("constant tangent: a resumed run factorises afresh and agrees to round-off", "[contact][ipopt]") {
  // The uninterrupted run reduces steps 3 and 4 from step 1's factors; the resumed one holds none
  // and factorises at step 3 with that step's candidates. Not the same bytes (a plastic strip's
  // resume is: tests/contact/test_passes.cpp), the same answers to round-off.
  const std::string scene = std::string(ROLLER_SOURCE_DIR) + "/problems/hertz.toml";
  test::TempDir dir("roller_constant_tangent_resume");
  Simulation whole(load_scene(scene)), first(load_scene(scene));
  for (int step = 1; step <= 2; ++step) {
    REQUIRE(whole.advance_step(step).converged());
    REQUIRE(first.advance_step(step).converged());
  }
  first.save_state(dir.path() / "after_2.cbor");
  Simulation resumed(load_scene(scene));
  resumed.load_state(dir.path() / "after_2.cbor", /*strip_only=*/false);
  for (int step = 3; step <= 4; ++step) {
    INFO("step " << step);
    const Simulation::StepRecord w = whole.advance_step(step), r = resumed.advance_step(step);
    REQUIRE(w.converged());
    REQUIRE(r.converged());
    CHECK(w.counters.factorizations == 0);
    CHECK(r.counters.factorizations == (step == 3 ? 1 : 0));
    CHECK((force_on_roller(whole.state().contact) - force_on_roller(resumed.state().contact)).norm() <=
          1e-10 * force_on_roller(whole.state().contact).norm());
    const VecX& uw = whole.model().total_displacement();
    CHECK((uw - resumed.model().total_displacement()).lpNorm<Eigen::Infinity>() <=
          1e-10 * uw.lpNorm<Eigen::Infinity>());
  }
}
