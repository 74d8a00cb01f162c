#include "roller/analysis/elliptic_fit.hpp"

#include <algorithm>
#include <cmath>
#include <unsupported/Eigen/NonLinearOptimization>
#include <unsupported/Eigen/NumericalDiff>

#include "roller/analysis/contact_zones.hpp"
#include "roller/analysis/hertz.hpp"

namespace roller {

namespace {

// The ellipse's work-equivalent nodal forces on the chain at unit peak.
std::vector<Real> unit_forces(const std::vector<Real>& x, Real centre, Real half_width) {
  std::vector<Real> shifted(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) shifted[i] = x[i] - centre;
  HertzSolution unit;
  unit.half_width = half_width;
  unit.peak = 1.0;
  return hertz_nodal_forces(unit, shifted);
}

// Residuals F_i - t0 phi_i(d, w) over the parameters (d, w, t0), the shape Eigen's
// Levenberg-Marquardt takes (with forward-difference derivatives).
struct Residuals {
  using Scalar = Real;
  using InputType = Eigen::VectorXd;
  using ValueType = Eigen::VectorXd;
  using JacobianType = Eigen::MatrixXd;
  enum { InputsAtCompileTime = Eigen::Dynamic, ValuesAtCompileTime = Eigen::Dynamic };

  const std::vector<Real>* x = nullptr;
  const std::vector<Real>* force = nullptr;
  Real length = 1.0;  // scales d and w to order one
  int inputs() const { return 3; }
  int values() const { return static_cast<int>(x->size()); }
  int operator()(const Eigen::VectorXd& p, Eigen::VectorXd& r) const {
    const std::vector<Real> phi = unit_forces(*x, p(0) * length, std::max(std::abs(p(1)), 1e-9) * length);
    for (std::size_t i = 0; i < phi.size(); ++i) r(static_cast<Index>(i)) = (*force)[i] - p(2) * phi[i];
    return 0;
  }
};

}  // namespace

EllipticFit fit_elliptic_forces(const std::vector<Real>& x, const std::vector<Real>& force) {
  EllipticFit fit;
  Real largest = 0.0;
  for (Real f : force) largest = std::max(largest, f);
  if (!(largest > 0.0)) return fit;
  // The start: the loaded nodes' extent (half a spacing beyond the outermost) and the peak of the
  // ellipse that carries their total force.
  std::vector<bool> loaded(x.size());
  Real total = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    loaded[i] = force[i] > 1e-6 * largest;
    if (loaded[i]) total += force[i];
  }
  if (std::count(loaded.begin(), loaded.end(), true) < 3) return fit;
  const ZoneExtent extent = zone_extent(x, loaded);
  const Real w0 = extent.half_width();
  Residuals functor;
  functor.x = &x;
  functor.force = &force;
  functor.length = w0;
  Eigen::VectorXd p(3);
  p << extent.centre() / w0, 1.0, 2.0 * total / (M_PI * w0);
  Eigen::NumericalDiff<Residuals> numerical(functor, 1e-10);
  Eigen::LevenbergMarquardt<Eigen::NumericalDiff<Residuals>> lm(numerical);
  lm.parameters.xtol = 1e-12;
  lm.parameters.ftol = 1e-14;
  lm.minimize(p);
  Eigen::VectorXd r(x.size());
  functor(p, r);
  Real norm = 0.0;
  for (Real f : force) norm += f * f;
  fit.centre = p(0) * w0;
  fit.half_width = std::abs(p(1)) * w0;
  fit.peak = p(2);
  fit.residual = std::sqrt(r.squaredNorm() / norm);
  fit.valid = std::isfinite(fit.half_width) && fit.half_width > 0.0 && fit.peak > 0.0;
  return fit;
}

}  // namespace roller
