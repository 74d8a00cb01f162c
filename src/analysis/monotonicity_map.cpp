#include "roller/analysis/monotonicity_map.hpp"

#include <cmath>
#include <tuple>

#include <fmt/format.h>

#include "roller/core/error.hpp"

namespace roller {

namespace {

std::string axis_violation(const char* name, const GridAxis& axis, bool positive) {
  if (!(std::isfinite(axis.lo) && std::isfinite(axis.hi) && axis.lo <= axis.hi)) {
    return fmt::format("{} range [{}, {}]: needs finite lo <= hi", name, axis.lo, axis.hi);
  }
  if (axis.n < 1) return fmt::format("{} grid n = {}: needs n >= 1", name, axis.n);
  if (axis.n == 1 && axis.lo != axis.hi) {
    return fmt::format("{} range [{}, {}] with n = 1: needs lo = hi or n >= 2", name, axis.lo, axis.hi);
  }
  if (positive && !(axis.lo > 0.0)) {
    return fmt::format("{} range starts at {}: the yield stress must be > 0", name, axis.lo);
  }
  return {};
}

}  // namespace

MaterialParams MonotonicityMapOptions::material() const {
  MaterialParams m;
  m.youngs_modulus = youngs_modulus;
  m.poisson_ratio = poisson_ratio;
  m.plastic = true;
  m.yield_stress = sigma.lo;
  m.tangent_modulus = tangent_modulus;
  return m;
}

bool MonotonicityMapOptions::is_valid(std::string* why) const {
  std::string v;
  for (const auto& [name, axis, positive] : {std::tuple{"sigma_pl", sigma, true}, std::tuple{"a", a, false},
                                             std::tuple{"b", b, false}, std::tuple{"c", c, false}}) {
    v = axis_violation(name, axis, positive);
    if (!v.empty()) break;
  }
  if (v.empty()) material().is_valid(&v);
  if (v.empty() && !(std::isfinite(mass_scale) && mass_scale >= 0.0)) {
    v = fmt::format("mass_scale = {}: must be finite and >= 0", mass_scale);
  }
  if (why != nullptr) *why = v;
  return v.empty();
}

Mat4 map_operator(const MonotonicityMapOptions& options, Real sigma_pl, const ThesisParameters& p) {
  const MaterialParams material = options.material();
  OperatorOptions op;
  op.layout = options.layout;
  op.tangent = TangentKind::PlasticBranch;
  op.mass_scale = options.mass_scale;
  const Vec4 stress = stress_from_parameters(p, options.out_of_plane, options.poisson_ratio);
  return operator_a(material, stress, sigma_pl, op);
}

MapPoint evaluate_map_point(const MonotonicityMapOptions& options, Real sigma_pl, const ThesisParameters& p) {
  return {sigma_pl, p, definiteness(map_operator(options, sigma_pl, p))};
}

std::vector<MapPoint> sweep_grid(const MonotonicityMapOptions& options) {
  std::string why;
  if (!options.is_valid(&why)) throw InputError("monotonicity map: " + why);
  std::vector<MapPoint> out;
  out.reserve(static_cast<std::size_t>(options.sigma.n) * options.a.n * options.b.n * options.c.n);
  for (int is = 0; is < options.sigma.n; ++is)
    for (int ia = 0; ia < options.a.n; ++ia)
      for (int ib = 0; ib < options.b.n; ++ib)
        for (int ic = 0; ic < options.c.n; ++ic) {
          const ThesisParameters p{options.a.value(ia), options.b.value(ib), options.c.value(ic)};
          out.push_back(evaluate_map_point(options, options.sigma.value(is), p));
        }
  return out;
}

std::string MapSlice::describe() const {
  switch (plane) {
    case SlicePlane::AB: return fmt::format("(a,b) plane, c = {:g} MPa", fixed);
    case SlicePlane::CA: return fmt::format("(c,a) plane, b = {:g} MPa", fixed);
    case SlicePlane::CB: return fmt::format("(c,b) plane, a = {:g} MPa", fixed);
  }
  return "?";
}

std::vector<MapSlice> thesis_slices() {
  return {{"a", SlicePlane::AB, 0.0},   {"b", SlicePlane::AB, -5.0},  {"c", SlicePlane::AB, -10.0},
          {"d", SlicePlane::AB, -15.0}, {"e", SlicePlane::AB, -20.0}, {"f", SlicePlane::AB, 10.0},
          {"g", SlicePlane::CA, 0.0},   {"h", SlicePlane::CA, -75.0}, {"i", SlicePlane::CA, -105.0},
          {"j", SlicePlane::CA, 105.0}, {"k", SlicePlane::CB, 0.0},   {"l", SlicePlane::CB, -75.0}};
}

std::vector<MapPoint> sweep_slice(const MonotonicityMapOptions& options, const MapSlice& slice, Real sigma_pl,
                                  int n_first, int n_second) {
  std::string why;
  if (!options.is_valid(&why)) throw InputError("monotonicity map: " + why);
  if (n_first < 2 || n_second < 2) {
    throw InputError(fmt::format("monotonicity slice: {} x {} points, needs >= 2 per axis", n_first, n_second));
  }
  if (!(sigma_pl > 0.0)) {
    throw InputError(fmt::format("monotonicity slice: sigma_pl = {}, needs > 0", sigma_pl));
  }
  const GridAxis first{slice.plane == SlicePlane::CB ? options.b.lo : options.a.lo,
                       slice.plane == SlicePlane::CB ? options.b.hi : options.a.hi, n_first};
  const GridAxis second{slice.plane == SlicePlane::AB ? options.b.lo : options.c.lo,
                        slice.plane == SlicePlane::AB ? options.b.hi : options.c.hi, n_second};
  std::vector<MapPoint> out;
  out.reserve(static_cast<std::size_t>(n_first) * n_second);
  for (int i = 0; i < n_first; ++i)
    for (int j = 0; j < n_second; ++j) {
      const Real x = first.value(i), y = second.value(j);
      ThesisParameters p;
      switch (slice.plane) {
        case SlicePlane::AB: p = {x, y, slice.fixed}; break;
        case SlicePlane::CA: p = {x, slice.fixed, y}; break;
        case SlicePlane::CB: p = {slice.fixed, x, y}; break;
      }
      out.push_back(evaluate_map_point(options, sigma_pl, p));
    }
  return out;
}

}  // namespace roller
