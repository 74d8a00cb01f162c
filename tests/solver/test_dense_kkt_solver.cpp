// The dense KKT solver behind Ipopt's MA27 interface (solver/dense_kkt_solver.hpp): solves
// and inertia of symmetric indefinite KKT matrices given as MA27 triplets, MA27's reports of a
// rank deficiency and of workspaces too small.
#include <catch2/catch.hpp>

#include <random>
#include <vector>

#include "roller/core/eigenvalues.hpp"
#include "roller/core/types.hpp"
#include "roller/solver/dense_kkt_solver.hpp"

using namespace roller;
namespace ma27 = roller::dense_kkt::dense_ma27;

namespace {

// A matrix as MA27 takes it, with the workspaces Ipopt's MA27 interface would allocate.
struct Triplets {
  int n = 0;
  std::vector<int> row, col;  // 1-based
  std::vector<double> value;
};

// Triplets of the lower triangle of `a`, the off-diagonal entries of every third column given in
// the upper triangle instead and every diagonal entry split into two summands (MA27 accepts
// either triangle and adds duplicates).
Triplets to_triplets(const MatX& a) {
  Triplets t;
  t.n = static_cast<int>(a.rows());
  for (int c = 0; c < t.n; ++c)
    for (int r = c; r < t.n; ++r) {
      if (a(r, c) == 0.0) continue;
      const bool upper = r != c && c % 3 == 0;
      const int parts = r == c ? 2 : 1;
      for (int p = 0; p < parts; ++p) {
        t.row.push_back((upper ? c : r) + 1);
        t.col.push_back((upper ? r : c) + 1);
        t.value.push_back(a(r, c) / parts);
      }
    }
  return t;
}

struct Factorised {
  int iflag = 0;  // of the factorisation (INFO(1))
  int info2 = 0;
  int negative = 0;
  std::vector<double> a;
  std::vector<int> iw;
};

// Analysis then factorisation, with LA and LIW as Ipopt sizes them (5 x INFO(5), 5 x INFO(6)),
// or as given.
Factorised factorise(const Triplets& t, int la_override = -1, int liw_override = -1) {
  int n = t.n, nz = static_cast<int>(t.value.size()), nsteps = 0, iflag = 0, maxfrt = 0;
  int icntl[30], info[20];
  double cntl[5], ops = 0.0;
  ma27::init(icntl, cntl);
  std::vector<int> iw0(2 * nz + 3 * n + 1), ikeep(3 * n), iw1(2 * n);
  int liw0 = static_cast<int>(iw0.size());
  ma27::analyse(&n, &nz, t.row.data(), t.col.data(), iw0.data(), &liw0, ikeep.data(), iw1.data(), &nsteps, &iflag,
                icntl, cntl, info, &ops);
  REQUIRE(iflag == 0);
  int la = la_override >= 0 ? la_override : std::max(nz, 5 * info[4]);
  int liw = liw_override >= 0 ? liw_override : 5 * info[5];
  Factorised f;
  f.a.assign(static_cast<std::size_t>(la), 0.0);
  f.iw.assign(static_cast<std::size_t>(liw), 0);
  std::copy(t.value.begin(), t.value.end(), f.a.begin());
  ma27::factorise(&n, &nz, t.row.data(), t.col.data(), f.a.data(), &la, f.iw.data(), &liw, ikeep.data(), &nsteps,
                  &maxfrt, iw1.data(), icntl, cntl, info);
  f.iflag = info[0];
  f.info2 = info[1];
  f.negative = info[14];
  return f;
}

VecX solve(Factorised& f, int n, const VecX& b) {
  VecX x = b;
  int la = static_cast<int>(f.a.size()), liw = static_cast<int>(f.iw.size()), maxfrt = 1, nsteps = 1;
  int icntl[30], iw1[1];
  double cntl[5], w[1];
  ma27::solve(&n, f.a.data(), &la, f.iw.data(), &liw, w, &maxfrt, x.data(), iw1, &nsteps, icntl, cntl);
  return x;
}

// An interior-point KKT matrix [H + D, J^T; J, -delta I]: H dense symmetric (indefinite when
// `indefinite_h`), J m x n.
MatX kkt_matrix(int n, int m, bool indefinite_h, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  MatX b(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) b(i, j) = u(gen);
  MatX h = b.transpose() * b + 0.1 * MatX::Identity(n, n);
  if (indefinite_h) h -= 2.0 * MatX::Identity(n, n);
  MatX k = MatX::Zero(n + m, n + m);
  k.topLeftCorner(n, n) = h;
  for (int r = 0; r < m; ++r)
    for (int c = 0; c < 3; ++c) {  // a contact row: a few entries
      const int col = (3 * r + c) % n;
      k(n + r, col) = k(col, n + r) = u(gen);
    }
  k.bottomRightCorner(m, m) = -1e-8 * MatX::Identity(m, m);
  return k;
}

int negative_eigenvalues(const MatX& a) {
  const VecX lambda = symmetric_eigenvalues(a);
  return static_cast<int>((lambda.array() < 0.0).count());
}

}  // namespace

