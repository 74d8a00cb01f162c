#include "roller/contact/contact_set.hpp"

#include <cmath>
#include <limits>

namespace roller {

namespace {

// Surface length each node of an ordered surface chain represents: half of each adjacent edge.
std::vector<Real> tributary_lengths(const std::vector<Vec2>& x, const std::vector<Index>& nodes) {
  std::vector<Real> l(nodes.size(), 0.0);
  for (std::size_t k = 0; k + 1 < nodes.size(); ++k) {
    const Real edge = (x[nodes[k + 1]] - x[nodes[k]]).norm();
    l[k] += 0.5 * edge;
    l[k + 1] += 0.5 * edge;
  }
  return l;
}

// Depth of the surface element under each node: distance to the nearest other node of the
// elements that contain it, measured along y (the strip's thickness direction), in the initial
// mesh. Not in the current configuration: once the surface deforms, neighbouring top nodes
// differ in y by micrometres and would pass for the element's depth (measured on Z1 after step
// 1: 1e-3 to 0.1 mm instead of 6.67 mm, i.e. penalties 50-5000x stiffer than the factor says).
std::vector<Real> element_depths(const StripModel& model, const std::vector<Index>& nodes) {
  const auto& x = model.mesh().nodes;
  std::vector<Real> depth(model.mesh().n_nodes(), std::numeric_limits<Real>::infinity());
  for (const auto& element : model.mesh().elements)
    for (Index a : element)
      for (Index b : element) {
        const Real dy = std::abs(x[a].y() - x[b].y());
        if (dy > 1e-12 * (1.0 + std::abs(x[a].y()))) depth[a] = std::min(depth[a], dy);
      }
  std::vector<Real> out;
  for (Index n : nodes) out.push_back(depth[n]);
  return out;
}

}  // namespace

std::vector<ContactCandidate> make_contact_candidates(const StripModel& model, const std::vector<Index>& nodes,
                                                      const VecX& prescribed, const VecX& predictor,
                                                      const Vec2& roller_end_centre, Real radius, Real reach) {
  const Mesh& mesh = model.mesh();
  std::vector<Vec2> x = model.current_coordinates();
  std::vector<Real> lengths = tributary_lengths(x, nodes);
  const std::vector<Real> depths = element_depths(model, nodes);
  // A periodic strip (docs/model.md, Periodic strip): a node of the right edge is its left edge's
  // node, which takes its share of the surface; every node is seen at its image nearest the roller.
  std::vector<Index> masters;
  if (mesh.period > 0.0) {
    masters = node_masters(mesh);
    for (std::size_t k = 0; k < nodes.size(); ++k)
      if (masters[nodes[k]] != nodes[k])
        for (std::size_t j = 0; j < nodes.size(); ++j)
          if (nodes[j] == masters[nodes[k]]) lengths[j] += lengths[k];
    for (const Index n : nodes) x[n].x() = nearest_image_x(mesh, x[n].x(), roller_end_centre.x());
  }
  const DofMap& dofs = model.dof_map();
  std::vector<ContactCandidate> out;
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const Index n = nodes[k];
    if (!masters.empty() && masters[n] != n) continue;
    if ((x[n] - roller_end_centre).norm() - radius > reach) continue;
    ContactCandidate c;
    c.node = n;
    c.position = x[n];
    for (int i = 0; i < 2; ++i) {
      c.free_dof[i] = dofs.free_index(2 * n + i);
      if (c.free_dof[i] < 0) c.prescribed(i) = prescribed(2 * n + i);
    }
    const Vec2 predicted = x[n] + Vec2(predictor(2 * n), predictor(2 * n + 1));
    const Vec2 normal = (predicted - roller_end_centre).normalized();
    c.tangent = Vec2(-normal.y(), normal.x());
    c.tributary_length = lengths[k];
    c.element_size = depths[k];
    out.push_back(c);
  }
  return out;
}

}  // namespace roller
