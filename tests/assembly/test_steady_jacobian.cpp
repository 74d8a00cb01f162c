// The steady problem's Jacobian (assembly/steady_jacobian.hpp) against central differences of the
// nodal forces of the swept states: solving it for a right-hand side b must give the displacement
// whose forces change by b, for each hardening law's lane states.
#include <catch2/catch.hpp>

#include <cmath>

#include <Eigen/SparseLU>

#include "../support/small_stationary_strip.hpp"

#include "roller/assembly/steady_jacobian.hpp"
#include "roller/material/j2_plasticity.hpp"

using namespace roller;

namespace {

// The free dofs' forces sum w B^T sigma of the states swept from the virgin strip at u.
VecX swept_forces(const StationaryStrip& strip, const DofMap& dofs, const VecX& u) {
  return dofs.gather_free(strip.forces(strip.sweep(strip.strains(u), strip.virgin_upstream())));
}

}  // namespace

TEST_CASE("steady Jacobian: its solution changes the swept forces by the right-hand side", "[stationary]") {
  MaterialParams hardening = test::plastic_steel();
  hardening.tangent_modulus = 2.0e4;
  MaterialParams armstrong_frederick = test::plastic_steel();
  armstrong_frederick.hardening = Hardening::Chaboche;
  armstrong_frederick.n_chaboche = 1;
  armstrong_frederick.chaboche[0] = {2.0e4, 20.0};
  const auto [name, material] =
      GENERATE_COPY(table<const char*, MaterialParams>({{"perfectly plastic", test::plastic_steel()},
                                                        {"isotropic", hardening},
                                                        {"Armstrong-Frederick", armstrong_frederick}}));
  // The lanes' yielding steps walked in parts (the default) or returned at once (the transient's).
  const int parts = GENERATE(as<int>{}, kDefaultPathParts, 1);
  INFO(name << ", " << parts << " parts a step");

  // Under an elliptic pressure of peak 5 k, whose elastic field yields when it is swept.
  const test::SmallStationaryStrip small(material, 5.0);
  const Mesh& mesh = small.mesh;
  const DofMap& dofs = small.dofs;
  const SparseMatrix& k = small.elastic;
  const VecX& load = small.load;
  Eigen::SimplicialLDLT<SparseMatrix> k_e(k);
  VecX u = VecX::Zero(mesh.n_dofs());
  dofs.scatter_free(k_e.solve(dofs.gather_free(load)), u);

  const StationaryStrip strip(mesh, small.materials, small.options, 1.0, 1, parts);
  const std::vector<Vec4> strains = strip.strains(u);
  const std::vector<MaterialState> upstream = strip.virgin_upstream();
  const SteadyJacobian j = steady_jacobian(strip, dofs, k, strains, upstream, strip.sweep(strains, upstream));
  REQUIRE(j.n_yielding > 50);  // the pressure yields a plastic zone, and lanes leave it elastic
  // One lane state per yielding step: an elastic step copies the state upstream of it.
  REQUIRE(j.matrix.rows() == j.n_free + (5 + 4 * material.n_back_stresses()) * j.n_yielding);

  VecX b = VecX::Zero(j.matrix.rows());
  for (Index i = 0; i < j.n_free; ++i) b[i] = 1e3 * std::sin(1.7 * i + 0.3);
  Eigen::SparseLU<SparseMatrix> lu(j.matrix);
  REQUIRE(lu.info() == Eigen::Success);
  const VecX x = lu.solve(b);
  VecX du = VecX::Zero(mesh.n_dofs());
  dofs.scatter_free(x.head(j.n_free), du);
  // A ten-millionth of the displacement, so that no point changes between yielding and not: at a
  // hundred-thousandth some do, and the differences are 1-4 % off (measured; 3e-8 here).
  const Real h = 1e-7 * u.cwiseAbs().maxCoeff() / du.cwiseAbs().maxCoeff();
  const VecX change = (swept_forces(strip, dofs, u + h * du) - swept_forces(strip, dofs, u - h * du)) / (2.0 * h);
  const Real error = (change - b.head(j.n_free)).norm() / b.head(j.n_free).norm();
  // The elastic stiffness alone misses the lanes' plastic flow by far.
  const VecX elastic_change = k * x.head(j.n_free);
  CHECK((elastic_change - b.head(j.n_free)).norm() / b.head(j.n_free).norm() > 0.05);
  CHECK(error < 1e-6);
}
