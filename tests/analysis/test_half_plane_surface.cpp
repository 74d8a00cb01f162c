// The half-plane's surface stress of semi-elliptic tractions against McEwen's closed form
// (Johnson, Contact Mechanics (7.5); the test's mcewen.hpp, written independently from the
// subsurface field), and the ellipse recovered from nodal forces.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "../support/mcewen.hpp"
#include "roller/analysis/half_plane_surface.hpp"

using namespace roller;

TEST_CASE("the half-plane's surface stress of Hertz's pressure and q = mu p is McEwen's at z = 0",
          "[analysis][melan]") {
  for (const Real mu : {0.0, 0.25, 0.5}) {
    // McEwen's shear is -mu p (a = 1, p0 = 1): the traction's sigma_xy.
    const EllipticLoad pressure{0.0, 1.0, 1.0}, shear{0.0, 1.0, -mu};
    for (Real x = -4.0; x <= 4.0; x += 0.0625) {
      const Vec4 s = half_plane_surface_stress(x, pressure, {shear});
      const Vec4 m = test::mcewen_stress(x, 0.0, mu, 0.3);
      CHECK(s[0] == Approx(m[0]).margin(1e-9));
      CHECK(s[1] == Approx(m[1]).margin(1e-9));
      CHECK(s[3] == Approx(m[3]).margin(1e-9));
    }
    // The extremes of (sigma_xx - sigma_yy)/2 are +-mu p0, at the edges.
    CHECK(half_plane_surface_stress(1.0, pressure, {shear})[0] == Approx(2.0 * mu).margin(1e-12));
  }
  // Shifted and scaled: the same field in (x - m)/b, in units of the peak.
  const Vec4 s = half_plane_surface_stress(10.0 + 0.3 * 2.0, {10.0, 2.0, 500.0}, {{10.0, 2.0, -150.0}});
  const Vec4 m = test::mcewen_stress(0.3, 0.0, 0.3, 0.3) * 500.0;
  CHECK(s[0] == Approx(m[0]).epsilon(1e-12));
  CHECK(s[3] == Approx(m[3]).epsilon(1e-12));
}

TEST_CASE("an ellipse is recovered from its nodal forces", "[analysis][melan]") {
  // Work-equivalent nodal forces of p0 sqrt(1 - x^2/a^2), a = 2, at 10 nodes across a half-width.
  const Real a = 2.0, p0 = 2307.7, centre = 92.03, h = 0.2;
  std::vector<Real> x, f, l;
  for (int i = -20; i <= 20; ++i) {
    x.push_back(centre + i * h);
    Real force = 0.0;  // Simpson over the node's tributary length
    for (int k = 0; k <= 100; ++k) {
      const Real s = x.back() - h / 2 + h * k / 100.0;
      const Real w = (k == 0 || k == 100) ? 1.0 : (k % 2 ? 4.0 : 2.0);
      force += w * EllipticLoad{centre, a, p0}.at(s) * h / 300.0;
    }
    f.push_back(force);
    l.push_back(h);
  }
  const EllipticLoad fit = elliptic_fit(x, f, l);
  CHECK(fit.centre == Approx(centre).epsilon(1e-9));
  CHECK(fit.half_width == Approx(a).epsilon(5e-4));
  CHECK(fit.peak == Approx(p0).epsilon(5e-4));
}
