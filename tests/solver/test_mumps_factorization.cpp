// MUMPS wrapper: an indefinite symmetric system with its inertia, and an unsymmetric one.
#include <algorithm>
#include <filesystem>

#include <catch2/catch.hpp>

#include "../support/grid_matrix.hpp"
#include "roller/solver/mumps_factorization.hpp"
#include "roller/solver/sparse_solver.hpp"

using namespace roller;

using test::grid_matrix;

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
  // Inertia only: the factors discarded as they are computed, the pivots counted all the same,
  // twice with one analysis.
  MumpsSolver inertia;
  inertia.discard_factors();
  for (int pass = 0; pass < 2; ++pass) {
    REQUIRE(inertia.factorize(a));
    CHECK(inertia.negative_pivots() == expected_negative);
  }
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

namespace {

// The Schur variables used below, scattered through an n-variable grid, and the others.
const std::vector<Index> kSchur = {3, 17, 18, 40, 5};
std::vector<Index> interior_of(Index n) {
  std::vector<Index> interior;
  for (Index k = 0; k < n; ++k)
    if (std::find(kSchur.begin(), kSchur.end(), k) == kSchur.end()) interior.push_back(k);
  return interior;
}

// The block of `dense` at rows r and columns c.
MatX block(const MatX& dense, const std::vector<Index>& r, const std::vector<Index>& c) {
  MatX b(r.size(), c.size());
  for (std::size_t i = 0; i < r.size(); ++i)
    for (std::size_t j = 0; j < c.size(); ++j) b(i, j) = dense(r[i], c[j]);
  return b;
}

}  // namespace

TEST_CASE("MumpsSolver Schur complement and interior solve equal the dense block formulas", "[solver]") {
  // A 2D 5-point Laplacian plus a diagonal shift (SPD), Schur variables scattered through it.
  const int g = 7, n = g * g;
  const SparseMatrix a = grid_matrix(
      g, [](int k) { return 4.2 + 0.01 * k; }, -1.0);
  const std::vector<Index>& schur = kSchur;
  const std::vector<Index> interior = interior_of(n);
  const MatX dense = MatX(a);
  const MatX a_ii = block(dense, interior, interior), a_is = block(dense, interior, schur);
  const MatX s_dense = block(dense, schur, schur) - a_is.transpose() * a_ii.ldlt().solve(a_is);

  // In core with each ordering, and out of core (factors in files under `ooc`, removed when the
  // solver ends).
  const std::filesystem::path ooc = std::filesystem::temp_directory_path() / "roller_test_mumps_ooc";
  std::filesystem::remove_all(ooc);
  std::filesystem::create_directories(ooc);
  std::vector<LinearSolverOptions> variants(4);
  variants[1].ordering = "amd";
  variants[2].ordering = "metis";
  variants[3].out_of_core = true;
  variants[3].directory = ooc.string();
  for (const LinearSolverOptions& options : variants)
    for (const auto symmetry : {MumpsSolver::Symmetry::Symmetric, MumpsSolver::Symmetry::General}) {
      INFO("ordering " << options.ordering << ", out of core " << options.out_of_core);
      MumpsSolver solver(symmetry, options);
      MatX s;
      for (Real scale : {1.0, 3.0}) {  // second pass reuses the analysis
        REQUIRE(solver.factorize_with_schur(scale * a, schur, &s));
        if (options.out_of_core) CHECK_FALSE(std::filesystem::is_empty(ooc));  // the factors are on disk
        CHECK((s - scale * s_dense).norm() < 1e-12 * scale * s_dense.norm());
      }
      const VecX b = VecX::LinSpaced(n, -1.0, 2.0);
      VecX b_i(interior.size());
      for (std::size_t k = 0; k < interior.size(); ++k) b_i(k) = b(interior[k]);
      const VecX x_i = (3.0 * a_ii).ldlt().solve(b_i);
      const VecX x = solver.solve_interior(b);
      for (std::size_t k = 0; k < interior.size(); ++k) CHECK(std::abs(x(interior[k]) - x_i(k)) < 1e-12);
      for (const Index k : schur) CHECK(x(k) == 0.0);
      // A plain factorisation afterwards solves the whole system again.
      REQUIRE(solver.factorize(a));
      const VecX x_full = solver.solve(a * b);
      CHECK((x_full - b).norm() < 1e-10 * b.norm());
    }
  CHECK(std::filesystem::is_empty(ooc));
  std::filesystem::remove_all(ooc);
}

TEST_CASE("MumpsSolver retries a factorisation whose delayed pivots overrun the workspace", "[solver]") {
  // A 20 x 20 grid graph with unit off-diagonals and a diagonal of 0 or +-1e-8: threshold
  // pivoting rejects most diagonal pivots and delays them up the tree, which MUMPS's analysis (on
  // the pattern) cannot foresee. With no headroom (ICNTL(14) = 0) the first attempt overruns
  // (INFOG(1) = -9, measured) and the wrapper raises the headroom until it fits.
  const int n = 20 * 20;
  const SparseMatrix a = grid_matrix(
      20, [](int k) { return 1e-8 * (k % 3 - 1); }, 1.0);
  LinearSolverOptions options;
  options.workspace_percent = 0;
  MumpsSolver ldlt(MumpsSolver::Symmetry::Symmetric, options);
  REQUIRE(ldlt.factorize(a));
  CHECK(ldlt.workspace_percent() > 0);  // it did retry
  // The matrix is ill-conditioned (tiny diagonal): check the residual (backward error).
  const VecX b = a * VecX::LinSpaced(n, -1.0, 1.0);
  CHECK((a * ldlt.solve(b) - b).norm() < 1e-12 * b.norm());
}

TEST_CASE("MumpsSolver's Schur complement of an unsymmetric matrix, and its reduced solve, are A's own", "[solver]") {
  // The steady Jacobian is not symmetric: S = A_ss - A_si A_ii^-1 A_is with A_si != A_is^T, and
  // the reduction and expansion around a Schur solve of the caller's give A x = b.
  const int g = 8, n = g * g;
  SparseMatrix a = grid_matrix(
      g, [](int k) { return 4.2 + 0.01 * k; }, -1.0);
  for (int k = 0; k + 1 < n; ++k) a.coeffRef(k + 1, k) += 0.3 + 0.001 * k;  // an upwind term below the diagonal
  a.makeCompressed();
  const std::vector<Index>& schur = kSchur;
  const std::vector<Index> interior = interior_of(n);
  const MatX dense = MatX(a);
  const MatX s_dense =
      block(dense, schur, schur) -
      block(dense, schur, interior) * block(dense, interior, interior).lu().solve(block(dense, interior, schur));
  REQUIRE((s_dense - s_dense.transpose()).norm() > 1e-3 * s_dense.norm());  // the test can tell S from S^T
  MumpsSolver solver(MumpsSolver::Symmetry::General);
  MatX s;
  REQUIRE(solver.factorize_with_schur(a, schur, &s));
  CHECK((s - s_dense).norm() < 1e-12 * s_dense.norm());
  const VecX b = VecX::LinSpaced(n, -1.0, 2.0);
  const VecX x = solver.solve_with_schur(b, [&](const VecX& reduced) { return VecX(s.lu().solve(reduced)); });
  CHECK((a * x - b).norm() < 1e-12 * b.norm());
}
