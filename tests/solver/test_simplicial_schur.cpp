// SimplicialSchur (Eigen's LDL^T with a Schur complement) against MumpsSolver on the same
// matrices: the Schur complement, the interior solve and the full solve through the Schur
// system; the factors recognised only for the matrix factorised; a matrix whose eliminated
// block is not positive definite refused, so that SchurCondenser takes MUMPS.
#include <catch2/catch.hpp>

#include "../support/grid_matrix.hpp"
#include "roller/solver/mumps_factorization.hpp"
#include "roller/solver/schur_condenser.hpp"
#include "roller/solver/simplicial_schur.hpp"

using namespace roller;
using test::grid_matrix;

TEST_CASE("SimplicialSchur gives MUMPS's Schur complement and solves", "[solver]") {
  const int g = 14;
  // Positive definite, with unequal diagonal entries; the Schur list out of order.
  const SparseMatrix a = grid_matrix(
      g, [](int k) { return 4.2 + 0.05 * (k % 5); }, -1.0);
  const std::vector<Index> schur = {17, 3, 4, 150, 5, 60};
  SimplicialSchur simplicial;
  MumpsSolver mumps;
  MatX s_simplicial, s_mumps;
  REQUIRE(simplicial.factorize_with_schur(a, schur, 1e-12, &s_simplicial));
  REQUIRE(mumps.factorize_with_schur(a, schur, &s_mumps));
  CHECK((s_simplicial - s_mumps).norm() <= 1e-13 * s_mumps.norm());
  CHECK((s_simplicial - s_simplicial.transpose()).norm() == 0.0);

  const VecX b = VecX::LinSpaced(a.rows(), -1.0, 3.0);
  const VecX xi = simplicial.solve_interior(b);
  CHECK((xi - mumps.solve_interior(b)).norm() <= 1e-13 * xi.norm());
  for (const Index v : schur) CHECK(xi(v) == 0.0);
  // The full solve with the Schur system solved densely gives A x = b.
  const Eigen::LDLT<MatX> dense(s_simplicial);
  const VecX x = simplicial.solve_with_schur(b, [&](const VecX& r) { return VecX(dense.solve(r)); });
  CHECK((a * x - b).norm() <= 1e-12 * b.norm());
  // A caller that fixes the Schur values gets the interior that goes with them.
  const VecX fixed = simplicial.solve_with_schur(b, [](const VecX& r) { return VecX(VecX::Ones(r.size())); });
  const VecX fixed_mumps = mumps.solve_with_schur(b, [](const VecX& r) { return VecX(VecX::Ones(r.size())); });
  CHECK((fixed - fixed_mumps).norm() <= 1e-13 * fixed_mumps.norm());

  CHECK(simplicial.holds_factors_of(a, schur));
  CHECK_FALSE(simplicial.holds_factors_of(a, {17, 3, 4, 150, 5}));
  SparseMatrix changed = a;
  changed.coeffRef(40, 39) += 1e-9;  // the lower triangle is what it reads
  CHECK_FALSE(simplicial.holds_factors_of(changed, schur));
  // A second factorisation with the same pattern (analysis kept) is that matrix's.
  REQUIRE(simplicial.factorize_with_schur(changed, schur, 1e-12, &s_simplicial));
  REQUIRE(mumps.factorize_with_schur(changed, schur, &s_mumps));
  CHECK((s_simplicial - s_mumps).norm() <= 1e-13 * s_mumps.norm());
  CHECK(simplicial.holds_factors_of(changed, schur));
}

TEST_CASE("SimplicialSchur refuses an eliminated block that is not positive definite", "[solver]") {
  const int g = 8;
  const SparseMatrix indefinite = grid_matrix(
      g, [](int) { return 2.7; }, -1.0);  // eigenvalues 2.7 - 2cos - 2cos: some negative
  SimplicialSchur simplicial;
  MatX s;
  CHECK_FALSE(simplicial.factorize_with_schur(indefinite, {0, 1}, 1e-12, &s));
  CHECK_FALSE(simplicial.holds_factors_of(indefinite, {0, 1}));
  // The condenser then condenses it with MUMPS, and says so by its inertia: MUMPS's pivots.
  SchurCondenser condenser;
  REQUIRE(condenser.condense(indefinite, {0, 1}, {0, 1}, &s) == SchurCondenser::Outcome::Factorised);
  MumpsSolver mumps;
  MatX expected;
  REQUIRE(mumps.factorize_with_schur(indefinite, {0, 1}, &expected));
  CHECK((s - expected).norm() <= 1e-12 * expected.norm());
  const auto inertia = condenser.inertia_of(indefinite);
  REQUIRE(inertia);
  CHECK(inertia->negative > 0);
}
