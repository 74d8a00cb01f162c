#pragma once
// Basic numeric types shared by every module. Units throughout roller: mm, N, MPa, s
// (so density is in t/mm^3: steel 7.8e-9).
#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <cstdint>
#include <vector>

namespace roller {

using Real = double;
using Index = std::int64_t;

using Vec2 = Eigen::Matrix<Real, 2, 1>;
using Mat2 = Eigen::Matrix<Real, 2, 2>;
using Vec3 = Eigen::Matrix<Real, 3, 1>;
using VecX = Eigen::Matrix<Real, Eigen::Dynamic, 1>;
using MatX = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>;
using SparseMatrix = Eigen::SparseMatrix<Real, Eigen::ColMajor, int>;
using Triplet = Eigen::Triplet<Real, int>;

// Plane-strain stress and strain vectors carry four components in the order
// [xx, yy, zz, xy]. Stress components are tensor components; strain vectors use the
// engineering shear 2*E_xy in the last slot, so that stress . strain is the work density.
// The zz strain is zero in plane strain except where B-bar redistributes the volumetric part.
using Vec4 = Eigen::Matrix<Real, 4, 1>;
using Mat4 = Eigen::Matrix<Real, 4, 4>;

}  // namespace roller
