#include "roller/analysis/roller_flattening.hpp"

#include <algorithm>

#include <Eigen/QR>

namespace roller {

RollerFlattening roller_flattening(const std::vector<NodeContactRecord>& contact, const Vec2& centre, Real radius,
                                   bool elastic) {
  RollerFlattening out;
  if (!elastic) {
    out.effective_radius = radius;
    return out;
  }
  std::vector<Vec2> touching;
  for (const NodeContactRecord& c : contact)
    if (c.contact.status != ContactStatus::Open) touching.push_back(c.position - centre);
  for (const Vec2& p : touching) out.flattening = std::max(out.flattening, radius - p.norm());
  if (touching.size() < 3) return out;
  // Least squares in (1, x, x^2), x scaled by the contact's half-extent for conditioning.
  Real scale = 0.0;
  for (const Vec2& p : touching) scale = std::max(scale, std::abs(p.x()));
  if (!(scale > 0.0)) return out;
  MatX a(touching.size(), 3);
  VecX y(touching.size());
  for (std::size_t i = 0; i < touching.size(); ++i) {
    const Real s = touching[i].x() / scale;
    a.row(static_cast<Index>(i)) << 1.0, s, s * s;
    y(static_cast<Index>(i)) = touching[i].y();
  }
  const VecX fit = a.colPivHouseholderQr().solve(y);
  const Real curvature = 2.0 * fit(2) / (scale * scale);  // y'' = 1 / R'
  if (curvature > 0.0) out.effective_radius = 1.0 / curvature;
  return out;
}

}  // namespace roller
