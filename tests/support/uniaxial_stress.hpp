#pragma once
// A material point in uniaxial stress (S_yy = S_zz = S_xy = 0), driven by an axial strain
// increment or to an axial stress: Newton on the free strain components with the consistent
// tangent, so each converged step is the return mapping's answer to round-off.
#include <Eigen/LU>
#include <catch2/catch.hpp>
#include <cmath>

#include "roller/material/j2_plasticity.hpp"

namespace roller::testing {

struct UniaxialStep {
  MaterialUpdate update;
  Vec4 strain_increment = Vec4::Zero();  // [xx, yy, zz, 2xy] that gives it
};

// One increment of axial strain; the lateral (yy, zz) increments make S_yy = S_zz = 0.
inline UniaxialStep uniaxial_strain_step(const MaterialParams& p, Real d_axial, const MaterialState& state) {
  Vec4 de(d_axial, -p.poisson_ratio * d_axial, -p.poisson_ratio * d_axial, 0.0);
  for (int iteration = 0; iteration < 30; ++iteration) {
    const MaterialUpdate u = update_material(p, de, state);
    const Vec2 residual(u.stress(1), u.stress(2));
    if (residual.norm() <= 1e-11 * p.yield_stress) return {u, de};
    const Mat2 jacobian = u.tangent.block<2, 2>(1, 1);
    de.segment<2>(1) -= jacobian.inverse() * residual;
  }
  FAIL("uniaxial stress Newton did not converge");
  return {};
}

// One increment to the axial stress `target`: Newton on (xx, yy, zz) so that
// S = [target, 0, 0, 0]. The starting guess is elastic.
inline UniaxialStep uniaxial_stress_step(const MaterialParams& p, Real target, const MaterialState& state) {
  const Real ds = (target - state.stress(0)) / p.youngs_modulus;
  Vec4 de(ds, -p.poisson_ratio * ds, -p.poisson_ratio * ds, 0.0);
  const Eigen::Vector3d goal(target, 0.0, 0.0);
  for (int iteration = 0; iteration < 50; ++iteration) {
    const MaterialUpdate u = update_material(p, de, state);
    const Eigen::Vector3d residual = u.stress.head<3>() - goal;
    if (residual.norm() <= 1e-11 * p.yield_stress) return {u, de};
    const Eigen::Matrix3d jacobian = u.tangent.topLeftCorner<3, 3>();
    de.head<3>() -= jacobian.partialPivLu().solve(residual);
  }
  FAIL("uniaxial stress Newton (stress control) did not converge");
  return {};
}

}  // namespace roller::testing
