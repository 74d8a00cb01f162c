#include "pass_fatigue.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <utility>

#include <nlohmann/json.hpp>

#include "roller/analysis/hertz.hpp"
#include "roller/core/error.hpp"

namespace roller {

PassFatigue fatigue_of_pass(const Scene& scene, const PassRecord& record, Real x, const std::vector<DepthCycle>& cycles,
                            const Vec2& largest_force) {
  ROLLER_ASSERT(scene.fatigue && scene.roller, "fatigue indices need [fatigue] and a roller");
  PassSurface surface;
  const Real normal = std::abs(largest_force.y());
  surface.traction_coefficient = normal > 0.0 ? std::abs(largest_force.x()) / normal : 0.0;
  surface.peak_pressure =
      normal > 0.0 ? hertz_line_contact(normal, scene.roller->radius, scene.contact_modulus()).peak : 0.0;
  const MaterialParams top = scene.strip_material().surface();
  surface.shear_yield = top.plastic ? top.lowest_yield_stress() / std::sqrt(3.0) : 0.0;
  // Without plastic flow in the window the surface's shear change is round-off, not a ratchet.
  surface.shear_strain_per_pass = record.max_plastic_increment > 0.0 ? record.surface_shear_increment : 0.0;
  return pass_fatigue(*scene.fatigue, record.pass, x, cycles, surface);
}

std::vector<DepthCycle> framed(std::vector<DepthCycle> lanes, const std::vector<DepthSample>& before,
                               const std::vector<DepthSample>& after) {
  ROLLER_ASSERT(lanes.size() == before.size() && lanes.size() == after.size(),
                "a stationary pass has one row of lanes per element of the extraction column");
  for (std::size_t i = 0; i < lanes.size(); ++i) {
    ROLLER_ASSERT(std::abs(lanes[i].depth - before[i].depth) <= 1e-6 * (1.0 + lanes[i].depth),
                  "the lanes' rows and the column's elements lie at the same depths");
    lanes[i].stress.insert(lanes[i].stress.begin(), before[i].stress);
    lanes[i].stress.push_back(after[i].stress);
  }
  return lanes;
}

PassCycles start_cycles(const Scene& scene, const RollerProgram& program, int pass, const StripModel& strip) {
  const PathSegment* travel = travel_segment(*scene.roller);
  const Real before = static_cast<Real>((pass - 1) * scene.steps.n_steps);
  PassCycles c;
  c.x = travel ? 0.5 * (program.pose(before + travel->first_step - 1).centre.x() +
                        program.pose(before + travel->last_step).centre.x())
               : program.pass_start(pass).centre.x();
  c.observe(strip, scene.mesh.height);
  return c;
}

std::vector<VtuField> fatigue_cell_fields(const Mesh& mesh, Real strip_height, const PassFatigue& f, Real window_start,
                                          Real window_end) {
  const Index n = mesh.n_elements();
  VtuField dang_van{"dang_van_index", 1, std::vector<Real>(n, 0.0), {}};
  VtuField subsurface{"fi_sub_index", 1, std::vector<Real>(n, 0.0), {}};
  if (f.depths.empty()) return {dang_van, subsurface};
  for (Index e = 0; e < n; ++e) {
    const Vec2 c = element_centroid(mesh, e);
    if (c.x() < window_start || c.x() > window_end) continue;
    const Real depth = strip_height - c.y();
    // The depths are sorted: the nearest is at the first one at or below, or the one above it.
    auto it = std::lower_bound(f.depths.begin(), f.depths.end(), depth,
                               [](const FatigueAtDepth& d, Real z) { return d.depth < z; });
    if (it == f.depths.end() || (it != f.depths.begin() && depth - std::prev(it)->depth < it->depth - depth)) --it;
    dang_van.values[e] = it->dang_van_index;
    subsurface.values[e] = it->subsurface_index;
  }
  return {dang_van, subsurface};
}

namespace {

nlohmann::json finite_or_null(Real v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

}  // namespace

void to_json(nlohmann::json& j, const FatigueAnswer& a) {
  j = {{"pass", a.pass},
       {"dang_van_index", a.dang_van_index},
       {"dang_van_depth", a.dang_van_depth},
       {"subsurface_index", a.subsurface_index},
       {"subsurface_depth", a.subsurface_depth},
       {"surface_index", finite_or_null(a.surface_index)},
       {"traction_coefficient", a.traction_coefficient},
       {"peak_pressure", a.peak_pressure},
       {"shear_yield", a.shear_yield},
       {"shear_strain_per_pass", a.shear_strain_per_pass},
       {"ratchetting_life", finite_or_null(a.ratchetting_life)}};
}

void from_json(const nlohmann::json& j, FatigueAnswer& a) {
  a.pass = j.at("pass").get<int>();
  for (auto [key, field] : {std::pair{"dang_van_index", &a.dang_van_index},
                            {"dang_van_depth", &a.dang_van_depth},
                            {"subsurface_index", &a.subsurface_index},
                            {"subsurface_depth", &a.subsurface_depth},
                            {"traction_coefficient", &a.traction_coefficient},
                            {"peak_pressure", &a.peak_pressure},
                            {"shear_yield", &a.shear_yield},
                            {"shear_strain_per_pass", &a.shear_strain_per_pass}})
    *field = j.at(key).get<Real>();
  const nlohmann::json& surface = j.at("surface_index");
  a.surface_index = surface.is_null() ? -std::numeric_limits<Real>::infinity() : surface.get<Real>();
  const nlohmann::json& life = j.at("ratchetting_life");
  a.ratchetting_life = life.is_null() ? std::numeric_limits<Real>::infinity() : life.get<Real>();
}

}  // namespace roller
