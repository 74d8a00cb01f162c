#pragma once
// McEwen's closed-form stresses of a half-plane under the Hertz pressure p0 sqrt(1 - x^2/a^2) and
// the sliding traction q = mu p (Johnson, Contact Mechanics, (7.5); a = 1, per unit p0), as the
// code's [xx, yy, zz, xy] with y vertical and zz = nu (xx + yy) out of plane (plane strain).
// z >= 0 is the depth. The same formulas as python/rollerpy/validation/line_contact_shakedown.py.
#include <cmath>

#include "roller/core/types.hpp"

namespace roller::test {

inline Vec4 mcewen_stress(Real x, Real z, Real mu, Real nu) {
  const Real r = 1.0 - x * x + z * z;
  const Real s = std::sqrt(r * r + 4.0 * x * x * z * z);
  const Real m = std::sqrt(std::max(0.5 * (s + r), 0.0));
  const Real n = (x > 0.0 ? 1.0 : x < 0.0 ? -1.0 : 0.0) * std::sqrt(std::max(0.5 * (s - r), 0.0));
  const Real d = std::max(m * m + n * n, 1e-300);
  Real sx = -(m * (1.0 + (z * z + n * n) / d) - 2.0 * z);
  Real sz = -m * (1.0 - (z * z + n * n) / d);
  Real t = n * (m * m - z * z) / d;
  sx += -mu * (n * (2.0 - (z * z - m * m) / d) - 2.0 * x);
  sz += mu * n * (m * m - z * z) / d;
  t += -mu * (m * (1.0 + (z * z + n * n) / d) - 2.0 * z);
  return Vec4(sx, sz, nu * (sx + sz), t);
}

}  // namespace roller::test
