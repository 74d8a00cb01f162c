#include "roller/io/scene_warnings.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "roller/analysis/hertz.hpp"
#include "roller/contact/roller.hpp"
#include "roller/core/error.hpp"
#include "roller/io/roller_start.hpp"

namespace roller {

namespace {

// The spacing of the top surface's nodes around x (the element size the contact meets) [mm].
Real surface_spacing_at(const Mesh& mesh, Real x) {
  const std::vector<Index>& top = mesh.node_set("top");
  Real spacing = 0.0, distance = 0.0;
  bool found = false;
  for (std::size_t k = 0; k + 1 < top.size(); ++k) {
    const Vec2 a = mesh.nodes[top[k]], b = mesh.nodes[top[k + 1]];
    const Real d = std::abs(0.5 * (a.x() + b.x()) - x);
    if (!found || d < distance) {
      spacing = std::abs(b.x() - a.x());
      distance = d;
      found = true;
    }
  }
  return spacing;
}

// The contact's half-width the scene will reach, from Hertz's line contact: under the largest
// prescribed force, else for the deepest press (the chord half-width of a press d, sqrt(2 R d),
// over sqrt(2): Hertz's width for that depth is about that); nullopt without either.
std::optional<Real> expected_half_width(const Scene& scene) {
  const RollerSpec& roller = *scene.roller;
  const Real e_star = scene.contact_modulus();
  Real force = 0.0, depth = 0.0, y = 0.0;
  for (const PathSegment& seg : roller.path) {
    if (seg.fy) force = std::max(force, *seg.fy);
    y += seg.fy ? 0.0 : seg.dy;
    depth = std::max(depth, -y);
  }
  if (force > 0.0) return hertz_line_contact(force, roller.radius, e_star).half_width;
  if (depth > 0.0) return std::sqrt(roller.radius * depth);
  return std::nullopt;
}

}  // namespace

void check_load_fits_strip(const Scene& scene) {
  if (!scene.roller) return;
  const Real e_star = scene.contact_modulus();
  const Real length = scene.mesh.length;
  for (std::size_t i = 0; i < scene.roller->path.size(); ++i) {
    const std::optional<Real> fy = scene.roller->path[i].fy;
    if (!fy || !(*fy > 0.0)) continue;
    const Real a = hertz_line_contact(*fy, scene.roller->radius, e_star).half_width;
    if (!(2.0 * a >= length)) continue;
    const MaterialParams surface = scene.strip_material().surface();
    const std::string roller_modulus = scene.roller->elastic()
                                           ? fmt::format(" and the roller's E = {:g} MPa (nu = {:g})",
                                                         scene.roller->youngs_modulus, scene.roller->poisson_ratio)
                                           : std::string();
    throw InputError(fmt::format(
        "{}: roller.path[{}].fy = {:g} N/mm on the top surface's E = {:g} MPa (nu = {:g}){} makes a Hertz contact "
        "2a = {:.4g} mm wide, wider than the strip (mesh.length = {:g} mm): the load would not fit on it. A modulus "
        "in Pa or GPa, or a force in N rather than N/mm? roller works in mm, N/mm and MPa (steel: E = 2.1e5 MPa)",
        scene.file.string(), i, *fy, surface.youngs_modulus, surface.poisson_ratio, roller_modulus, 2.0 * a, length));
  }
}

void check_traction_below_friction(const Scene& scene) {
  if (!scene.roller) return;
  const RollerSpec& roller = *scene.roller;
  const auto mu_source = [](const PathSegment& seg, std::size_t i) {
    return seg.friction ? fmt::format("roller.path[{}].friction", i) : std::string("contact.friction");
  };
  for (std::size_t i = 0; i < roller.path.size(); ++i) {
    const PathSegment& seg = roller.path[i];
    const Real mu = seg.friction.value_or(scene.contact.friction);
    if (seg.q_over_p && std::abs(*seg.q_over_p) > mu)
      throw InputError(fmt::format(
          "{}: roller.path[{}].q_over_p = {:g} exceeds the segment's friction coefficient mu = {:g} ({}): friction "
          "carries at most mu times the normal force, so the roller would slide; expected |q_over_p| <= mu, or "
          "slip = 1 for a sliding roller (q = mu p)",
          scene.file.string(), i, *seg.q_over_p, mu, mu_source(seg, i)));
    if (!seg.fx) continue;
    // Both forces are linear over a segment, so its ends decide; the vertical force may come from
    // an earlier segment (held) or be unknown (dy: motion), and then friction is the run's to find.
    const PrescribedForce end = prescribed_force(roller, seg.last_step);
    if (!end.fy || !end.fx || std::abs(*end.fx) <= mu * *end.fy) continue;
    throw InputError(fmt::format(
        "{}: roller.path[{}].fx = {:g} N/mm exceeds mu = {:g} ({}) times the vertical force fy = {:g} N/mm at step "
        "{}: friction carries at most {:g} N/mm, so the roller would slide without a steady state; expected "
        "|fx| <= mu fy, or slip = 1 for a sliding roller (q = mu p)",
        scene.file.string(), i, *seg.fx, mu, mu_source(seg, i), *end.fy, seg.last_step, mu * *end.fy));
  }
}

std::vector<std::string> scene_warnings(const Scene& scene, const Mesh& mesh) {
  std::vector<std::string> out;
  const std::string file = scene.file.string();
  std::vector<std::pair<std::string, MaterialParams>> bands{{"material", scene.material}};
  for (std::size_t i = 0; i < scene.layers.size(); ++i)
    bands.emplace_back(fmt::format("layer[{}]", i), scene.layers[i].material);
  // A yield stress above 5 % of E: no metal comes near it (steels 0.1-0.8 %); legal, as an extreme
  // contrast of layers may mean it.
  constexpr Real kLargestYieldOverModulus = 0.05;
  for (const auto& [table, m] : bands) {
    if (m.plastic && m.yield_stress > kLargestYieldOverModulus * m.youngs_modulus)
      out.push_back(fmt::format(
          "{}: {}.yield_stress = {:g} MPa is {:.3g} of {}.E = {:g} MPa, above any metal's (steels 0.001-0.008): a "
          "yield stress in Pa, or E in GPa? roller works in MPa (steel: E = 2.1e5, yield_stress 250 to 1500)",
          file, table, m.yield_stress, m.yield_stress / m.youngs_modulus, table, m.youngs_modulus));
    else if (m.youngs_modulus < 1e3 && m.plastic && m.yield_stress > 10.0)
      out.push_back(
          fmt::format("{}: {}.E = {:g} MPa with {}.yield_stress = {:g} MPa: E looks like GPa; "
                      "roller works in MPa (steel: E = 2.1e5)",
                      file, table, m.youngs_modulus, table, m.yield_stress));
  }
  if (!scene.roller) return out;
  const Real x = given_start_centre(scene).x();
  const Real h = surface_spacing_at(mesh, x);
  const Real radius = scene.roller->radius;
  if (radius < h)
    out.push_back(
        fmt::format("{}: roller.radius = {:g} mm is smaller than the element under it ({:.3g} mm): a radius "
                    "in metres? roller works in mm",
                    file, radius, h));
  // A contact as wide as a good part of the strip: its ends carry the load (a force in N, not N/mm?).
  if (const std::optional<Real> a = expected_half_width(scene); a && 2.0 * *a > scene.mesh.length / 3.0)
    out.push_back(
        fmt::format("{}: the contact will be about {:.3g} mm wide (Hertz 2a for the path's largest load or press), "
                    "more than a third of the strip's mesh.length = {:g} mm: the strip's ends will carry part of "
                    "the load. A force in N rather than N/mm, or a modulus too small? roller works in mm, N/mm and "
                    "MPa",
                    file, 2.0 * *a, scene.mesh.length));
  // Nodes within the contact width 2a: 2a/h + 1 on average.
  if (const std::optional<Real> a = expected_half_width(scene); a && h > 0.0 && 2.0 * *a / h + 1.0 < 4.0)
    out.push_back(
        fmt::format("{}: the contact will span about {:.1f} nodes (Hertz half-width a = {:.3g} mm for the "
                    "path's load or press, element size {:.3g} mm under the roller): pressures and stick/slip "
                    "zones need at least 4; refine the mesh there (mesh.refine, mesh.x_lines)",
                    file, 2.0 * *a / h + 1.0, *a, h));
  return out;
}

}  // namespace roller
