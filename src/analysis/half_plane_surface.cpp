#include "roller/analysis/half_plane_surface.hpp"

#include <cmath>

#include "roller/core/error.hpp"

namespace roller {

Real EllipticLoad::at(Real x) const {
  const Real xi = (x - centre) / half_width;
  return std::abs(xi) < 1.0 ? peak * std::sqrt(1.0 - xi * xi) : 0.0;
}

Vec4 half_plane_surface_stress(Real x, const EllipticLoad& pressure, const std::vector<EllipticLoad>& shears) {
  const Real p = pressure.at(x);
  Vec4 s(-p, -p, 0.0, 0.0);
  for (const EllipticLoad& t : shears) {
    const Real xi = (x - t.centre) / t.half_width;
    // (1/pi) PV int_{-1}^{1} sqrt(1 - u^2)/(xi - u) du
    const Real hilbert = std::abs(xi) <= 1.0 ? xi : xi - std::copysign(std::sqrt(xi * xi - 1.0), xi);
    s[0] -= 2.0 * t.peak * hilbert;
    s[3] += t.at(x);
  }
  return s;
}

EllipticLoad elliptic_fit(const std::vector<Real>& x, const std::vector<Real>& f, const std::vector<Real>& l) {
  ROLLER_ASSERT(x.size() == f.size() && x.size() == l.size(), "one force and length per point");
  Real total = 0.0, first = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) total += f[i], first += f[i] * x[i];
  EllipticLoad e;
  if (!(total > 0.0)) return e;
  e.centre = first / total;
  Real second = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i)
    second += f[i] * ((x[i] - e.centre) * (x[i] - e.centre) - l[i] * l[i] / 12.0);
  e.half_width = 2.0 * std::sqrt(second / total);
  e.peak = 2.0 * total / (M_PI * e.half_width);
  return e;
}

}  // namespace roller
