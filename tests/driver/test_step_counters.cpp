// The work counters of solver.csv per step: summed over every contact solve of the step (a
// suspended roller solves the contact once per suspension pass, a cut step once per sub-increment),
// not only the last one's.
#include <catch2/catch.hpp>

#include <string>

#include "roller/driver/simulation.hpp"
#include "roller/io/scene_loader.hpp"

using namespace roller;

TEST_CASE("step counters: a suspended roller's linearisations and NLP solves summed over its passes",
          "[driver][counters]") {
  // Z3 DATA01 (a suspended roller, ipopt, condensed): each linearisation factorises the strip's
  // tangent once, so the step's factorisations and linearisations agree when both are summed
  // (the last contact solve's linearisations alone were a third of the factorisations). The
  // suspension coupled by passes: a joint solve is one contact solve a step.
  Simulation sim(load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/z3_data01.toml",
                            {{"contact.roller_coupling", "\"passes\""}}));
  int steps_with_several_passes = 0;
  for (int step = 1; step <= 6; ++step) {
    const Simulation::StepRecord r = sim.advance_step(step);
    INFO("step " << step << ": " << r.stats.brief());
    REQUIRE(r.converged);
    CHECK(r.stats.linearisations == r.factorizations);
    CHECK(r.stats.nlp_solves >= r.stats.linearisations);
    CHECK(r.stats.ipopt_time_s > 0.0);
    if (r.last.suspension_passes > 1) ++steps_with_several_passes;
    CHECK(r.stats.linearisations == r.last.stats.linearisations);  // no cuts: one sub-increment
  }
  CHECK(steps_with_several_passes >= 3);
}

TEST_CASE("BackendStats::add sums the work and keeps the last solve's state", "[contact][counters]") {
  BackendStats first, second;
  first.nlp_solves = 3;
  first.linearisations = 2;
  first.cold_restarts = 1;
  first.ipopt_time_s = 0.5;
  first.condensed_dofs = 10;
  first.complementarity = 1e-3;
  first.acceptable_level = true;
  second.nlp_solves = 4;
  second.linearisations = 5;
  second.ipopt_time_s = 0.25;
  second.condensed_dofs = 12;
  second.complementarity = 1e-9;
  BackendStats sum = first;
  sum.add(second);
  CHECK(sum.nlp_solves == 7);
  CHECK(sum.linearisations == 7);
  CHECK(sum.cold_restarts == 1);
  CHECK(sum.ipopt_time_s == 0.75);
  CHECK(sum.condensed_dofs == 12);
  CHECK(sum.complementarity == 1e-9);
  CHECK(sum.acceptable_level);
}
