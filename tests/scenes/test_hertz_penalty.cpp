// Hertz line contact with the penalty backend: half-width and peak pressure against the analytic
// solution, global equilibrium (contact force = support reaction), the penalty penetration bound.
#include <catch2/catch.hpp>

#include "../support/run_scene.hpp"
#include "roller/analysis/hertz.hpp"

using namespace roller;

namespace {

Simulation run_hertz(int refine) {
  return test::run_scene("hertz", {{"mesh.refine", std::to_string(refine)}, {"contact.backend", "\"penalty\""}});
}

}  // namespace

TEST_CASE("Hertz line contact (penalty): a and p0 within 2 % of the analytic solution", "[contact][hertz]") {
  const Simulation sim = run_hertz(2);
  const Real e_star = sim.scene().material.youngs_modulus / (1 - std::pow(sim.scene().material.poisson_ratio, 2));
  const Real load = force_on_roller(sim.state().contact).y();
  const HertzComparison c = compare_with_hertz(pressure_profile(sim.state().contact, sim.state().pose), load,
                                               sim.scene().roller->radius, e_star);
  INFO("P = " << load << " a = " << c.half_width << " (analytic " << c.analytic.half_width << "), p0 = " << c.peak
              << " (analytic " << c.analytic.peak << "), L2 " << c.l2_error);
  CHECK(std::abs(c.half_width_error) < 0.02);
  CHECK(std::abs(c.peak_error) < 0.02);
  CHECK(c.l2_error < 0.05);
}

TEST_CASE("Hertz (penalty): contact force equals the support reaction, penetration within the penalty bound",
          "[contact][hertz]") {
  Simulation sim = run_hertz(1);
  // Support reaction: internal forces at the constrained dofs of the bottom edge.
  VecX g;
  sim.model().evaluate(VecX::Zero(sim.model().n_dofs()), &g, nullptr);
  Real reaction_y = 0.0;
  for (Index a : sim.model().mesh().node_set("bottom")) reaction_y += g(2 * a + 1);
  const Vec2 f = force_on_roller(sim.state().contact);
  CHECK(reaction_y == Approx(f.y()).epsilon(1e-6));  // the support carries what the roller pushes
  CHECK(std::abs(f.x()) < 1e-6 * f.y());
  // Penetration of each node = F_N / kN = p h / (factor E*) (penalty_backend.hpp).
  const Real e_star = sim.scene().material.youngs_modulus / (1 - std::pow(sim.scene().material.poisson_ratio, 2));
  for (const auto& c : sim.state().contact) {
    if (c.contact.status == ContactStatus::Open) continue;
    const Real p = c.contact.normal_force / c.tributary_length;
    CHECK(-c.contact.gap <= p * c.element_size / (sim.scene().contact.penalty.factor * e_star) * (1 + 1e-6));
    CHECK(-c.contact.gap > 0.0);
  }
}
