#include "roller/analysis/fatigue.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "roller/analysis/enclosing_ball.hpp"
#include "roller/core/error.hpp"

namespace roller {

namespace {

Real hydrostatic(const Vec4& s) { return (s(0) + s(1) + s(2)) / 3.0; }

Vec4 deviator(const Vec4& s) {
  const Real h = hydrostatic(s);
  return {s(0) - h, s(1) - h, s(2) - h, s(3)};
}

// A plane-strain deviator (three independent components) as a point of R^3 whose Euclidean norm
// is sqrt(s:s): ((xx - yy)/sqrt2, sqrt(3/2) zz, sqrt2 xy); and back.
Vec3 coordinates(const Vec4& s) {
  return {(s(0) - s(1)) / std::sqrt(2.0), std::sqrt(1.5) * s(2), std::sqrt(2.0) * s(3)};
}
Vec4 deviator_at(const Vec3& y) {
  const Real zz = y(1) / std::sqrt(1.5);
  const Real difference = std::sqrt(2.0) * y(0);  // xx - yy
  const Real sum = -zz;                           // xx + yy
  return {0.5 * (sum + difference), 0.5 * (sum - difference), zz, y(2) / std::sqrt(2.0)};
}

// The cycle's deviators as points of R^3 (coordinates above), after checking it has finite samples.
std::vector<Vec3> deviatoric_path(const std::vector<Vec4>& cycle, const char* who) {
  require(!cycle.empty(), fmt::format("{}: the stress cycle has no sample", who));
  std::vector<Vec3> path;
  path.reserve(cycle.size());
  for (const Vec4& s : cycle) {
    if (!s.allFinite()) throw NumericalError(fmt::format("{}: a stress of the cycle is not finite", who));
    path.push_back(coordinates(deviator(s)));
  }
  return path;
}

}  // namespace

bool FatigueParams::is_valid(std::string* why) const {
  auto fail = [&](const char* key, Real value, const char* rule) {
    if (why) *why = fmt::format("fatigue.{} = {:g}: {}", key, value, rule);
    return false;
  };
  if (!(std::isfinite(dang_van_a) && dang_van_a >= 0.0))
    return fail("dang_van_a", dang_van_a, "must be finite and >= 0 (the hydrostatic stress's weight, ~0.3 for steels)");
  if (!(std::isfinite(dang_van_limit) && dang_van_limit > 0.0))
    return fail("dang_van_limit", dang_van_limit, "must be finite and > 0 [MPa] (the shear fatigue limit tau_w)");
  if (!(std::isfinite(shear_fatigue_limit) && shear_fatigue_limit > 0.0))
    return fail("shear_fatigue_limit", shear_fatigue_limit, "must be finite and > 0 [MPa] (Ekberg's tau_e)");
  if (!(std::isfinite(critical_shear_strain) && critical_shear_strain > 0.0))
    return fail("critical_shear_strain", critical_shear_strain,
                "must be finite and > 0 (the shear strain that exhausts the ductility, e.g. 11 for a rail steel)");
  if (why) why->clear();
  return true;
}

Real tresca_shear(const Vec4& t) {
  const Real mean = 0.5 * (t(0) + t(1));
  const Real r = std::hypot(0.5 * (t(0) - t(1)), t(3));
  const Real hi = std::max(mean + r, t(2)), lo = std::min(mean - r, t(2));
  return 0.5 * (hi - lo);
}

DangVan dang_van(const std::vector<Vec4>& cycle, Real a) {
  const Ball ball = smallest_enclosing_ball(deviatoric_path(cycle, "dang_van"));
  DangVan out;
  out.centre = deviator_at(ball.centre);
  out.radius = ball.radius / std::sqrt(2.0);  // sqrt(J2) = |s| / sqrt2
  out.value = -std::numeric_limits<Real>::infinity();
  for (std::size_t i = 0; i < cycle.size(); ++i) {
    const Real tau = tresca_shear(deviator(cycle[i]) - out.centre);
    const Real h = hydrostatic(cycle[i]);
    if (tau + a * h > out.value) out = {out.centre, out.radius, tau + a * h, tau, h, static_cast<int>(i)};
  }
  return out;
}

EkbergSubsurface ekberg_subsurface(const std::vector<Vec4>& cycle, Real a) {
  const std::vector<Vec3> path = deviatoric_path(cycle, "ekberg_subsurface");
  Real chord = 0.0;  // the longest, in |s|
  for (std::size_t i = 0; i < path.size(); ++i)
    for (std::size_t j = i + 1; j < path.size(); ++j) chord = std::max(chord, (path[i] - path[j]).squaredNorm());
  EkbergSubsurface out;
  out.shear_amplitude = 0.5 * std::sqrt(chord) / std::sqrt(2.0);  // half the chord, in sqrt(J2)
  out.max_hydrostatic = -std::numeric_limits<Real>::infinity();
  for (const Vec4& s : cycle) out.max_hydrostatic = std::max(out.max_hydrostatic, hydrostatic(s));
  out.value = out.shear_amplitude + a * out.max_hydrostatic;
  return out;
}

Real ekberg_surface(Real traction_coefficient, Real p0, Real shear_yield) {
  require(p0 > 0.0, "ekberg_surface: the peak pressure p0 must be > 0");
  return std::abs(traction_coefficient) - shear_yield / p0;
}

Real ratchetting_life(Real shear_strain_per_pass, Real critical_shear_strain) {
  const Real rate = std::abs(shear_strain_per_pass);
  return rate > 0.0 ? critical_shear_strain / rate : std::numeric_limits<Real>::infinity();
}

PassFatigue pass_fatigue(const FatigueParams& p, int pass, Real x, const std::vector<DepthCycle>& cycles,
                         const PassSurface& surface) {
  PassFatigue out;
  out.pass = pass;
  out.x = x;
  out.surface = surface;
  // No contact in the pass: no surface load, an index of minus infinity.
  out.surface_index = surface.peak_pressure > 0.0
                          ? ekberg_surface(surface.traction_coefficient, surface.peak_pressure, surface.shear_yield)
                          : -std::numeric_limits<Real>::infinity();
  out.ratchetting_life = ratchetting_life(surface.shear_strain_per_pass, p.critical_shear_strain);
  for (const DepthCycle& c : cycles) {
    if (c.stress.empty()) continue;
    FatigueAtDepth d;
    d.depth = c.depth;
    d.dang_van = dang_van(c.stress, p.dang_van_a);
    d.dang_van_index = d.dang_van.value / p.dang_van_limit;
    d.subsurface = ekberg_subsurface(c.stress, p.dang_van_a);
    d.subsurface_index = d.subsurface.value / p.shear_fatigue_limit;
    const int row = static_cast<int>(out.depths.size());
    if (out.dang_van_row < 0 || d.dang_van_index > out.depths[out.dang_van_row].dang_van_index) out.dang_van_row = row;
    if (out.subsurface_row < 0 || d.subsurface_index > out.depths[out.subsurface_row].subsurface_index)
      out.subsurface_row = row;
    out.depths.push_back(d);
  }
  return out;
}

FatigueAnswer answer_of(const PassFatigue& f) {
  FatigueAnswer a;
  a.pass = f.pass;
  if (f.dang_van_row >= 0) {
    a.dang_van_index = f.depths[f.dang_van_row].dang_van_index;
    a.dang_van_depth = f.depths[f.dang_van_row].depth;
  }
  if (f.subsurface_row >= 0) {
    a.subsurface_index = f.depths[f.subsurface_row].subsurface_index;
    a.subsurface_depth = f.depths[f.subsurface_row].depth;
  }
  a.surface_index = f.surface_index;
  a.traction_coefficient = f.surface.traction_coefficient;
  a.peak_pressure = f.surface.peak_pressure;
  a.shear_yield = f.surface.shear_yield;
  a.shear_strain_per_pass = f.surface.shear_strain_per_pass;
  a.ratchetting_life = f.ratchetting_life;
  return a;
}

std::string describe(const FatigueAnswer& a) {
  auto says = [](bool initiates) { return initiates ? "initiates" : "below the limit"; };
  std::string life = std::isfinite(a.ratchetting_life)
                         ? fmt::format("{:.3g} passes to ratchetting failure (surface shear {:.3g} a pass)",
                                       a.ratchetting_life, a.shear_strain_per_pass)
                         : std::string("no surface ratchet");
  return fmt::format(
      "fatigue of pass {}: Dang Van {:.3g} at {:.3g} mm ({}), Ekberg FI_sub/tau_e {:.3g} at {:.3g} mm ({}), "
      "FI_surf {:.3g} (f = {:.3g}, k/p0 = {:.3g}: {}), {}",
      a.pass, a.dang_van_index, a.dang_van_depth, says(a.dang_van_index > 1.0), a.subsurface_index, a.subsurface_depth,
      says(a.subsurface_index > 1.0), a.surface_index, a.traction_coefficient,
      a.peak_pressure > 0.0 ? a.shear_yield / a.peak_pressure : 0.0, says(a.surface_index > 0.0), life);
}

}  // namespace roller
