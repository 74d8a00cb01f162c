#include "roller/analysis/pass_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

#include "roller/core/error.hpp"
#include "roller/core/json_vectors.hpp"

namespace roller {

namespace {

// Depth of maximum shear under a Hertz line contact, in contact half-widths (Johnson, Contact
// Mechanics, 4.2: tau_1 max at z = 0.78 a).
constexpr Real kMaxShearDepth = 0.78;
constexpr Real kWindowDepth = 4.0;  // window depth in a

Real area(const Mesh& mesh, Index e) {
  const auto& n = mesh.elements[e];
  Real twice = 0.0;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const Vec2& p = mesh.nodes[n[i]];
    const Vec2& q = mesh.nodes[n[(i + 1) % n.size()]];
    twice += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * std::abs(twice);
}

Real mean_plastic_strain(const StripModel& strip, Index e) {
  Real sum = 0.0;
  for (int q = 0; q < strip.points_per_element(); ++q) sum += strip.state(e, q).eq_plastic_strain;
  return sum / strip.points_per_element();
}

Real mean_shear_strain(const StripModel& strip, Index e) {
  Real sum = 0.0;
  const std::vector<Vec4> strain = strip.total_strain(e);
  for (const Vec4& s : strain) sum += s(3);
  return sum / static_cast<Real>(strain.size());
}

// Area-weighted mean over the elements where `inside` holds.
template <class Inside, class Value>
Real weighted_mean(const Mesh& mesh, Inside inside, Value value) {
  Real sum = 0.0, weight = 0.0;
  for (Index e = 0; e < mesh.n_elements(); ++e) {
    if (!inside(e)) continue;
    const Real w = area(mesh, e);
    sum += w * value(e);
    weight += w;
  }
  return weight > 0.0 ? sum / weight : 0.0;
}

}  // namespace

void PassTrack::observe(Real centre_x, const std::vector<Real>& contact_x, const std::vector<Real>& contact_pressure,
                        Real step_load_half_width) {
  if (contact_x.empty()) return;
  x_min = touched ? std::min(x_min, centre_x) : centre_x;
  x_max = touched ? std::max(x_max, centre_x) : centre_x;
  touched = true;
  const auto [lo, hi] = std::minmax_element(contact_x.begin(), contact_x.end());
  half_width = std::max(half_width, 0.5 * (*hi - *lo));
  load_half_width = std::max(load_half_width, step_load_half_width);
  for (Real p : contact_pressure) peak_pressure = std::max(peak_pressure, p);
}

void PassTrack::observe_force(const Vec2& force_on_strip) {
  if (std::abs(force_on_strip.y()) <= std::abs(largest_force.y())) return;
  largest_force = force_on_strip;
}

void PassTrack::observe_motion(Real centre_x, Real angle, Real radius, bool in_contact) {
  if (has_pose && in_contact) rolled += centre_x - last_x, turned += radius * (angle - last_angle);
  has_pose = true, last_x = centre_x, last_angle = angle;
}

nlohmann::json PassTrack::save() const {
  return {{"touched", touched},
          {"x_min", x_min},
          {"x_max", x_max},
          {"half_width", half_width},
          {"load_half_width", load_half_width},
          {"peak_pressure", peak_pressure},
          {"largest_force", {largest_force.x(), largest_force.y()}},
          {"rolled", rolled},
          {"turned", turned},
          {"has_pose", has_pose},
          {"last_x", last_x},
          {"last_angle", last_angle}};
}

PassTrack PassTrack::load(const nlohmann::json& j) {
  PassTrack t;
  t.touched = j.at("touched").get<bool>();
  t.x_min = j.at("x_min").get<Real>();
  t.x_max = j.at("x_max").get<Real>();
  t.half_width = j.at("half_width").get<Real>();
  t.load_half_width = j.at("load_half_width").get<Real>();
  t.peak_pressure = j.at("peak_pressure").get<Real>();
  if (j.contains("largest_force"))  // absent in a state file written before it was kept
    t.largest_force = Vec2(j.at("largest_force").at(0).get<Real>(), j.at("largest_force").at(1).get<Real>());
  if (j.contains("rolled")) {  // absent in a state file written before the creep was kept
    t.rolled = j.at("rolled").get<Real>();
    t.turned = j.at("turned").get<Real>();
    t.has_pose = j.at("has_pose").get<bool>();
    t.last_x = j.at("last_x").get<Real>();
    t.last_angle = j.at("last_angle").get<Real>();
  }
  return t;
}

PassBaseline PassBaseline::of(const StripModel& strip) {
  PassBaseline b;
  const Index n = strip.mesh().n_elements();
  b.plastic_strain.resize(n);
  b.shear_strain.resize(n);
  for (Index e = 0; e < n; ++e) {
    b.plastic_strain[e] = mean_plastic_strain(strip, e);
    b.shear_strain[e] = mean_shear_strain(strip, e);
  }
  b.displacement = strip.total_displacement();
  return b;
}

nlohmann::json PassBaseline::save() const {
  return {{"plastic_strain", to_list(plastic_strain)},
          {"shear_strain", to_list(shear_strain)},
          {"displacement", to_list(displacement)}};
}

PassBaseline PassBaseline::load(const nlohmann::json& j) {
  PassBaseline b;
  b.plastic_strain = to_reals(j.at("plastic_strain"));
  b.shear_strain = to_reals(j.at("shear_strain"));
  b.displacement = to_vec(j.at("displacement"));
  return b;
}

PassRecord measure_pass(int pass, const StripModel& strip, Real strip_height, const PassTrack& track,
                        const PassBaseline& start) {
  PassRecord r;
  r.pass = pass;
  r.peak_pressure = track.peak_pressure;
  r.contact_half_width = track.half_width;
  r.creep = track.creep();
  const Mesh& mesh = strip.mesh();
  const Real a = track.load_half_width;
  // The window: the middle half of the rolled stretch, or all of it when that is short.
  const Real length = track.x_max - track.x_min;
  const Real inset = length > 4.0 * a ? 0.25 * length : 0.0;
  r.track_start = track.x_min + inset;
  r.track_end = track.x_max - inset;
  const Real x_mid = 0.5 * (track.x_min + track.x_max);
  // The mid-track surface node: the top node nearest x_mid in the initial mesh. A periodic strip's
  // track may pass its right edge: every x is taken at its image nearest the track's middle.
  auto near_track = [&](Real x) { return nearest_image_x(mesh, x, x_mid); };
  const std::vector<Index>& top = mesh.node_set("top");
  const Index surface = *std::min_element(top.begin(), top.end(), [&](Index p, Index q) {
    return std::abs(near_track(mesh.nodes[p].x()) - x_mid) < std::abs(near_track(mesh.nodes[q].x()) - x_mid);
  });
  const VecX& u = strip.total_displacement();
  r.surface_ux = u(2 * surface);
  r.surface_uy = u(2 * surface + 1);
  r.surface_dux = r.surface_ux - start.displacement(2 * surface);
  r.surface_duy = r.surface_uy - start.displacement(2 * surface + 1);
  r.shear_depth = kMaxShearDepth * a;
  if (!track.touched || a <= 0.0) return r;

  std::vector<Real> plastic_increment(mesh.n_elements()), depth(mesh.n_elements());
  std::vector<bool> in_window(mesh.n_elements());
  for (Index e = 0; e < mesh.n_elements(); ++e) {
    const Vec2 c = element_centroid(mesh, e);
    const Real x = near_track(c.x());
    depth[e] = strip_height - c.y();
    in_window[e] = x >= r.track_start && x <= r.track_end && depth[e] <= kWindowDepth * a;
    plastic_increment[e] = mean_plastic_strain(strip, e) - start.plastic_strain[e];
    if (in_window[e]) r.max_plastic_increment = std::max(r.max_plastic_increment, plastic_increment[e]);
  }
  r.mean_plastic_increment = weighted_mean(
      mesh, [&](Index e) { return in_window[e]; }, [&](Index e) { return plastic_increment[e]; });
  // The band at the depth of maximum shear: the window's elements whose centroid lies within a/4
  // of it.
  auto in_band = [&](Index e) { return in_window[e] && std::abs(depth[e] - r.shear_depth) <= 0.25 * a; };
  r.band_plastic_increment = weighted_mean(mesh, in_band, [&](Index e) { return plastic_increment[e]; });
  r.residual_shear_strain = weighted_mean(mesh, in_band, [&](Index e) { return mean_shear_strain(strip, e); });
  r.residual_shear_increment =
      r.residual_shear_strain - weighted_mean(mesh, in_band, [&](Index e) { return start.shear_strain[e]; });
  // The top row: the window's elements at its least depth (Kapoor's ratchetting surface layer).
  Real top_depth = std::numeric_limits<Real>::infinity();
  for (Index e = 0; e < mesh.n_elements(); ++e)
    if (in_window[e]) top_depth = std::min(top_depth, depth[e]);
  auto in_top_row = [&](Index e) { return in_window[e] && depth[e] <= top_depth + 1e-9 * strip_height; };
  r.surface_shear_increment =
      weighted_mean(mesh, in_top_row, [&](Index e) { return mean_shear_strain(strip, e) - start.shear_strain[e]; });
  return r;
}

std::vector<DepthSample> depth_profile(const StripModel& strip, Real strip_height, Real x) {
  const Mesh& mesh = strip.mesh();
  if (mesh.period > 0.0) {  // the image of x on the mesh
    const Real left = mesh.nodes[mesh.node_set("left").front()].x();
    x = nearest_image_x(mesh, x, left + 0.5 * mesh.period);
  }
  std::vector<DepthSample> out;
  for (Index e = 0; e < mesh.n_elements(); ++e) {
    Real lo = mesh.nodes[mesh.elements[e][0]].x(), hi = lo;
    for (Index a : mesh.elements[e]) {
      lo = std::min(lo, mesh.nodes[a].x());
      hi = std::max(hi, mesh.nodes[a].x());
    }
    if (x < lo || x >= hi) continue;
    DepthSample s;
    s.depth = strip_height - element_centroid(mesh, e).y();
    for (int q = 0; q < strip.points_per_element(); ++q) {
      const MaterialState& state = strip.state(e, q);
      s.stress += state.stress;
      for (const Vec4& alpha : state.back_stress) s.back_stress += alpha;
    }
    s.stress /= strip.points_per_element();
    s.back_stress /= strip.points_per_element();
    s.plastic_strain = mean_plastic_strain(strip, e);
    out.push_back(s);
  }
  std::sort(out.begin(), out.end(), [](const DepthSample& p, const DepthSample& q) { return p.depth < q.depth; });
  return out;
}

void PassCycles::observe(const StripModel& strip, Real strip_height) {
  const std::vector<DepthSample> column = depth_profile(strip, strip_height, x);
  if (depths.empty()) {
    for (const DepthSample& d : column) depths.push_back({d.depth, {}});
  }
  ROLLER_ASSERT(column.size() == depths.size(), "a column keeps its elements over a pass");
  for (std::size_t i = 0; i < column.size(); ++i) depths[i].stress.push_back(column[i].stress);
}

nlohmann::json PassCycles::save() const {
  nlohmann::json j;
  j["x"] = x;
  j["depths"] = nlohmann::json::array();
  for (const DepthCycle& d : depths) {
    std::vector<Real> flat;
    for (const Vec4& s : d.stress) flat.insert(flat.end(), s.data(), s.data() + 4);
    j["depths"].push_back({{"depth", d.depth}, {"stress", to_list(flat)}});
  }
  return j;
}

PassCycles PassCycles::load(const nlohmann::json& j) {
  PassCycles c;
  c.x = j.at("x").get<Real>();
  for (const nlohmann::json& d : j.at("depths")) {
    const std::vector<Real> flat = to_reals(d.at("stress"));
    DepthCycle cycle{d.at("depth").get<Real>(), {}};
    for (std::size_t k = 0; k + 3 < flat.size(); k += 4)
      cycle.stress.emplace_back(flat[k], flat[k + 1], flat[k + 2], flat[k + 3]);
    c.depths.push_back(std::move(cycle));
  }
  return c;
}

}  // namespace roller
