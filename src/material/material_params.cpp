#include "roller/material/material_params.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

namespace roller {

namespace {

std::string describe_text(const std::string& field, const std::string& value, const std::string& rule) {
  return "material." + field + " = " + value + ": " + rule;
}

std::string fmt_real(Real value) {
  std::ostringstream out;
  out << std::setprecision(12) << value;
  return out.str();
}

std::string describe(const std::string& field, Real value, const std::string& rule) {
  return describe_text(field, fmt_real(value), rule);
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
  if (p.plastic) {
    const std::string law = enum_name(p.hardening);
    if (p.hardening == Hardening::Mixed && !(p.kinematic_fraction >= 0.0 && p.kinematic_fraction <= 1.0))
      return describe("kinematic_fraction", p.kinematic_fraction,
                      "must satisfy 0 <= m <= 1 (the kinematic share of H')");
    if (p.hardening == Hardening::Chaboche) {
      if (p.tangent_modulus != 0.0)
        return describe("tangent_modulus", p.tangent_modulus,
                        "must be 0 with hardening = \"chaboche\" (its hardening is in the back-stresses; "
                        "use a back-stress with gamma = 0 for a linear kinematic part and voce_Q/voce_b for "
                        "an isotropic one)");
      if (!(p.n_chaboche >= 1 && p.n_chaboche <= kMaxBackStresses))
        return describe_text(
            "chaboche_C", "(" + std::to_string(p.n_chaboche) + " values)",
            "hardening = \"chaboche\" needs 1 to " + std::to_string(kMaxBackStresses) + " back-stresses");
      for (int i = 0; i < p.n_chaboche; ++i) {
        const BackStressLaw& b = p.chaboche[static_cast<std::size_t>(i)];
        const std::string entry = "entry " + std::to_string(i + 1) + " ";
        if (!(std::isfinite(b.modulus) && b.modulus >= 0.0))
          return describe("chaboche_C", b.modulus, entry + "must be finite and >= 0 [MPa]");
        if (!(std::isfinite(b.recovery) && b.recovery >= 0.0))
          return describe("chaboche_gamma", b.recovery, entry + "must be finite and >= 0");
      }
    } else if (p.n_chaboche != 0) {
      return describe_text("chaboche_C", "(" + std::to_string(p.n_chaboche) + " values)",
                           "back-stresses need hardening = \"chaboche\" (it is \"" + law + "\")");
    }
    if (!std::isfinite(p.voce_saturation))
      return describe("voce_Q", p.voce_saturation, "must be finite [MPa] (Voce saturation; < 0 softens)");
    if (!(std::isfinite(p.voce_rate) && p.voce_rate >= 0.0))
      return describe("voce_b", p.voce_rate, "must be finite and >= 0 (Voce rate)");
    // Softening: the yield stress saturates at sigma_y0 + Q, which must stay a yield stress, and it
    // may not fall faster than 3G rises, or the return mapping's consistency has no unique root.
    if (p.voce_saturation < 0.0 && !(p.yield_stress + p.voce_saturation > 0.0))
      return describe("voce_Q", p.voce_saturation,
                      "must satisfy yield_stress + voce_Q > 0 (yield_stress = " + fmt_real(p.yield_stress) +
                          " MPa; a softening Voce term saturates at their sum)");
    if (p.voce_saturation < 0.0 && !(p.voce_saturation * p.voce_rate > -3.0 * p.shear_modulus()))
      return describe("voce_b", p.voce_rate,
                      "must satisfy voce_Q * voce_b > -3G = " + fmt_real(-3.0 * p.shear_modulus()) +
                          " MPa (softening faster than the elastic shear stiffness has no unique return mapping)");
    if (p.integration == StressIntegration::Substep &&
        (p.hardening != Hardening::Isotropic || p.voce_saturation != 0.0))
      return describe_text(
          "stress_integration", "\"substep\"",
          "substep integrates linear isotropic hardening only; use return_mapping with hardening = \"" + law +
              "\" or Voce terms");
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
