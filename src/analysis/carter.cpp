#include "roller/analysis/carter.hpp"

#include <cmath>

#include <fmt/format.h>

#include "roller/core/error.hpp"

namespace roller {

Real CarterTraction::ratio() const {
  const Real r = stick_half_width / hertz.half_width;
  return std::copysign(1.0 - r * r, creep);
}

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
  const Real q = friction * (hertz.pressure(x) - stick_relief().pressure(x - stick_centre()));
  return creep < 0.0 ? -q : q;
}

CarterTraction carter_traction(const HertzSolution& hertz, Real creep, Real radius, Real friction) {
  if (!std::isfinite(creep)) throw InputError(fmt::format("Carter's traction: the creep {} is not finite", creep));
  if (creep != 0.0 && !(friction > 0.0))
    throw InputError(fmt::format(
        "Carter's traction: rolling with creep {} needs a friction coefficient > 0 (contact.friction), not {}", creep,
        friction));
  CarterTraction t;
  t.hertz = hertz;
  t.friction = friction;
  t.creep = creep;
  if (creep == 0.0) {  // free rolling: the whole contact sticks and carries no traction
    t.stick_half_width = hertz.half_width;
    return t;
  }
  t.stick_half_width = std::max(0.0, hertz.half_width - std::abs(creep) * radius / friction);
  return t;
}

std::vector<Real> carter_nodal_forces(const CarterTraction& t, const std::vector<Real>& x) {
  std::vector<Real> q = hertz_nodal_forces(t.hertz, x);
  if (t.stick_half_width > 0.0) {
    std::vector<Real> shifted;
    for (const Real xi : x) shifted.push_back(xi - t.stick_centre());
    const std::vector<Real> relief = hertz_nodal_forces(t.stick_relief(), shifted);
    for (std::size_t i = 0; i < q.size(); ++i) q[i] -= relief[i];
  }
  for (Real& f : q) f *= t.creep < 0.0 ? -t.friction : t.friction;
  return q;
}

}  // namespace roller
