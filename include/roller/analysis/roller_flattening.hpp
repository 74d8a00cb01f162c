#pragma once
// How an elastic roller's rim flattens in its contact, read off the contact nodes' deformed
// positions (they lie on the deformed rim: their gap is zero). For a Hertz contact of two elastic
// bodies the rim inside the contact is a circle of radius R' = R (1 + E'_strip / E'_roller), E' the
// plane-strain moduli (docs/model.md, Elastic roller): Hitchcock's flattened roll radius of the
// rolling-mill literature, here for the line contact of two half-planes.
#include <optional>
#include <vector>

#include "roller/contact/contact_records.hpp"

namespace roller {

struct RollerFlattening {
  // The rim's largest inward radial displacement over the contact, R - min |x - c| [mm]; 0 without
  // contact.
  Real flattening = 0.0;
  // The radius of the parabola y = y0 + b x + x^2 / (2 R') fitted (least squares) through the
  // contact nodes relative to the centre [mm]; none with fewer than 3 nodes in contact or a fit
  // that is not convex.
  std::optional<Real> effective_radius;
};

// `contact`: the nodes of a solved contact (their positions deformed); `centre`, `radius`: the
// roller's centre and undeformed radius; `elastic`: false for a rigid roller, whose rim does not
// deform (0 and its radius, with or without contact).
RollerFlattening roller_flattening(const std::vector<NodeContactRecord>& contact, const Vec2& centre, Real radius,
                                   bool elastic = true);

}  // namespace roller
