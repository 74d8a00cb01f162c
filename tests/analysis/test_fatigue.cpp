// The fatigue indices (analysis/fatigue.hpp) on cycles with closed forms, and the smallest
// enclosing ball against a brute force over every ball two to four points fix.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "roller/analysis/enclosing_ball.hpp"
#include "roller/analysis/fatigue.hpp"

using namespace roller;

namespace {

// Every ball through two points (as diameter), three (circumcircle) or four (circumsphere) that
// holds all the points; the least is the smallest enclosing ball.
Real brute_force_radius(const std::vector<Vec3>& p) {
  Real best = std::numeric_limits<Real>::infinity();
  auto consider = [&](const Vec3& c) {
    Real r = 0.0;
    for (const Vec3& x : p) r = std::max(r, (x - c).norm());
    best = std::min(best, r);
  };
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      consider(0.5 * (p[i] + p[j]));
      for (std::size_t k = j + 1; k < n; ++k) {
        const Vec3 u = p[j] - p[i], v = p[k] - p[i], w = u.cross(v);
        if (w.squaredNorm() > 1e-20)
          consider(p[i] + (v.squaredNorm() * w.cross(u) + u.squaredNorm() * v.cross(w)) / (2.0 * w.squaredNorm()));
        for (std::size_t l = k + 1; l < n; ++l) {
          Eigen::Matrix3d m;
          m.row(0) = u.transpose();
          m.row(1) = v.transpose();
          m.row(2) = (p[l] - p[i]).transpose();
          if (std::abs(m.determinant()) < 1e-12) continue;
          const Vec3 rhs(u.squaredNorm(), v.squaredNorm(), (p[l] - p[i]).squaredNorm());
          consider(p[i] + m.inverse() * (0.5 * rhs));
        }
      }
    }
  return best;
}

// A plane-strain stress [xx, yy, zz, xy] from a deviator's parts and a mean stress.
Vec4 stress(Real xx, Real yy, Real zz, Real xy) { return Vec4(xx, yy, zz, xy); }

}  // namespace

TEST_CASE("the smallest enclosing ball equals the brute force's, on general, coplanar and collinear sets",
          "[analysis][fatigue]") {
  std::mt19937 random(7);
  std::normal_distribution<Real> normal;
  for (int trial = 0; trial < 60; ++trial) {
    const int n = 2 + trial % 11;
    std::vector<Vec3> points;
    for (int i = 0; i < n; ++i) {
      Vec3 x(normal(random), normal(random), normal(random));
      if (trial % 3 == 1) x.z() = 0.5 * x.x() - 0.2 * x.y();  // coplanar
      if (trial % 3 == 2) x = Vec3(1.0, 2.0, -1.0) * x.x();   // collinear
      points.push_back(x);
    }
    if (trial % 5 == 0) points.push_back(points.front());  // a repeated point
    const Ball ball = smallest_enclosing_ball(points);
    INFO("trial " << trial << ", " << points.size() << " points");
    for (const Vec3& x : points) CHECK((x - ball.centre).norm() <= ball.radius * (1.0 + 1e-10) + 1e-14);
    CHECK(ball.radius == Approx(brute_force_radius(points)).epsilon(1e-9));
  }
}

