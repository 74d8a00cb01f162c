#include "roller/analysis/carter.hpp"

#include <cmath>

#include <fmt/format.h>

#include "roller/core/error.hpp"

namespace roller {

Real CarterTraction::stick_centre() const { return hertz.half_width - stick_half_width; }

bool CarterTraction::sticks(Real x) const { return std::abs(x - stick_centre()) < stick_half_width; }

HertzSolution CarterTraction::stick_relief() const {
  HertzSolution h;
  h.half_width = stick_half_width;
  h.peak = hertz.peak * stick_half_width / hertz.half_width;
  h.load = 0.5 * M_PI * h.half_width * h.peak;
  return h;
}

Real CarterTraction::traction(Real x) const {
  return direction() * friction * (hertz.pressure(x) - stick_relief().pressure(x - stick_centre()));
}

Real CarterTraction::elastic_creep(Real radius) const {
  return std::copysign(friction * hertz.half_width / radius * (1.0 - stick_half_width / hertz.half_width), ratio);
}

CarterTraction carter_traction(const HertzSolution& hertz, Real ratio, Real friction) {
  if (!std::isfinite(ratio)) throw InputError(fmt::format("Carter's traction: Q/P = {} is not finite", ratio));
  if (std::abs(ratio) > friction)
    throw InputError(
        fmt::format("Carter's traction: |Q/P| = {:.6g} exceeds the friction coefficient {}: the roller would slide",
                    std::abs(ratio), friction));
  CarterTraction t;
  t.hertz = hertz;
  t.friction = friction;
  t.ratio = ratio;
  t.stick_half_width =
      friction > 0.0 ? hertz.half_width * std::sqrt(1.0 - std::abs(ratio) / friction) : hertz.half_width;
  return t;
}

std::vector<Real> stick_relief_forces(const CarterTraction& t, const std::vector<Real>& x) {
  if (t.stick_half_width <= 0.0) return std::vector<Real>(x.size(), 0.0);
  std::vector<Real> shifted;
  for (const Real xi : x) shifted.push_back(xi - t.stick_centre());
  return hertz_nodal_forces(t.stick_relief(), shifted);
}

std::vector<Real> carter_nodal_forces(const CarterTraction& t, const std::vector<Real>& x) {
  std::vector<Real> q = hertz_nodal_forces(t.hertz, x);
  const std::vector<Real> relief = stick_relief_forces(t, x);
  for (std::size_t i = 0; i < q.size(); ++i) q[i] = t.direction() * t.friction * (q[i] - relief[i]);
  return q;
}

}  // namespace roller
