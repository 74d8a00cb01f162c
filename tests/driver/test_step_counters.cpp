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
    INFO("step " << step << ": " << r.details.brief());
    REQUIRE(r.converged());
    CHECK(r.details.get<IpoptDetails>().linearisations == r.counters.factorizations);
    CHECK(r.details.get<IpoptDetails>().nlp_solves >= r.details.get<IpoptDetails>().linearisations);
    CHECK(r.details.get<IpoptDetails>().ipopt_time_s > 0.0);
    if (r.last.suspension_passes > 1) ++steps_with_several_passes;
    CHECK(r.details.get<IpoptDetails>().linearisations ==
          r.last.details.get<IpoptDetails>().linearisations);  // no cuts: one sub-increment
  }
  CHECK(steps_with_several_passes >= 3);
}

TEST_CASE("BackendDetails::add sums the work and keeps the last solve's state", "[contact][counters]") {
  BackendDetails first, second;
  IpoptDetails& f = first.fill<IpoptDetails>();
  f.nlp_solves = 3;
  f.linearisations = 2;
  f.cold_restarts = 1;
  f.ipopt_time_s = 0.5;
  f.condensed_dofs = 10;
  f.complementarity = 1e-3;
  f.acceptable_level = true;
  IpoptDetails& s = second.fill<IpoptDetails>();
  s.nlp_solves = 4;
  s.linearisations = 5;
  s.ipopt_time_s = 0.25;
  s.condensed_dofs = 12;
  s.complementarity = 1e-9;
  BackendDetails sum = first;
  sum.add(second);
  const IpoptDetails& total = sum.get<IpoptDetails>();
  CHECK(total.nlp_solves == 7);
  CHECK(total.linearisations == 7);
  CHECK(total.cold_restarts == 1);
  CHECK(total.ipopt_time_s == 0.75);
  CHECK(total.condensed_dofs == 12);
  CHECK(total.complementarity == 1e-9);
  CHECK(total.acceptable_level);
  // A solve that measured nothing keeps the work and zeroes the state; another backend's
  // details read as zeros.
  sum.add(BackendDetails{});
  CHECK(sum.get<IpoptDetails>().nlp_solves == 7);
  CHECK(sum.get<IpoptDetails>().condensed_dofs == 0);
  CHECK(sum.get<PenaltyDetails>().penalty_stages == 0);
  BackendDetails empty;
  empty.add(second);
  CHECK(empty.get<IpoptDetails>().nlp_solves == 4);
}