TEST_CASE("Dang Van's index has its closed forms on proportional cycles", "[analysis][fatigue]") {
  const int n = 73;
  auto cycle = [&](const Vec4& mean, const Vec4& amplitude) {
    std::vector<Vec4> c;
    for (int i = 0; i < n; ++i) c.push_back(mean + std::sin(2.0 * M_PI * i / (n - 1)) * amplitude);
    return c;
  };
  SECTION("reversed shear tau_a: centre 0, radius tau_a, index tau_a / tau_w") {
    const DangVan dv = dang_van(cycle(Vec4::Zero(), stress(0, 0, 0, 150.0)), 0.3);
    CHECK(dv.centre.norm() < 1e-9);
    CHECK(dv.radius == Approx(150.0).epsilon(1e-12));
    CHECK(dv.value == Approx(150.0).epsilon(1e-12));
    CHECK(dv.hydrostatic == Approx(0.0).margin(1e-9));
  }
  SECTION("reversed tension at the tension limit: the index is 1 with a = 3 tau_w / sigma_w - 3/2") {
    // Dang Van's calibration (Tresca shear): at the peak tau = sigma/2, sigma_h = sigma/3.
    const Real sigma_w = 400.0, tau_w = 250.0, a = 3.0 * tau_w / sigma_w - 1.5;
    const DangVan dv = dang_van(cycle(Vec4::Zero(), stress(sigma_w, 0, 0, 0)), a);
    CHECK(dv.value / tau_w == Approx(1.0).epsilon(1e-12));
    CHECK(dv.shear == Approx(sigma_w / 2).epsilon(1e-12));
  }
  SECTION("a mean stress moves the centre to its deviator and adds its hydrostatic part") {
    const Vec4 mean = stress(120.0, -40.0, 30.0, 25.0), amplitude = stress(0, 0, 0, 100.0);
    const DangVan dv = dang_van(cycle(mean, amplitude), 0.25);
    const Real h = (120.0 - 40.0 + 30.0) / 3.0;
    CHECK((dv.centre - Vec4(120.0 - h, -40.0 - h, 30.0 - h, 25.0)).norm() < 1e-9);
    CHECK(dv.value == Approx(100.0 + 0.25 * h).epsilon(1e-12));
  }
  SECTION("Ekberg's subsurface index: half the longest chord, with the largest hydrostatic stress") {
    const EkbergSubsurface e = ekberg_subsurface(cycle(stress(-90.0, -90.0, -90.0, 0), stress(0, 0, 0, 150.0)), 0.3);
    CHECK(e.shear_amplitude == Approx(150.0).epsilon(1e-9));
    CHECK(e.max_hydrostatic == Approx(-90.0).epsilon(1e-12));
    CHECK(e.value == Approx(150.0 - 27.0).epsilon(1e-9));
  }
}

TEST_CASE("a rotating shear path is centred on its circle, which the mean cannot find", "[analysis][fatigue]") {
  // A path whose time mean is off its circle's centre (most samples on one side): the smallest
  // ball's centre is the circle's (the time mean, where code_aster's search starts, is not).
  std::vector<Vec4> path;
  for (int i = 0; i <= 40; ++i) {
    const Real t = M_PI * (i < 30 ? i / 60.0 : 0.5 + (i - 30) / 10.0 * 1.5);
    path.push_back(stress(80.0 * std::cos(t), -80.0 * std::cos(t), 0.0, 80.0 * std::sin(t)));
  }
  const DangVan dv = dang_van(path, 0.0);
  CHECK(dv.centre.norm() < 1e-9);
  CHECK(dv.radius == Approx(80.0).epsilon(1e-12));  // sqrt(J2) = sqrt((xx^2 + yy^2)/2 + xy^2)
}

TEST_CASE("the surface index, the ratchetting life and the governing depths", "[analysis][fatigue]") {
  CHECK(ekberg_surface(0.4, 2000.0, 400.0) == Approx(0.2));
  CHECK(ekberg_surface(-0.1, 2000.0, 400.0) == Approx(-0.1));
  CHECK(ratchetting_life(-2e-3, 11.0) == Approx(5500.0));
  CHECK(std::isinf(ratchetting_life(0.0, 11.0)));
  FatigueParams p{0.3, 200.0, 250.0, 11.0};
  std::string why;
  REQUIRE(p.is_valid(&why));
  std::vector<DepthCycle> cycles{{0.1, {stress(0, 0, 0, 100.0), stress(0, 0, 0, -100.0)}},
                                 {0.5, {stress(0, 0, 0, 300.0), stress(0, 0, 0, -300.0)}},
                                 {0.9, {stress(0, 0, 0, 50.0), stress(0, 0, 0, -50.0)}}};
  const PassFatigue f = pass_fatigue(p, 3, 100.0, cycles, {0.0, 2000.0, 400.0, -2e-3});
  REQUIRE(f.depths.size() == 3);
  CHECK(f.dang_van_row == 1);
  CHECK(f.depths[1].dang_van_index == Approx(300.0 / 200.0));
  CHECK(f.depths[1].subsurface_index == Approx(300.0 / 250.0));
  const FatigueAnswer a = answer_of(f);
  CHECK(a.dang_van_depth == 0.5);
  CHECK(a.ratchetting_life == Approx(5500.0));
  CHECK_THAT(describe(a), Catch::Contains("Dang Van 1.5 at 0.5 mm (initiates)") && Catch::Contains("FI_surf -0.2") &&
                              Catch::Contains("5.5e+03 passes"));
  p.dang_van_limit = 0.0;
  CHECK_FALSE(p.is_valid(&why));
  CHECK_THAT(why, Catch::Contains("fatigue.dang_van_limit = 0"));
}
