// SchurCondenser: the Schur complement on a subset of a held superset, the interior solve and
// the inertia, against dense block formulas; factors reused only for the very matrix held.
#include <catch2/catch.hpp>

#include <algorithm>

#include "../support/grid_matrix.hpp"
#include "roller/core/eigenvalues.hpp"
#include "roller/solver/schur_condenser.hpp"

using namespace roller;
using test::grid_matrix;

namespace {

std::vector<Index> complement(Index n, const std::vector<Index>& set) {
  std::vector<Index> out;
  for (Index k = 0; k < n; ++k)
    if (std::find(set.begin(), set.end(), k) == set.end()) out.push_back(k);
  return out;
}

// S = A_WW - A_WI A_II^-1 A_IW, dense.
MatX dense_schur(const SparseMatrix& a, const std::vector<Index>& set) {
  const MatX d(a);
  const std::vector<Index> interior = complement(a.rows(), set);
  const MatX a_ii = d(interior, interior), a_iw = d(interior, set);
  return d(set, set) - a_iw.transpose() * a_ii.lu().solve(a_iw);
}

}  // namespace

TEST_CASE("SchurCondenser reduces a held Schur complement to any subset exactly", "[solver]") {
  const int g = 12;
  const SparseMatrix a = grid_matrix(
      g, [](int k) { return 4.1 + 0.02 * (k % 7); }, -1.0);
  const std::vector<Index> superset = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 30, 31};  // the top row and two more
  SchurCondenser condenser;
  MatX s;
  // Sets in another order than the superset's, a set equal to it, and a single variable.
  const std::vector<std::vector<Index>> sets = {{5, 4, 6, 3}, superset, {31, 7}, {9}};
  for (std::size_t k = 0; k < sets.size(); ++k) {
    const std::vector<Index>& set = sets[k];
    INFO("set " << k);
    const auto outcome = condenser.condense(a, set, superset, &s);
    CHECK(outcome == (k == 0 ? SchurCondenser::Outcome::Factorised : SchurCondenser::Outcome::Reused));
    const MatX expected = dense_schur(a, set);
    CHECK((s - expected).norm() < 1e-12 * expected.norm());
    // Interior solve: A_I'I' x = b on the variables outside the set, zero on it.
    const VecX b = VecX::LinSpaced(a.rows(), -1.0, 2.0);
    const std::vector<Index> interior = complement(a.rows(), set);
    const MatX d(a);
    const VecX x_expected = d(interior, interior).lu().solve(VecX(b(interior)));
    const VecX x = condenser.solve_interior(b);
    CHECK((VecX(x(interior)) - x_expected).norm() < 1e-12 * x_expected.norm());
    for (const Index v : set) CHECK(x(v) == 0.0);
  }
  // A set outside the superset, or another matrix, is factorised again.
  CHECK(condenser.condense(a, {40, 3}, {40, 3}, &s) == SchurCondenser::Outcome::Factorised);
  CHECK((s - dense_schur(a, {40, 3})).norm() < 1e-12 * s.norm());
  const SparseMatrix a2 = 2.0 * a;
  CHECK(condenser.condense(a2, {40, 3}, {40, 3}, &s) == SchurCondenser::Outcome::Factorised);
  CHECK(condenser.condense(a2, {3}, {40, 3}, &s) == SchurCondenser::Outcome::Reused);
  CHECK((s - dense_schur(a2, {3})).norm() < 1e-12 * s.norm());
}

TEST_CASE("SchurCondenser gives the inertia of the matrix it holds, and only of that one", "[solver]") {
  // Shifted grid Laplacian: eigenvalues 4.0 - shift - 2cos(i pi/(g+1)) - 2cos(j pi/(g+1)).
  const int g = 10;
  const Real shift = 1.3;
  const SparseMatrix a = grid_matrix(
      g, [&](int) { return 4.0 - shift; }, -1.0);
  Index expected = 0;
  for (const Real lambda : symmetric_eigenvalues(MatX(a))) expected += lambda < 0.0 ? 1 : 0;
  REQUIRE(expected > 0);
  SchurCondenser condenser;
  MatX s;
  // Superset: the last grid row; the indefinite S_C[R,R] makes the condenser factorise on the set.
  std::vector<Index> superset;
  for (Index k = 0; k < g; ++k) superset.push_back((g - 1) * g + k);
  const std::vector<Index> set = {superset[2], superset[3]};
  REQUIRE(condenser.condense(a, set, superset, &s) != SchurCondenser::Outcome::Failed);
  CHECK((s - dense_schur(a, set)).norm() < 1e-10 * s.norm());
  const auto inertia = condenser.inertia_of(a);
  REQUIRE(inertia);
  CHECK(inertia->negative == expected);
  CHECK(inertia->zero == 0);
  const SparseMatrix other = 1.5 * a;
  CHECK_FALSE(condenser.inertia_of(other));

  // Positive definite with the whole superset held: no negative, no null eigenvalue.
  const SparseMatrix spd = grid_matrix(
      g, [](int) { return 4.5; }, -1.0);
  REQUIRE(condenser.condense(spd, set, superset, &s) == SchurCondenser::Outcome::Factorised);
  const auto positive = condenser.inertia_of(spd);
  REQUIRE(positive);
  CHECK(positive->negative == 0);
  CHECK(positive->zero == 0);
  condenser.release();
  CHECK_FALSE(condenser.inertia_of(spd));
}

TEST_CASE("SchurCondenser reports a matrix singular outside the Schur set", "[solver]") {
  // The pure Neumann grid Laplacian (diagonal = number of neighbours; constants are its null
  // space) beside one decoupled variable, which alone is kept: the eliminated block is singular.
  const int g = 6, n = g * g;
  const SparseMatrix grid = grid_matrix(
      g,
      [&](int k) {
        const int i = k / g, j = k % g;
        return static_cast<Real>((i > 0) + (i + 1 < g) + (j > 0) + (j + 1 < g));
      },
      -1.0);
  std::vector<Triplet> t;
  for (int k = 0; k < grid.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(grid, k); it; ++it) t.emplace_back(it.row(), it.col(), it.value());
  t.emplace_back(n, n, 1.0);
  SparseMatrix a(n + 1, n + 1);
  a.setFromTriplets(t.begin(), t.end());
  SchurCondenser condenser;
  MatX s;
  CHECK(condenser.condense(a, {n}, {n}, &s) == SchurCondenser::Outcome::Failed);
  CHECK_THAT(condenser.message(), Catch::Contains("singular"));
  // Node 0 tied to the kept variable by a spring: the eliminated grid is grounded and condenses,
  // S = 1 + 1 - 1 (the spring, then the grounded grid which transmits it whole: S = 1).
  t.emplace_back(0, 0, 1.0);
  t.emplace_back(n, n, 1.0);
  t.emplace_back(n, 0, -1.0);
  t.emplace_back(0, n, -1.0);
  a.setFromTriplets(t.begin(), t.end());
  REQUIRE(condenser.condense(a, {n}, {n}, &s) == SchurCondenser::Outcome::Factorised);
  CHECK(s(0, 0) == Approx(1.0).epsilon(1e-10));
}
