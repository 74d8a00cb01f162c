// Anderson's acceleration (solver/anderson.hpp): on a linear fixed point it terminates like GMRES;
// its updated and downdated QR gives the least-squares combination a fresh factorisation gives;
// a repeated correction starts the history again.
#include <catch2/catch.hpp>

#include <cmath>
#include <deque>

#include <Eigen/QR>

#include "roller/solver/anderson.hpp"

using namespace roller;

namespace {

// g(u) = b - A u for a non-symmetric A close to the identity: u <- u + g(u) is Richardson's
// iteration for A u = b, which converges slowly (spectral radius of I - A near 0.95).
struct Linear {
  MatX a;
  VecX b;
  explicit Linear(int n) : a(MatX::Identity(n, n)), b(n) {
    for (int i = 0; i < n; ++i) {
      b[i] = std::cos(0.7 * i);
      a(i, i) = 0.05 + 0.9 * i / n;  // eigenvalues of A in [0.05, 0.95]
      if (i + 1 < n) a(i, i + 1) = 0.3;
    }
  }
  VecX g(const VecX& u) const { return b - a * u; }
};

// The same step with a fresh least-squares solve over the window's differences.
struct Reference {
  int depth;
  std::deque<VecX> du, dg;
  VecX last_u, last_g;
  VecX next(const VecX& u, const VecX& g) {
    if (last_u.size() == u.size()) {
      du.push_back(u - last_u);
      dg.push_back(g - last_g);
      if (static_cast<int>(du.size()) > depth) du.pop_front(), dg.pop_front();
    }
    last_u = u;
    last_g = g;
    VecX out = u + g;
    if (du.empty()) return out;
    MatX m(u.size(), static_cast<Index>(dg.size()));
    for (std::size_t j = 0; j < dg.size(); ++j) m.col(static_cast<Index>(j)) = dg[j];
    const VecX gamma = m.colPivHouseholderQr().solve(g);
    for (std::size_t j = 0; j < du.size(); ++j) out -= gamma[static_cast<Index>(j)] * (du[j] + dg[j]);
    return out;
  }
};

}  // namespace

TEST_CASE("Anderson: a linear fixed point in n unknowns is solved within n + 1 steps", "[solver]") {
  const int n = 12;
  const Linear problem(n);
  const VecX exact = problem.a.lu().solve(problem.b);
  Anderson anderson(n, 1e14);
  VecX u = VecX::Zero(n);
  for (int k = 0; k <= n + 1; ++k) u = anderson.next(u, problem.g(u));
  CHECK((u - exact).norm() <= 1e-8 * exact.norm());
  // Without the acceleration, n + 2 steps are far from it.
  VecX plain = VecX::Zero(n);
  for (int k = 0; k <= n + 1; ++k) plain += problem.g(plain);
  CHECK((plain - exact).norm() > 1e-2 * exact.norm());
}

TEST_CASE("Anderson: the updated QR gives a fresh least squares' iterates while the window slides", "[solver]") {
  const int n = 30, depth = 4;
  const Linear problem(n);
  Anderson anderson(depth, 1e14);
  Reference reference{depth, {}, {}, {}, {}};
  VecX u = VecX::Zero(n), v = VecX::Zero(n);
  for (int k = 0; k < 12; ++k) {  // 8 steps past the window's filling: 8 downdates
    u = anderson.next(u, problem.g(u));
    v = reference.next(v, problem.g(v));
    CHECK((u - v).norm() <= 1e-9 * v.norm());
    CHECK(anderson.columns() == std::min(k, depth));
  }
}

TEST_CASE("Anderson: a repeated correction starts the history again", "[solver]") {
  Anderson anderson(5);
  const VecX g = VecX::Constant(3, 1.0);
  VecX u = VecX::Zero(3);
  u = anderson.next(u, g);
  u = anderson.next(u, g);  // the same g: its difference is zero
  CHECK(anderson.columns() == 0);
  CHECK(u.isApprox(VecX::Constant(3, 2.0)));
}
