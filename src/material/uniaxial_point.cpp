#include "roller/material/uniaxial_point.hpp"

#include <fmt/format.h>

#include <Eigen/LU>

#include "roller/core/error.hpp"

namespace roller {

UniaxialStep uniaxial_strain_step(const MaterialParams& p, Real d_axial, const MaterialState& state) {
  Vec4 de(d_axial, -p.poisson_ratio * d_axial, -p.poisson_ratio * d_axial, 0.0);
  for (int iteration = 0; iteration < 30; ++iteration) {
    const MaterialUpdate u = update_material(p, de, state);
    const Vec2 residual(u.stress(1), u.stress(2));
    if (residual.norm() <= 1e-11 * p.yield_stress) return {u, de};
    const Mat2 jacobian = u.tangent.block<2, 2>(1, 1);
    de.segment<2>(1) -= jacobian.inverse() * residual;
  }
  throw NumericalError(fmt::format(
      "uniaxial strain step of {:g}: the lateral stresses did not vanish in 30 Newton iterations", d_axial));
}

UniaxialStep uniaxial_stress_step(const MaterialParams& p, Real target, const MaterialState& state) {
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
  throw NumericalError(
      fmt::format("uniaxial stress step to {:g} MPa: the stress was not reached in 50 Newton iterations (beyond the "
                  "law's saturated stress?)",
                  target));
}

namespace {

// Walks the turning points, one `step(target of the step, state)` per increment.
template <class Step>
std::vector<UniaxialSample> walk(const MaterialParams& p, const std::vector<Real>& turning_points, int steps_per_branch,
                                 Real start, Step step) {
  require(steps_per_branch >= 1, "a uniaxial path takes at least one step a branch");
  MaterialState state = initial_state(p);
  Real strain = 0.0;
  Real at = start;
  std::vector<UniaxialSample> out{{}};
  for (const Real target : turning_points) {
    const Real from = at;
    for (int k = 1; k <= steps_per_branch; ++k) {
      at = from + (target - from) * k / steps_per_branch;
      const UniaxialStep s = step(at, strain, state);
      state = s.update.trial;
      strain += s.strain_increment(0);
      out.push_back({strain, state.stress(0), strain - state.stress(0) / p.youngs_modulus, state.eq_plastic_strain});
    }
  }
  return out;
}

}  // namespace

std::vector<UniaxialSample> uniaxial_strain_path(const MaterialParams& p, const std::vector<Real>& turning_points,
                                                 int steps_per_branch) {
  return walk(p, turning_points, steps_per_branch, 0.0, [&](Real target, Real strain, const MaterialState& s) {
    return uniaxial_strain_step(p, target - strain, s);
  });
}

std::vector<UniaxialSample> uniaxial_stress_path(const MaterialParams& p, const std::vector<Real>& turning_points,
                                                 int steps_per_branch) {
  return walk(p, turning_points, steps_per_branch, 0.0,
              [&](Real target, Real, const MaterialState& s) { return uniaxial_stress_step(p, target, s); });
}

}  // namespace roller
