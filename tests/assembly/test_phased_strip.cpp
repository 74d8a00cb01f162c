// The stationary pass at several places of the roller between two nodes (assembly/phased_strip.hpp,
// docs/model.md "Phases"): the lanes walk the copies' points in turn, h/P apart; each copy holds
// its own ends; copies loaded alike are the one strip's pass.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "../support/small_stationary_strip.hpp"

#include "roller/assembly/phased_strip.hpp"
#include "roller/assembly/stationary_strip.hpp"
#include "roller/core/error.hpp"
#include "roller/steady/stationary_pass.hpp"

using namespace roller;

namespace {

constexpr Real kElement = 8.0 / 48;  // the small strip's element length along x

}  // namespace

TEST_CASE("phased strip: a lane walks the copies' points in turn, h/P apart, upstream first", "[stationary]") {
  const int phases = GENERATE(2, 3);
  const Real travel = GENERATE(1.0, -1.0);
  const test::SmallStationaryStrip small(test::plastic_steel(), 4.5);
  const PhasedStrip phased = phased_strip(small.mesh, small.materials, small.dofs, phases, -travel * kElement / phases);
  REQUIRE(phased.mesh.n_nodes() == phases * small.mesh.n_nodes());
  REQUIRE(phased.dofs.n_free() == phases * small.dofs.n_free());
  const StationaryStrip strip(phased.mesh, phased.materials, small.options, travel, phases);
  const StationaryStrip one(small.mesh, small.materials, small.options, travel);
  REQUIRE(strip.streamlines().size() == one.streamlines().size());
  const Index base_points = small.mesh.n_elements() * strip.points_per_element();
  for (const Streamline& line : strip.streamlines()) {
    REQUIRE(line.points.size() == static_cast<std::size_t>(phases) * one.streamlines().front().points.size());
    CHECK(line.points.front() < base_points);  // the first copy's point meets the material first
    for (std::size_t i = 1; i < line.points.size(); ++i) {
      const Index p = line.points[i], before = line.points[i - 1];
      CHECK(p / base_points == (before / base_points + 1) % phases);
      CHECK(travel * (strip.point_position(before).x() - strip.point_position(p).x()) ==
            Approx(kElement / phases).epsilon(1e-9));
    }
  }
}

TEST_CASE("phased strip: each copy is held at its own two ends by a state uniform along x", "[stationary]") {
  const test::SmallStationaryStrip small(test::plastic_steel(), 4.5);
  const PhasedStrip phased = phased_strip(small.mesh, small.materials, small.dofs, 2, -0.5 * kElement);
  const StationaryStrip strip(phased.mesh, phased.materials, small.options, 1.0, 2);
  std::vector<MaterialState> states = strip.virgin_upstream();
  for (std::size_t i = 0; i < states.size(); ++i) states[i].stress = Vec4(-300.0 + 5.0 * i, 0.0, -90.0 + i, 0.0);
  const VecX all = strip.forces(strip.spread(states));
  const VecX up = strip.end_forces(states, StationaryStrip::End::Upstream);
  const VecX down = strip.end_forces(states, StationaryStrip::End::Downstream);
  const Real scale = all.cwiseAbs().maxCoeff();
  CHECK((all - up - down).cwiseAbs().maxCoeff() <= 1e-9 * scale);
  const Index n = small.mesh.n_dofs();
  for (int k = 0; k < 2; ++k) {  // both copies' ends carry their layer's forces
    CHECK(up.segment(k * n, n).cwiseAbs().maxCoeff() > 0.1 * scale);
    CHECK(down.segment(k * n, n).cwiseAbs().maxCoeff() > 0.1 * scale);
  }
  CHECK(strip.end_x(StationaryStrip::End::Upstream) == Approx(8.0));
}

TEST_CASE("phased strip: a periodic strip or no phase is an input error", "[stationary]") {
  test::SmallStationaryStrip small(test::plastic_steel(), 4.5);
  CHECK_THROWS_AS(phased_strip(small.mesh, small.materials, small.dofs, 0, 0.0), InputError);
  small.mesh.period = 8.0;
  CHECK_THROWS_WITH(phased_strip(small.mesh, small.materials, small.dofs, 2, -0.1), Catch::Contains("periodic"));
}

TEST_CASE("phased stationary pass: copies loaded at the same place of their meshes give the one strip's pass",
          "[stationary]") {
  // Each copy carries the load on its own nodes, so the load moves with it and every copy sees the
  // roller at the same place: a lane then meets each strain twice in a row, and the second step,
  // of no strain, changes nothing. The fixed point is the one strip's, in every copy, through the
  // sweep over the interleaved lanes, the copies' ends and the steady Jacobian over all of them.
  MaterialParams steel = test::plastic_steel();
  steel.tangent_modulus = GENERATE(0.0, 2.0e4);
  const test::SmallStationaryStrip small(steel, 4.5);
  StationarySettings settings;
  settings.tolerance = 1e-10;
  SteadyJacobianSettings newton;
  newton.tolerance = settings.tolerance;

  SparseSolver k_one(MumpsSolver::Symmetry::Symmetric);
  REQUIRE(k_one.factorize(small.elastic));
  const StationaryStrip one(small.mesh, small.materials, small.options, 1.0);
  PrescribedLoadCorrection carrier_one(small.dofs, k_one, small.load);
  SteadyJacobianCorrection correction_one(one, small.dofs, small.elastic, carrier_one, one.virgin_upstream(), newton);
  const StationaryPassResult reference =
      solve_stationary_pass(one, small.dofs, correction_one, one.virgin_upstream(), settings);
  REQUIRE(reference.converged());
  REQUIRE(reference.n_yielded > 50);

  const PhasedStrip phased = phased_strip(small.mesh, small.materials, small.dofs, 2, -0.5 * kElement);
  const StationaryStrip strip(phased.mesh, phased.materials, small.options, 1.0, 2);
  StripModel model(phased.mesh, linear_elastic(phased.materials), small.options);
  model.set_dof_map(phased.dofs);
  SparseMatrix k;
  model.evaluate(VecX::Zero(phased.mesh.n_dofs()), nullptr, &k);
  SparseSolver k_e(MumpsSolver::Symmetry::Symmetric);
  REQUIRE(k_e.factorize(k));
  const Index n = small.mesh.n_dofs();
  VecX load(2 * n);
  load << small.load, small.load;
  PrescribedLoadCorrection carrier(phased.dofs, k_e, load);
  SteadyJacobianCorrection correction(strip, phased.dofs, k, carrier, strip.virgin_upstream(), newton);
  const StationaryPassResult r =
      solve_stationary_pass(strip, phased.dofs, correction, strip.virgin_upstream(), settings);
  REQUIRE(r.converged());
  CHECK(correction.factorizations() >= 1);
  const Real scale = reference.displacement.cwiseAbs().maxCoeff();
  Real largest = 0.0;
  for (const MaterialState& s : reference.states) largest = std::max(largest, s.eq_plastic_strain);
  const auto base_points = reference.states.size();
  for (Index copy = 0; copy < 2; ++copy) {
    CHECK((r.displacement.segment(copy * n, n) - reference.displacement).cwiseAbs().maxCoeff() <= 1e-7 * scale);
    Real gap = 0.0;
    for (std::size_t p = 0; p < base_points; ++p)
      gap = std::max(
          gap, std::abs(r.states[copy * base_points + p].eq_plastic_strain - reference.states[p].eq_plastic_strain));
    CHECK(gap <= 1e-6 * largest);
  }
}
