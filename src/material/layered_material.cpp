#include "roller/material/layered_material.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace roller {

Real YieldProfile::at(Real depth) const {
  if (points.empty()) return 0.0;
  if (depth <= points.front().first) return points.front().second;
  if (depth >= points.back().first) return points.back().second;
  // First point deeper than `depth`: the interval [k-1, k] holds it.
  const auto it = std::upper_bound(points.begin(), points.end(), depth,
                                   [](Real d, const std::pair<Real, Real>& p) { return d < p.first; });
  const auto& [d1, s1] = *it;
  const auto& [d0, s0] = *(it - 1);
  const Real t = (depth - d0) / (d1 - d0);
  return s0 + t * (s1 - s0);
}

bool YieldProfile::is_valid(std::string* why) const {
  auto bad = [why](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  for (std::size_t k = 0; k < points.size(); ++k) {
    const auto [depth, sigma] = points[k];
    if (!(std::isfinite(depth) && depth >= 0.0))
      return bad(
          fmt::format("yield_profile[{}]: depth {} mm: expected a finite depth >= 0 (from the top surface)", k, depth));
    if (k > 0 && !(depth > points[k - 1].first))
      return bad(fmt::format("yield_profile[{}]: depth {} mm after depth {} mm: expected strictly increasing depths", k,
                             depth, points[k - 1].first));
    if (!(std::isfinite(sigma) && sigma > 0.0))
      return bad(fmt::format("yield_profile[{}]: yield stress {} MPa: expected a finite value > 0", k, sigma));
  }
  return true;
}

MaterialAtDepth LayeredMaterial::at_depth(Real depth) const {
  MaterialAtDepth out{base, static_cast<int>(layers.size())};
  bool follows = true;
  Real bottom = 0.0;
  for (std::size_t i = 0; i < layers.size(); ++i) {
    bottom += layers[i].thickness;
    if (depth < bottom) {
      out = {layers[i].material, static_cast<int>(i)};
      follows = layers[i].follows_profile;
      break;
    }
  }
  if (follows && !yield_profile.empty() && out.material.plastic) out.material.yield_stress = yield_profile.at(depth);
  return out;
}

std::vector<Real> LayeredMaterial::boundaries() const {
  std::vector<Real> out;
  Real bottom = 0.0;
  for (const MaterialLayer& l : layers) out.push_back(bottom += l.thickness);
  return out;
}

bool LayeredMaterial::any_plastic() const {
  return base.plastic ||
         std::any_of(layers.begin(), layers.end(), [](const MaterialLayer& l) { return l.material.plastic; });
}

Real LayeredMaterial::max_poisson_ratio() const {
  Real nu = base.poisson_ratio;
  for (const MaterialLayer& l : layers) nu = std::max(nu, l.material.poisson_ratio);
  return nu;
}

}  // namespace roller