TEST_CASE("dense KKT solver: solves and counts the negative eigenvalues of symmetric indefinite matrices", "[ipopt]") {
  for (const bool indefinite_h : {false, true})
    for (const auto& [n, m] : std::vector<std::pair<int, int>>{{1, 0}, {12, 5}, {40, 25}, {90, 60}}) {
      INFO("n " << n << " m " << m << " indefinite H " << indefinite_h);
      const MatX k = kkt_matrix(n, m, indefinite_h, static_cast<unsigned>(7 * n + m));
      const Triplets t = to_triplets(k);
      Factorised f = factorise(t);
      REQUIRE(f.iflag == 0);
      CHECK(f.negative == negative_eigenvalues(k));
      if (!indefinite_h) CHECK(f.negative == m);  // Ipopt's "correct inertia": m negative
      std::mt19937 gen(3);
      std::uniform_real_distribution<double> u(-1.0, 1.0);
      VecX b(n + m);
      for (int i = 0; i < n + m; ++i) b(i) = u(gen);
      const VecX x = solve(f, n + m, b);
      CHECK((k * x - b).norm() <= 1e-9 * (k.norm() * x.norm() + b.norm()));
      // The values Ipopt gave stay where it put them (a refactorisation after a CALL_AGAIN reads them).
      for (std::size_t e = 0; e < t.value.size(); ++e) CHECK(f.a[e] == t.value[e]);
    }
}

TEST_CASE("dense KKT solver: a singular matrix is a rank deficiency, and too small workspaces ask for more",
          "[ipopt]") {
  // Two equal constraint rows without regularisation: rank n + m - 1.
  MatX k = kkt_matrix(10, 4, false, 11);
  k.bottomRightCorner(4, 4).setZero();
  k.row(13) = k.row(12);
  k.col(13) = k.col(12);
  const Triplets singular = to_triplets(k);
  const Factorised f = factorise(singular);
  CHECK(f.iflag == 3);
  CHECK(f.info2 == 13);

  const Triplets t = to_triplets(kkt_matrix(10, 4, false, 12));
  const int need = static_cast<int>(t.value.size()) + 14 * 14;
  const Factorised small_a = factorise(t, need - 1, -1);
  CHECK(small_a.iflag == -4);
  CHECK(small_a.info2 == need);
  const Factorised small_iw = factorise(t, -1, 14);
  CHECK(small_iw.iflag == -3);
  CHECK(small_iw.info2 == 15);
  CHECK(factorise(t, need, 15).iflag == 0);  // exactly what they asked for is enough
}

TEST_CASE("dense KKT solver: an index out of range is reported by the analysis", "[ipopt]") {
  Triplets t = to_triplets(kkt_matrix(5, 2, false, 1));
  t.row[3] = 8;
  int n = t.n, nz = static_cast<int>(t.value.size()), nsteps = 0, iflag = 0, liw = 100;
  int icntl[30], info[20];
  double cntl[5], ops = 0.0;
  std::vector<int> iw(100), ikeep(3 * n), iw1(2 * n);
  ma27::init(icntl, cntl);
  ma27::analyse(&n, &nz, t.row.data(), t.col.data(), iw.data(), &liw, ikeep.data(), iw1.data(), &nsteps, &iflag, icntl,
                cntl, info, &ops);
  CHECK(iflag == 1);
  CHECK(info[1] == 4);
}
