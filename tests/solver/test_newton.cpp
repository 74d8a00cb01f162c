// The one Newton (solver/newton.hpp) on small systems with known solutions: a potential with the
// energy merit, unsymmetric equations without a potential with the residual merit, the rate of
// convergence of both, the round-off floor, and the full steps the residual merit takes where
// its line search finds no acceptable point.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "roller/solver/newton.hpp"

using namespace roller;

namespace {

constexpr Index kN = 6;

// r(x) = A x + x.^3 - b with a tridiagonal A (unsymmetric when `skew` != 0). With skew = 0 it is
// the gradient of Pi = x'Ax/2 + sum x^4/4 - b'x, a convex potential.
class CubicSystem : public NewtonObjective {
 public:
  explicit CubicSystem(Real skew) : skew_(skew) {}
  Real roundoff_floor = 0.0;
  bool trial_points_fail = false;  // a test double: only the iterates (with a Jacobian) can be evaluated
  int evaluations = 0;

  Expected<ObjectiveValue> evaluate(const VecX& x, VecX* r, SparseMatrix* j) override {
    ++evaluations;
    if (!j && trial_points_fail) return Unexpected{"a trial point"};
    const SparseMatrix a = matrix();
    const VecX b = VecX::Ones(kN);
    *r = a * x + x.array().cube().matrix() - b;
    if (j) {
      *j = a;
      for (Index i = 0; i < kN; ++i) j->coeffRef(i, i) += 3.0 * x(i) * x(i);
    }
    ObjectiveValue v;
    v.value = 0.5 * x.dot(a * x) + 0.25 * x.array().pow(4).sum() - b.dot(x);
    v.force_scale = 1.0;
    v.roundoff_floor = roundoff_floor;
    v.symmetric = skew_ == 0.0;
    return v;
  }

 private:
  SparseMatrix matrix() const {
    std::vector<Eigen::Triplet<Real>> t;
    for (Index i = 0; i < kN; ++i) {
      t.emplace_back(i, i, 4.0);
      if (i + 1 < kN) {
        t.emplace_back(i, i + 1, -1.0 + skew_);
        t.emplace_back(i + 1, i, -1.0 - skew_);
      }
    }
    SparseMatrix a(kN, kN);
    a.setFromTriplets(t.begin(), t.end());
    return a;
  }
  Real skew_;
};

// Quadratic convergence: each residual at most C times the square of the one before, over the
// iterations where the residual is well above round-off.
void check_quadratic(const std::vector<Real>& history) {
  REQUIRE(history.size() >= 3);
  int checked = 0;
  for (std::size_t k = 1; k + 1 < history.size(); ++k) {
    if (history[k] > 0.1 || history[k + 1] < 1e-13) continue;
    CHECK(history[k + 1] <= 5.0 * history[k] * history[k]);
    ++checked;
  }
  CHECK(checked >= 1);
}

// Newton from x = `start` in every component; x ends at the last iterate.
NewtonReport solve(CubicSystem& system, Real start, NewtonMerit merit, Real tolerance, VecX& x) {
  x = VecX::Constant(kN, start);
  NewtonOptions options;
  options.residual_tolerance = tolerance;
  NewtonMinimiser newton;
  return newton.minimise(system, x, options, merit);
}

Real residual_norm(CubicSystem& system, const VecX& x) {
  VecX r;
  REQUIRE(system.evaluate(x, &r, nullptr));
  return r.norm();
}

}  // namespace

TEST_CASE("newton: the energy merit minimises a convex potential, converging quadratically", "[newton]") {
  CubicSystem system(0.0);
  VecX x;
  const NewtonReport report = solve(system, 3.0, NewtonMerit::Energy, 1e-13, x);
  REQUIRE(report.converged());
  CHECK_FALSE(report.at_roundoff_floor);
  CHECK(residual_norm(system, x) <= 1e-13);
  check_quadratic(report.residual_history);
}

TEST_CASE("newton: the residual merit solves unsymmetric equations without a potential, quadratically", "[newton]") {
  CubicSystem system(0.8);
  VecX x;
  const NewtonReport report = solve(system, 2.0, NewtonMerit::Residual, 1e-13, x);
  REQUIRE(report.converged());
  CHECK(residual_norm(system, x) <= 1e-13);
  check_quadratic(report.residual_history);
  // One LU factorisation per iteration: the Jacobian says it is unsymmetric.
  CHECK(report.counters.factorizations == report.counters.iterations);
}

TEST_CASE("newton: a residual at the round-off floor counts as converged, and says so", "[newton]") {
  CubicSystem system(0.0);
  system.roundoff_floor = 1e-3;
  VecX x;
  const NewtonReport report = solve(system, 3.0, NewtonMerit::Residual, 1e-12, x);
  REQUIRE(report.converged());
  CHECK(report.at_roundoff_floor);
  CHECK(report.residual_history.back() <= 1e-3);
  CHECK(report.residual > 1e-12);
}

TEST_CASE("newton: where the line search finds no point, the residual merit takes full steps, a few in a row",
          "[newton]") {
  CubicSystem unsymmetric(0.5);
  unsymmetric.trial_points_fail = true;
  VecX x;
  {
    // Near the solution a few full Newton steps converge.
    const NewtonReport report = solve(unsymmetric, 0.3, NewtonMerit::Residual, 1e-10, x);
    REQUIRE(report.converged());
    CHECK(report.counters.iterations <= NewtonMinimiser::kMaxFullStepsInARow);
    CHECK(report.line_search_cuts == 20 * report.counters.iterations);
  }
  {
    // Far from it, the solve stops after kMaxFullStepsInARow full steps.
    const NewtonReport report = solve(unsymmetric, 50.0, NewtonMerit::Residual, 1e-10, x);
    CHECK(report.status == Termination::LimitReached);
    CHECK(report.counters.iterations == NewtonMinimiser::kMaxFullStepsInARow);
    CHECK_THAT(report.message, Catch::Contains("no decrease of the residual"));
  }
  {
    // The energy merit has no full steps: it stops at the first direction.
    CubicSystem potential(0.0);
    potential.trial_points_fail = true;
    const NewtonReport report = solve(potential, 0.3, NewtonMerit::Energy, 1e-10, x);
    CHECK(report.status == Termination::Failed);
    CHECK(report.counters.iterations == 0);
    CHECK_THAT(report.message, Catch::Contains("no decrease of the incremental energy"));
  }
}
