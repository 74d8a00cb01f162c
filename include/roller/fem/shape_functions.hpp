#pragma once
// Isoparametric T3 (1-point rule) and Q4 (2x2 Gauss) shape functions, and the per-integration-
// point geometry of an element in a given configuration.
#include <vector>

#include "roller/core/types.hpp"
#include "roller/mesh/mesh.hpp"

namespace roller {

int n_integration_points(ElementType t);

// Geometry of one integration point: shape values N_A, spatial gradients dN_A/dX (rows = nodes)
// with respect to the configuration whose coordinates were given, and the volume weight
// det(J) * w (volume per unit strip width).
// Sizes are bounded by the Q4's four nodes so no integration point allocates on the heap.
using NodeValues = Eigen::Matrix<Real, Eigen::Dynamic, 1, 0, 4, 1>;
using NodeGradients = Eigen::Matrix<Real, Eigen::Dynamic, 2, 0, 4, 2>;

struct PointGeometry {
  NodeValues shape;
  NodeGradients gradients;
  Real weight = 0.0;
};

// Throws NumericalError when an integration point has det(J) <= 0 (inverted element): the
// message names the element so the caller can report it and cut the step.
std::vector<PointGeometry> element_geometry(ElementType t, const std::vector<Vec2>& coordinates, Index element_id);
// The same into `out` (resized), for loops over every element that reuse one buffer.
void element_geometry(ElementType t, const std::vector<Vec2>& coordinates, Index element_id,
                      std::vector<PointGeometry>& out);

}  // namespace roller
