#include "roller/material/material_params.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace roller {

Real MaterialParams::shear_modulus() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }

Real MaterialParams::bulk_modulus() const { return youngs_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio)); }

Real MaterialParams::lame_lambda() const {
  return youngs_modulus * poisson_ratio / ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio));
}

// From the bilinear uniaxial curve: total strain rate 1/E_T = elastic 1/E + plastic 1/H'.
Real MaterialParams::plastic_modulus() const {
  return youngs_modulus * tangent_modulus / (youngs_modulus - tangent_modulus);
}

namespace {

std::string describe(const std::string& field, Real value, const std::string& rule) {
  std::ostringstream out;
  out << "material." << field << " = " << std::setprecision(12) << value << ": " << rule;
  return out.str();
}

// The comparisons are written so that NaN fails every rule.
std::string first_violation(const MaterialParams& p) {
  const Real e = p.youngs_modulus;
  if (!(std::isfinite(e) && e > 0.0)) {
    return describe("youngs_modulus", e, "must be finite and > 0 (E in MPa)");
  }
  const Real nu = p.poisson_ratio;
  if (!(nu >= 0.0 && nu < 0.5)) {
    return describe("poisson_ratio", nu, "must satisfy 0 <= nu < 0.5");
  }
  if (p.plastic) {
    const Real sy = p.yield_stress;
    if (!(std::isfinite(sy) && sy > 0.0)) {
      return describe("yield_stress", sy, "must be finite and > 0 when plastic = true");
    }
    const Real et = p.tangent_modulus;
    if (!(et >= 0.0 && et < e)) {
      std::ostringstream rule;
      rule << "must satisfy 0 <= E_T < E = " << std::setprecision(12) << e
           << " when plastic = true (E_T = 0 is perfect plasticity)";
      return describe("tangent_modulus", et, rule.str());
    }
  }
  const Real rho = p.density;
  if (!(std::isfinite(rho) && rho >= 0.0)) {
    return describe("density", rho, "must be finite and >= 0 (t/mm^3; steel is 7.8e-9)");
  }
  if (p.n_substeps < 1) {
    return describe("n_substeps", p.n_substeps, "must be >= 1");
  }
  return {};
}

}  // namespace

bool MaterialParams::is_valid(std::string* why) const {
  const std::string violation = first_violation(*this);
  if (why != nullptr) *why = violation;
  return violation.empty();
}

}  // namespace roller
