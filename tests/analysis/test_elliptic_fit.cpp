// The like-with-like fit of a semi-elliptic traction to nodal forces (analysis/elliptic_fit.hpp):
// exact work-equivalent forces give the ellipse back; the nodes' status extent and the fit of p^2
// to nodal pressures do not.
#include <catch2/catch.hpp>

#include <cmath>

#include "roller/analysis/contact_zones.hpp"
#include "roller/analysis/elliptic_fit.hpp"
#include "roller/analysis/hertz.hpp"

using namespace roller;

namespace {

// A graded chain: spacing 0.3 mm near x = 0 growing by 4 % a node outwards, to |x| <= 12 mm.
std::vector<Real> graded_chain() {
  std::vector<Real> right{0.0};
  Real h = 0.3;
  while (right.back() < 12.0) {
    right.push_back(right.back() + h);
    h *= 1.04;
  }
  std::vector<Real> x;
  for (auto it = right.rbegin(); it != right.rend(); ++it) x.push_back(-*it + 0.11);  // off-centre nodes
  for (std::size_t i = 1; i < right.size(); ++i) x.push_back(right[i] + 0.11);
  return x;
}

std::vector<Real> ellipse_forces(const std::vector<Real>& x, Real centre, Real half_width, Real peak) {
  std::vector<Real> shifted;
  for (Real xi : x) shifted.push_back(xi - centre);
  HertzSolution h;
  h.half_width = half_width;
  h.peak = peak;
  return hertz_nodal_forces(h, shifted);
}

}  // namespace

TEST_CASE("elliptic fit: an ellipse's work-equivalent nodal forces give its centre, half-width and peak back",
          "[analysis]") {
  const std::vector<Real> x = graded_chain();
  for (auto [centre, half_width, peak] : {std::tuple{0.0, 2.0, 2308.0}, {0.37, 1.413, 55.0}, {-0.8, 3.05, 1.0}}) {
    const std::vector<Real> f = ellipse_forces(x, centre, half_width, peak);
    const EllipticFit fit = fit_elliptic_forces(x, f);
    INFO("d " << fit.centre << " (" << centre << "), w " << fit.half_width << " (" << half_width << "), t0 " << fit.peak
              << " (" << peak << "), residual " << fit.residual);
    REQUIRE(fit.valid);
    CHECK(std::abs(fit.centre - centre) < 1e-6 * half_width);
    CHECK(fit.half_width == Approx(half_width).epsilon(1e-6));
    CHECK(fit.peak == Approx(peak).epsilon(1e-6));
    CHECK(fit.residual < 1e-8);
    // The loaded nodes' extent is off by up to half a spacing on each side (here 0.15 mm or more
    // against a 1.4-3 mm half-width), which this fit is meant to remove.
    std::vector<bool> loaded;
    for (Real fi : f) loaded.push_back(fi > 0.0);
    const Real extent = zone_extent(x, loaded).half_width();
    CHECK(std::abs(extent / half_width - 1.0) > 1e-3);
  }
}

TEST_CASE("elliptic fit: fewer than three loaded nodes, or none, is no fit", "[analysis]") {
  const std::vector<Real> x{-1.0, -0.5, 0.0, 0.5, 1.0};
  CHECK_FALSE(fit_elliptic_forces(x, {0.0, 0.0, 0.0, 0.0, 0.0}).valid);
  CHECK_FALSE(fit_elliptic_forces(x, {0.0, 1.0, 2.0, 0.0, 0.0}).valid);
  CHECK(fit_elliptic_forces(x, {0.0, 1.0, 2.0, 1.0, 0.0}).valid);
}
