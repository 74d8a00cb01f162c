// The rim's flattening and effective radius read off contact nodes (analysis/roller_flattening.hpp)
// on points of known circles.
#include <catch2/catch.hpp>

#include <cmath>

#include "roller/analysis/roller_flattening.hpp"

using namespace roller;

namespace {

// Nodes every 0.2 mm over |x| <= half, on a circle of `radius` about `centre`, touching unless
// |x| > touching.
std::vector<NodeContactRecord> on_circle(const Vec2& centre, Real radius, Real half, Real touching) {
  std::vector<NodeContactRecord> out;
  const int n = static_cast<int>(std::lround(2.0 * half / 0.2));
  for (int i = 0; i <= n; ++i) {
    const Real x = -half + 0.2 * i;
    NodeContactRecord c;
    c.position = centre + Vec2(x, -std::sqrt(radius * radius - x * x));
    c.contact.status = std::abs(x) <= touching ? ContactStatus::Stick : ContactStatus::Open;
    out.push_back(c);
  }
  return out;
}

}  // namespace

TEST_CASE("roller flattening: a flattened arc's radius and the rim's inward displacement", "[analysis]") {
  const Vec2 centre(50.0, 120.0);
  // The contact's nodes on a circle of 200 mm whose lowest point lies 0.05 mm inside a 100 mm roller.
  const Real flat = 0.05, r_eff = 200.0, radius = 100.0;
  const Vec2 arc_centre = centre + Vec2(0.0, -radius + flat + r_eff);
  const auto contact = on_circle(arc_centre, r_eff, 6.0, 3.0);
  const RollerFlattening f = roller_flattening(contact, centre, radius);
  REQUIRE(f.effective_radius);
  // A parabola through a circle's arc of half-width 3 mm: its x^4 term shifts the fit by ~(3/200)^2.
  CHECK(*f.effective_radius == Approx(r_eff).epsilon(1e-3));
  // The lowest node, straight below the centre, is the innermost.
  CHECK(f.flattening == Approx(flat).epsilon(1e-9));
}

TEST_CASE("roller flattening: an undeformed rim, too few nodes, no contact", "[analysis]") {
  const Vec2 centre(0.0, 100.0);
  const RollerFlattening rigid = roller_flattening(on_circle(centre, 100.0, 4.0, 2.0), centre, 100.0);
  REQUIRE(rigid.effective_radius);
  CHECK(*rigid.effective_radius == Approx(100.0).epsilon(1e-3));
  CHECK(rigid.flattening == Approx(0.0).margin(1e-12));
  const RollerFlattening one = roller_flattening(on_circle(centre, 100.0, 4.0, 0.1), centre, 100.0);
  CHECK_FALSE(one.effective_radius);  // one node in contact: no arc to fit
  const RollerFlattening three = roller_flattening(on_circle(centre, 100.0, 4.0, 0.25), centre, 100.0);
  REQUIRE(three.effective_radius);  // three nodes: a parabola through them
  CHECK(*three.effective_radius == Approx(100.0).epsilon(1e-3));
  const RollerFlattening none = roller_flattening(on_circle(centre, 100.0, 4.0, -1.0), centre, 100.0);
  CHECK_FALSE(none.effective_radius);
  CHECK(none.flattening == 0.0);
}
