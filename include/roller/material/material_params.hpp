#pragma once
// Material data of the strip: isotropic elasticity, optional J2 plasticity with isotropic,
// kinematic, mixed or Chaboche hardening (docs/model.md, Material and Hardening laws), density
// for dynamic scenes.
#include <array>
#include <string>

#include "roller/core/enum_names.hpp"
#include "roller/core/types.hpp"

namespace roller {

enum class StressIntegration {
  ReturnMapping,  // backward-Euler radial return + consistent (algorithmic) tangent (default)
  Substep,        // the thesis's "variable stiffness" (docs/model.md, Sub-stepping): continuum
                  // tangent C^EP integrated over the strain increment in n_substeps forward-Euler
                  // sub-steps
};
template <>
struct EnumNames<StressIntegration> {
  static constexpr std::array<std::pair<StressIntegration, const char*>, 2> names{
      {{StressIntegration::ReturnMapping, "return_mapping"}, {StressIntegration::Substep, "substep"}}};
};

// How the yield surface moves and grows with plastic flow (docs/model.md, Hardening laws). Every
// law is one yield stress sigma_Y(p) = sigma_y0 + H_iso p + Q (1 - exp(-b p)) around a centre
// alpha = sum of back-stresses, each evolving as d alpha_i = 2/3 C_i d eps_p - gamma_i alpha_i dp.
enum class Hardening {
  Isotropic,  // H_iso = H' (from tangent_modulus), no back-stress: today's default
  Kinematic,  // linear kinematic (Prager): one back-stress C = H', gamma = 0
  Mixed,      // H_iso = (1 - m) H', one back-stress C = m H', gamma = 0 (m = kinematic_fraction)
  Chaboche,   // up to ten back-stresses (C_i, gamma_i); one with gamma > 0 is Armstrong-Frederick
};
template <>
struct EnumNames<Hardening> {
  static constexpr std::array<std::pair<Hardening, const char*>, 4> names{{{Hardening::Isotropic, "isotropic"},
                                                                           {Hardening::Kinematic, "kinematic"},
                                                                           {Hardening::Mixed, "mixed"},
                                                                           {Hardening::Chaboche, "chaboche"}}};
};

// Abaqus's combined hardening takes up to ten back-stresses; a calibrated rail steel uses six
// (problems/ratchet_rail.toml).
inline constexpr int kMaxBackStresses = 10;

// One back-stress of the Chaboche law: modulus C [MPa] and recovery gamma [-] (C/gamma is its
// saturation in uniaxial stress).
struct BackStressLaw {
  Real modulus = 0.0;   // C_i [MPa], >= 0
  Real recovery = 0.0;  // gamma_i [-], >= 0 (0: linear kinematic)
};

struct MaterialParams {
  Real youngs_modulus = 2.1e5;  // E [MPa]
  Real poisson_ratio = 0.3;     // nu [-], 0 <= nu < 0.5
  bool plastic = false;         // false: linear elastic, no plastic state is tracked
  Real yield_stress = 0.0;      // initial uniaxial yield stress sigma_y0 [MPa], > 0 when plastic
  Real tangent_modulus = 0.0;   // E_T [MPa], 0 <= E_T < E (E_T = 0: perfect plasticity)
  Real density = 0.0;           // rho [t/mm^3], needed only when strip inertia is on
  StressIntegration integration = StressIntegration::ReturnMapping;
  int n_substeps = 10;  // sub-steps of the Substep integration, >= 1

  Hardening hardening = Hardening::Isotropic;
  Real kinematic_fraction = 0.5;  // m of the Mixed law, 0 <= m <= 1
  // Back-stresses of the Chaboche law (the first n_chaboche of the array).
  std::array<BackStressLaw, kMaxBackStresses> chaboche{};
  int n_chaboche = 0;
  // Q [MPa] of the Voce isotropic term Q (1 - exp(-b p)): > 0 cyclic hardening, < 0 cyclic
  // softening (sigma_y0 + Q > 0 then bounds the yield stress from below).
  Real voce_saturation = 0.0;
  Real voce_rate = 0.0;  // b [-] >= 0

