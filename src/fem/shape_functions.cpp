#include "roller/fem/shape_functions.hpp"

#include <array>
#include <cmath>

#include <fmt/format.h>

#include "roller/core/error.hpp"

namespace roller {

int n_integration_points(ElementType t) { return t == ElementType::T3 ? 1 : 4; }

namespace {

struct ReferencePoint {
  Real xi, eta, weight;
};

// Natural-coordinate shape values and derivatives (columns d/dxi, d/deta).
void reference_shape(ElementType t, const ReferencePoint& p, NodeValues& n, NodeGradients& dn) {
  if (t == ElementType::T3) {
    n.resize(3);
    dn.resize(3, 2);
    n << 1.0 - p.xi - p.eta, p.xi, p.eta;
    dn << -1.0, -1.0, 1.0, 0.0, 0.0, 1.0;
    return;
  }
  static constexpr std::array<Real, 4> xs{-1, 1, 1, -1};
  static constexpr std::array<Real, 4> ys{-1, -1, 1, 1};
  n.resize(4);
  dn.resize(4, 2);
  for (int a = 0; a < 4; ++a) {
    n(a) = 0.25 * (1 + xs[a] * p.xi) * (1 + ys[a] * p.eta);
    dn(a, 0) = 0.25 * xs[a] * (1 + ys[a] * p.eta);
    dn(a, 1) = 0.25 * ys[a] * (1 + xs[a] * p.xi);
  }
}

const std::vector<ReferencePoint>& rule(ElementType t) {
  static const std::vector<ReferencePoint> t3{{1.0 / 3.0, 1.0 / 3.0, 0.5}};
  static const Real g = 1.0 / std::sqrt(3.0);
  static const std::vector<ReferencePoint> q4{{-g, -g, 1.0}, {g, -g, 1.0}, {g, g, 1.0}, {-g, g, 1.0}};
  return t == ElementType::T3 ? t3 : q4;
}

}  // namespace

std::vector<PointGeometry> element_geometry(ElementType t, const std::vector<Vec2>& coordinates, Index element_id) {
  std::vector<PointGeometry> out;
  element_geometry(t, coordinates, element_id, out);
  return out;
}

void element_geometry(ElementType t, const std::vector<Vec2>& coordinates, Index element_id,
                      std::vector<PointGeometry>& out) {
  const auto& points = rule(t);
  out.resize(points.size());
  NodeGradients dn;
  for (std::size_t q = 0; q < points.size(); ++q) {
    PointGeometry& g = out[q];
    reference_shape(t, points[q], g.shape, dn);
    Mat2 jac = Mat2::Zero();  // J_ij = dX_i / dxi_j
    for (Index a = 0; a < g.shape.size(); ++a) jac += coordinates[a] * dn.row(a);
    const Real det = jac.determinant();
    if (!(det > 0.0)) {
      throw NumericalError(
          fmt::format("element {} is inverted or degenerate (det J = {:.3e} at integration point {}); "
                      "the step is too large for the mesh: use smaller steps (a larger steps.count, or steps.max_cuts) "
                      "or a finer mesh",
                      element_id, det, q));
    }
    g.gradients = dn * jac.inverse();
    g.weight = det * points[q].weight;
  }
}

}  // namespace roller
