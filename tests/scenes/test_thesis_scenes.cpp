// The thesis's quasistatic scenes run end to end with their default (interior-point) backend and
// with the penalty backend (also at refine 2): every step converges, the roller stays in contact
// while pressed, the Coulomb bound holds, nothing penetrates (ipopt).
#include <catch2/catch.hpp>

#include "../support/run_scene.hpp"

using namespace roller;

TEST_CASE("thesis scenes Z1 and Z2 run end to end (ipopt, refine 1)", "[contact][scenes][slow]") {
  for (const char* name : {"z1_outf05", "z1_outf10", "z2_infini", "z2_large"}) {
    SECTION(name) {
      const Simulation sim = test::run_scene(name);
      CHECK(sim.scene().contact.backend == ContactBackendKind::Ipopt);
      int in_contact = 0;
      for (const auto& c : sim.state().contact) {
        in_contact += c.contact.status != ContactStatus::Open ? 1 : 0;
        CHECK(c.contact.gap >= -1e-8 * sim.scene().roller->radius);
        CHECK(std::abs(c.contact.tangential_force) <=
              sim.scene().contact.friction * c.contact.normal_force * (1 + 1e-4) + 1e-6);
      }
      CHECK(in_contact >= 2);
      CHECK(force_on_roller(sim.state().contact).y() > 0.0);
      CHECK(sim.model().total_displacement().allFinite());
    }
  }
}

TEST_CASE("thesis scenes Z1 and Z2 run end to end with the penalty backend (refine 1 and 2)",
          "[contact][scenes][slow]") {
  const std::vector<std::pair<std::string, int>> runs{{"z1_outf05", 1}, {"z1_outf10", 1}, {"z2_infini", 1},
                                                      {"z2_large", 1},  {"z1_outf05", 2}, {"z1_outf10", 2},
                                                      {"z2_infini", 2}, {"z2_large", 2}};
  for (const auto& [name, refine] : runs) {
    SECTION(name + " refine " + std::to_string(refine)) {
      const Simulation sim =
          test::run_scene(name, {{"contact.backend", "\"penalty\""}, {"mesh.refine", std::to_string(refine)}});
      // (The penalty backend's Coulomb bound is its return map, nothing to check here; its
      // forces are checked against the interior-point backend in test_backend_agreement.cpp.)
      int in_contact = 0;
      for (const auto& c : sim.state().contact) in_contact += c.contact.status != ContactStatus::Open ? 1 : 0;
      CHECK(in_contact >= 2);
      CHECK(force_on_roller(sim.state().contact).y() > 0.0);
    }
  }
}
