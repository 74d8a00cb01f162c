// MUMPS wrapper: an indefinite symmetric system with its inertia, and an unsymmetric one.
#include <catch2/catch.hpp>

#include "roller/solver/mumps_factorization.hpp"
#include "roller/solver/sparse_solver.hpp"

using namespace roller;

TEST_CASE("MumpsSolver (symmetric) solves a symmetric indefinite system and counts negative pivots", "[solver]") {
  // Tridiagonal 1D Laplacian shifted by -0.5: eigenvalues 2 - 2cos(k pi/(n+1)) - 0.5, three
  // of them negative for n = 20.
  const int n = 20;
  std::vector<Triplet> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2.0 - 0.5);
    if (i + 1 < n) {
      t.emplace_back(i + 1, i, -1.0);
      t.emplace_back(i, i + 1, -1.0);
    }
  }
  SparseMatrix a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  MumpsSolver ldlt;
  REQUIRE(ldlt.factorize(a));
  const VecX x_true = VecX::LinSpaced(n, 1.0, 2.0);
  const VecX x = ldlt.solve(a * x_true);
  CHECK((x - x_true).norm() < 1e-10 * x_true.norm());
  int expected_negative = 0;
  for (int k = 1; k <= n; ++k) expected_negative += (2.0 - 2.0 * std::cos(k * M_PI / (n + 1)) - 0.5 < 0) ? 1 : 0;
  CHECK(ldlt.negative_pivots() == expected_negative);
}

TEST_CASE("MumpsSolver (general) solves an unsymmetric system and reuses the analysis", "[solver]") {
  const int n = 30;
  std::vector<Triplet> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 4.0);
    if (i + 1 < n) {
      t.emplace_back(i + 1, i, -1.0);
      t.emplace_back(i, i + 1, -2.0);  // unsymmetric
    }
  }
  SparseMatrix a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  MumpsSolver lu(MumpsSolver::Symmetry::General);
  const VecX x_true = VecX::LinSpaced(n, -1.0, 3.0);
  for (Real s : {1.0, 2.5}) {  // same pattern, new values: numerical factorisation only
    const SparseMatrix as = s * a;
    REQUIRE(lu.factorize(as));
    CHECK((lu.solve(as * x_true) - x_true).norm() < 1e-10 * x_true.norm());
  }
  // A singular matrix is reported, not solved.
  SparseMatrix z(3, 3);
  z.insert(0, 0) = 1.0;
  z.insert(1, 1) = 0.0;
  z.insert(2, 2) = 1.0;
  MumpsSolver singular(MumpsSolver::Symmetry::General);
  CHECK_FALSE(singular.factorize(z));
  CHECK_THAT(singular.message(), Catch::Contains("MUMPS"));
}

TEST_CASE("SparseSolver solves below and above the MUMPS threshold alike", "[solver]") {
  for (const Index n : {Index{50}, kMumpsFromUnknowns + 10}) {
    for (const auto symmetry : {MumpsSolver::Symmetry::Symmetric, MumpsSolver::Symmetry::General}) {
      std::vector<Triplet> t;
      for (Index i = 0; i < n; ++i) {
        t.emplace_back(i, i, 3.0);
        if (i + 1 < n) {
          t.emplace_back(i + 1, i, -1.0);
          t.emplace_back(i, i + 1, symmetry == MumpsSolver::Symmetry::Symmetric ? -1.0 : -1.5);
        }
      }
      SparseMatrix a(n, n);
      a.setFromTriplets(t.begin(), t.end());
      SparseSolver solver(symmetry);
      const VecX x_true = VecX::LinSpaced(n, 0.5, 1.5);
      REQUIRE(solver.factorize(a));
      CHECK((solver.solve(a * x_true) - x_true).norm() < 1e-10 * x_true.norm());
    }
  }
}
