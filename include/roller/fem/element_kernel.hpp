#pragma once
// Plane-strain T3/Q4 element of the updated-Lagrangian strip (docs/model.md, Kinematics):
// (geometry in the configuration at the start of the increment, material, committed states,
//  element displacement increment) -> (energy, residual, tangent, trial states).
// No assembly and no solving happen here.
//
// Strain of the increment, with H = du/dX and F = I + H (X: start-of-increment configuration):
//   finite: E = 1/2 (H + H^T + H^T H)   (e + eta of the thesis)
//   small:  E = 1/2 (H + H^T)
// The element energy is  sum_q w_q W(E_q)  with W the material's incremental energy density,
// so residual = dEnergy/du = sum_q w_q B_q^T S_q with B_q = dE_q/du (B_L(u) of the thesis),
// and tangent = sum_q w_q (B_q^T C_q B_q + G_q), G_q = sum_ij S_ij d2E_ij/du2 the geometric
// (initial-stress) stiffness K_NL; G vanishes for small kinematics.
// B-bar (Q4 only): E_q is replaced by E_q + 1/3 (avg(tr E) - tr E_q) [1,1,1,0], the average
// taken over the element with the weights w_q; energy, residual and tangent stay exact
// derivatives of one another.
#include <vector>

#include "roller/fem/kinematics.hpp"
#include "roller/fem/shape_functions.hpp"
#include "roller/material/j2_plasticity.hpp"

namespace roller {

using ElementVector = Eigen::Matrix<Real, Eigen::Dynamic, 1, 0, 8, 1>;
using ElementMatrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic, 0, 8, 8>;

struct ElementInput {
  ElementType type = ElementType::Q4;
  const std::vector<PointGeometry>* geometry = nullptr;  // start-of-increment configuration
  const MaterialState* committed = nullptr;              // one state per integration point
  // Armstrong-Frederick's recovery frozen at these plastic multipliers, one per integration point
  // (update_material with FrozenRecovery); nullptr: the exact backward-Euler update.
  const Real* frozen_recovery = nullptr;
  ElementVector displacement;  // increment u, ordered [u_x0, u_y0, u_x1, u_y1, ...]
};

struct ElementOutput {
  Real energy = 0.0;
  ElementVector residual;              // filled when requested
  ElementMatrix tangent;               // filled when requested
  std::vector<MaterialUpdate> points;  // material update per integration point
  bool any_yielded = false;
};

// Throws NumericalError when the material update fails (message names the cause).
void evaluate_element(const ElementOptions& options, const MaterialParams& material, const ElementInput& in,
                      bool want_residual, bool want_tangent, ElementOutput& out);

// The two halves of evaluate_element without a material, small kinematics only (the stationary
// pass sweeps the material along rows of points between them; docs/model.md, Stationary pass):
// the strain of the displacement at each integration point as the material update sees it (B-bar
// applied), and the element's nodal forces sum_q w_q B_q^T sigma_q of stresses at its points.
std::vector<Vec4> element_strains(const ElementOptions& options, ElementType type,
                                  const std::vector<PointGeometry>& geometry, const ElementVector& displacement);
ElementVector element_forces(const ElementOptions& options, ElementType type,
                             const std::vector<PointGeometry>& geometry, const Vec4* stresses);

// Deformation gradient F = I + du/dX of the increment at each integration point, used to push
// the converged stress forward (finite kinematics).
std::vector<Mat2> deformation_gradients(const std::vector<PointGeometry>& geometry, const ElementVector& displacement);

// Push-forward of the converged second Piola-Kirchhoff stress of the increment to the Cauchy
// stress of the new configuration: sigma = J^-1 F S F^T (in plane), sigma_zz = J^-1 S_zz.
// This is the objective update: a rigid rotation R (E = 0, S = sigma_old) gives R sigma R^T.
// Kirchhoff stress of the thesis, tau = J_total sigma, equals sigma to O(volume change), which
// J2 flow keeps elastic-small; roller stores and outputs the Cauchy stress.
Vec4 push_forward(const Mat2& f, const Vec4& second_piola);

// Consistent (row sum = total mass) or lumped (diagonal, row-sum lumping) mass matrix
// rho * int N^T N, for both displacement components.
ElementMatrix element_mass(ElementType type, const std::vector<PointGeometry>& geometry, Real density, bool lumped);

}  // namespace roller