  // Derived quantities.
  Real shear_modulus() const;  // G = E / (2(1+nu))
  Real bulk_modulus() const;   // K = E / (3(1-2nu))
  Real lame_lambda() const;    // lambda = E nu / ((1+nu)(1-2nu))
  // Plastic modulus of the uniaxial curve, H' = E E_T / (E - E_T): the slope of yield stress
  // versus equivalent plastic strain.
  Real plastic_modulus() const;
  // Slope of the linear isotropic term H_iso [MPa] of sigma_Y(p) (the share of H' that is
  // isotropic; 0 for Kinematic and Chaboche).
  Real isotropic_modulus() const;
  // The back-stresses the law carries (Kinematic and Mixed: one with gamma = 0), at most
  // kMaxBackStresses; none when the material is elastic.
  int n_back_stresses() const;
  BackStressLaw back_stress_law(int i) const;
  // True when the isotropic part has a Voce term (Q and b both non-zero).
  bool has_voce() const { return voce_saturation != 0.0 && voce_rate != 0.0; }
  // The smallest size the yield surface reaches under any plastic flow: sigma_y0, or the saturated
  // sigma_y0 + Q of a softening Voce term (the yield stress of a shakedown bound).
  Real lowest_yield_stress() const {
    return has_voce() && voce_saturation < 0.0 ? yield_stress + voce_saturation : yield_stress;
  }
  // True when the update has an incremental potential (no Armstrong-Frederick recovery term).
  bool has_potential() const;

  // True when every field is admissible; otherwise false and *why names the field, its value
  // and the violated rule.
  bool is_valid(std::string* why) const;
  // E* = E / (1 - nu^2): the stiffness of line contact (Hertz) and of the plane-strain strip.
  Real plane_strain_modulus() const { return youngs_modulus / (1.0 - poisson_ratio * poisson_ratio); }
};

// Inline: the material update calls these for every integration point (docs/benchmarks.md).
inline Real MaterialParams::shear_modulus() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }

inline Real MaterialParams::bulk_modulus() const { return youngs_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio)); }

inline Real MaterialParams::lame_lambda() const {
  return youngs_modulus * poisson_ratio / ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio));
}

// From the bilinear uniaxial curve: total strain rate 1/E_T = elastic 1/E + plastic 1/H'.
inline Real MaterialParams::plastic_modulus() const {
  return youngs_modulus * tangent_modulus / (youngs_modulus - tangent_modulus);
}

inline Real MaterialParams::isotropic_modulus() const {
  switch (hardening) {
    case Hardening::Isotropic: return plastic_modulus();
    case Hardening::Mixed: return (1.0 - kinematic_fraction) * plastic_modulus();
    case Hardening::Kinematic:
    case Hardening::Chaboche: return 0.0;
  }
  return 0.0;
}

inline int MaterialParams::n_back_stresses() const {
  if (!plastic) return 0;
  switch (hardening) {
    case Hardening::Isotropic: return 0;
    case Hardening::Kinematic:
    case Hardening::Mixed: return 1;
    case Hardening::Chaboche: return n_chaboche;
  }
  return 0;
}

inline BackStressLaw MaterialParams::back_stress_law(int i) const {
  switch (hardening) {
    case Hardening::Kinematic: return {plastic_modulus(), 0.0};
    case Hardening::Mixed: return {kinematic_fraction * plastic_modulus(), 0.0};
    case Hardening::Chaboche: return chaboche[static_cast<std::size_t>(i)];
    case Hardening::Isotropic: break;
  }
  return {};
}

inline bool MaterialParams::has_potential() const {
  for (int i = 0; i < n_back_stresses(); ++i)
    if (back_stress_law(i).recovery != 0.0) return false;
  return true;
}

}  // namespace roller
