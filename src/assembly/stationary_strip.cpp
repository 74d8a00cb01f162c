#include "roller/assembly/stationary_strip.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <map>
#include <utility>

#include <fmt/format.h>

#include "roller/core/error.hpp"
#include "roller/material/j2_plasticity.hpp"

namespace roller {

namespace {

// Points closer in y than this fraction of the strip's smallest element height share a row.
constexpr Real kRowTolerance = 1e-6;
Real smallest_height(const Mesh& mesh) {
  Real h = std::numeric_limits<Real>::infinity();
  for (const auto& element : mesh.elements) {
    Real lo = std::numeric_limits<Real>::infinity(), hi = -lo;
    for (const Index a : element) lo = std::min(lo, mesh.nodes[a].y()), hi = std::max(hi, mesh.nodes[a].y());
    h = std::min(h, hi - lo);
  }
  return h;
}

}  // namespace

StationaryStrip::StationaryStrip(const Mesh& mesh, const ElementMaterials& materials, const ElementOptions& options,
                                 Real travel, int phases, int path_parts)
    : mesh_(mesh),
      materials_(materials),
      options_(options),
      path_parts_(path_parts),
      points_per_element_(n_integration_points(mesh.element_type)) {
  ROLLER_ASSERT(options.kinematics == Kinematics::Small, "the stationary strip is small-strain");
  geometry_.resize(mesh.n_elements());
  positions_.resize(mesh.n_elements() * points_per_element_);
  std::vector<Vec2> xe;
  for (Index e = 0; e < mesh.n_elements(); ++e) {
    xe.clear();
    for (const Index a : mesh.elements[e]) xe.push_back(mesh.nodes[a]);
    element_geometry(mesh.element_type, xe, e, geometry_[e]);
    for (int q = 0; q < points_per_element_; ++q) {
      Vec2 p = Vec2::Zero();
      for (std::size_t a = 0; a < xe.size(); ++a) p += geometry_[e][q].shape[static_cast<Index>(a)] * xe[a];
      positions_[e * points_per_element_ + q] = p;
    }
  }
  // Rows by y, and within a row one streamline per place in the element (docs/model.md,
  // "Streamlines"): a lane holds the same integration point of every element, so its strains follow
  // the field the way one material point's do in the transient pass; upstream first: the material
  // flows against the roller's travel.
  const Real tolerance = kRowTolerance * smallest_height(mesh);
  std::map<std::pair<long long, Index>, Streamline> rows;
  for (Index p = 0; p < n_points(); ++p) {
    Streamline& s = rows[{std::llround(positions_[p].y() / tolerance), p % points_per_element_}];
    s.y = positions_[p].y();
    s.points.push_back(p);
  }
  for (auto& [key, s] : rows) {
    std::sort(s.points.begin(), s.points.end(),
              [&](Index a, Index b) { return travel * positions_[a].x() > travel * positions_[b].x(); });
    for (std::size_t i = 1; i < s.points.size(); ++i)
      if (positions_[s.points[i]].x() == positions_[s.points[i - 1]].x())
        throw InputError(
            fmt::format("the stationary pass needs straight rows of integration points; element {} "
                        "shares a row position with another (use Q4 or T3 with one diagonal direction)",
                        s.points[i] / points_per_element_ + 1));
    // A lane's points lie on one side of their elements' centres, or its elements number their
    // corners otherwise than each other and the lane would zigzag between places.
    auto ahead = [&](Index p) {
      Real centre = 0.0;
      for (const Index a : mesh.elements[p / points_per_element_]) centre += mesh.nodes[a].x();
      return positions_[p].x() * static_cast<Real>(mesh.elements[p / points_per_element_].size()) > centre;
    };
    const bool first_ahead = ahead(s.points.front());
    for (const Index p : s.points)
      if (ahead(p) != first_ahead)
        throw InputError(fmt::format(
            "the stationary pass needs the elements of a row to number their corners alike; element {} "
            "puts its integration point {} on the other side of its centre from element {}'s",
            p / points_per_element_ + 1, p % points_per_element_ + 1, s.points.front() / points_per_element_ + 1));
    streamlines_.push_back(std::move(s));
  }
  streamline_of_.resize(n_points());
  for (std::size_t s = 0; s < streamlines_.size(); ++s)
    for (const Index p : streamlines_[s].points) streamline_of_[p] = static_cast<Index>(s);
  // The ends: the upstream one lies ahead of the roller, at the largest travel * x; each phase's
  // copy has its own (assembly/phased_strip.hpp), end_x() is the first copy's.
  ROLLER_ASSERT(phases >= 1 && mesh.n_nodes() % phases == 0 && mesh.n_elements() % phases == 0,
                "equal copies of the strip, one per phase");
  const Index copy_nodes = mesh.n_nodes() / phases, copy_elements = mesh.n_elements() / phases;
  for (int k = phases - 1; k >= 0; --k) {
    Real lo = mesh.nodes[k * copy_nodes].x(), hi = lo;
    for (Index a = k * copy_nodes; a < (k + 1) * copy_nodes; ++a)
      lo = std::min(lo, mesh.nodes[a].x()), hi = std::max(hi, mesh.nodes[a].x());
    end_x_[0] = travel > 0.0 ? hi : lo;
    end_x_[1] = travel > 0.0 ? lo : hi;
    for (int end = 0; end < 2; ++end) {
      auto on_end = [&](Index a) { return mesh.nodes[a].x() == end_x_[end]; };
      for (Index a = k * copy_nodes; a < (k + 1) * copy_nodes; ++a)
        if (on_end(a)) end_nodes_[end].push_back(a);
      for (Index e = k * copy_elements; e < (k + 1) * copy_elements; ++e)
        if (std::any_of(mesh.elements[e].begin(), mesh.elements[e].end(), on_end)) end_elements_[end].push_back(e);
    }
  }
  assemble_strain_operator();
}

void StationaryStrip::assemble_strain_operator() {
  std::vector<Eigen::Triplet<Real, int>> entries;
  for (Index e = 0; e < mesh_.n_elements(); ++e) {
    const auto& element = mesh_.elements[e];
    const Index n_local = 2 * static_cast<Index>(element.size());
    for (Index j = 0; j < n_local; ++j) {
      ElementVector unit = ElementVector::Zero(n_local);
      unit[j] = 1.0;
      const std::vector<Vec4> eps = element_strains(options_, mesh_.element_type, geometry_[e], unit);
      const auto dof = static_cast<int>(2 * element[static_cast<std::size_t>(j / 2)] + j % 2);
      for (int q = 0; q < points_per_element_; ++q)
        for (int c = 0; c < 4; ++c)
          if (eps[q][c] != 0.0)
            entries.emplace_back(static_cast<int>(4 * (e * points_per_element_ + q) + c), dof, eps[q][c]);
    }
  }
  strain_operator_.resize(static_cast<int>(4 * n_points()), static_cast<int>(mesh_.n_dofs()));
  strain_operator_.setFromTriplets(entries.begin(), entries.end());
}

std::vector<Vec4> StationaryStrip::strains(const VecX& u) const {
  std::vector<Vec4> out(n_points());
  Eigen::Map<VecX>(out.data()->data(), 4 * n_points()) = strain_operator_ * u;
  return out;
}

std::vector<Vec4> StationaryStrip::strains(const VecX& u, const std::vector<Index>& points) const {
  std::vector<Vec4> out;
  for (const Index p : points) out.push_back(strain_operator_.middleRows(4 * p, 4) * u);
  return out;
}

MaterialUpdate lane_step(const MaterialParams& m, const Vec4& step, const MaterialState& before, int parts) {
  MaterialUpdate update = update_material(m, step, before);
  if (update.yielded && parts > 1) {
    MaterialState walked = before;
    for (int i = 0; i < parts; ++i) walked = update_material(m, step / parts, walked).trial;
    update.trial = walked;
  }
  return update;
}

std::vector<MaterialState> StationaryStrip::sweep(const std::vector<Vec4>& strains,
                                                  const std::vector<MaterialState>& upstream,
                                                  SweepReport* report) const {
  ROLLER_ASSERT(upstream.size() == streamlines_.size(), "one upstream state per streamline");
  std::vector<MaterialState> out(n_points());
  Index yielded = 0;
  // The lanes are independent: one thread each at a time, dynamically, because the yielding lanes
  // take 17 return mappings a step and the others one. Each lane's states are the same whatever
  // thread sweeps it. An exception cannot leave an OpenMP loop: the first is kept and thrown after.
  std::exception_ptr failure;
  const auto n_lanes = static_cast<long>(streamlines_.size());
#pragma omp parallel for schedule(dynamic, 4) reduction(+ : yielded)
  for (long s = 0; s < n_lanes; ++s) {
    try {
      const MaterialState* state = &upstream[static_cast<std::size_t>(s)];
      Vec4 previous = Vec4::Zero();  // the upstream state carries no strain of this pass
      for (const Index p : streamlines_[static_cast<std::size_t>(s)].points) {
        const MaterialParams& m = materials_.of(p / points_per_element_);
        const MaterialUpdate update = lane_step(m, strains[p] - previous, *state, path_parts_);
        yielded += update.yielded ? 1 : 0;
        previous = strains[p];
        out[p] = update.trial;
        state = &out[p];
      }
    } catch (...) {
#pragma omp critical(roller_sweep_failure)
      if (!failure) failure = std::current_exception();
    }
  }
  if (failure) std::rethrow_exception(failure);
  if (report) report->n_yielded = yielded;
  return out;
}

VecX StationaryStrip::forces(const std::vector<MaterialState>& states) const {
  VecX weighted(4 * n_points());
  for (Index p = 0; p < n_points(); ++p)
    weighted.segment<4>(4 * p) = geometry_[p / points_per_element_][p % points_per_element_].weight * states[p].stress;
  return strain_operator_.transpose() * weighted;
}

std::vector<MaterialState> StationaryStrip::spread(const std::vector<MaterialState>& upstream) const {
  std::vector<MaterialState> out(n_points());
  for (Index p = 0; p < n_points(); ++p) out[p] = upstream[streamline_of_[p]];
  return out;
}

VecX StationaryStrip::end_forces(const std::vector<MaterialState>& states, End end) const {
  ROLLER_ASSERT(states.size() == streamlines_.size(), "one state per streamline");
  const int which = end == End::Upstream ? 0 : 1;
  VecX f = VecX::Zero(mesh_.n_dofs());
  std::array<Vec4, 4> stress;
  for (const Index e : end_elements_[which]) {
    for (int q = 0; q < points_per_element_; ++q)
      stress[q] = states[streamline_of_[e * points_per_element_ + q]].stress;
    const ElementVector fe = element_forces(options_, mesh_.element_type, geometry_[e], stress.data());
    const auto& element = mesh_.elements[e];
    for (std::size_t a = 0; a < element.size(); ++a) f.segment<2>(2 * element[a]) += fe.segment<2>(2 * a);
  }
  VecX out = VecX::Zero(mesh_.n_dofs());  // the end's nodes only: the elements' inner nodes are held inside
  for (const Index a : end_nodes_[which]) out.segment<2>(2 * a) = f.segment<2>(2 * a);
  return out;
}

VecX StationaryStrip::uniform_displacement(const std::vector<Vec4>& strains) const {
  ROLLER_ASSERT(strains.size() == streamlines_.size(), "one strain per streamline");
  // The node rows' heights, from the base up, and each row of elements' mean strain.
  const Real tolerance = kRowTolerance * smallest_height(mesh_);
  std::vector<Real> heights;
  for (const Vec2& x : mesh_.nodes) heights.push_back(x.y());
  std::sort(heights.begin(), heights.end());
  heights.erase(std::unique(heights.begin(), heights.end(), [&](Real a, Real b) { return b - a <= tolerance; }),
                heights.end());
  const std::size_t n_rows = heights.size() - 1;
  std::vector<Vec4> row_strain(n_rows, Vec4::Zero());
  std::vector<int> row_count(n_rows, 0);
  for (std::size_t s = 0; s < streamlines_.size(); ++s) {
    const auto above = std::upper_bound(heights.begin(), heights.end(), streamlines_[s].y);
    ROLLER_ASSERT(above != heights.begin() && above != heights.end(), "a streamline lies inside the strip");
    const std::size_t row = static_cast<std::size_t>(above - heights.begin()) - 1;
    row_strain[row] += strains[s];
    ++row_count[row];
  }
  // u at each node row, integrated from the base.
  std::vector<Vec2> column(heights.size(), Vec2::Zero());
  for (std::size_t j = 0; j < n_rows; ++j) {
    const Vec4 eps = row_count[j] > 0 ? Vec4(row_strain[j] / row_count[j]) : Vec4::Zero();
    column[j + 1] = column[j] + (heights[j + 1] - heights[j]) * Vec2(eps(3), eps(1));
  }
  VecX u = VecX::Zero(mesh_.n_dofs());
  for (Index a = 0; a < mesh_.n_nodes(); ++a) {
    const auto row = std::lower_bound(heights.begin(), heights.end(), mesh_.nodes[a].y() - tolerance);
    u.segment<2>(2 * a) = column[static_cast<std::size_t>(row - heights.begin())];
  }
  return u;
}

std::vector<MaterialState> StationaryStrip::virgin_upstream() const {
  std::vector<MaterialState> out;
  for (const Streamline& s : streamlines_)
    out.push_back(initial_state(materials_.of(s.points.front() / points_per_element_)));
  return out;
}

}  // namespace roller
