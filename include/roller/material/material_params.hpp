#pragma once
// Material data of the strip: isotropic elasticity, optional J2 plasticity with linear
// isotropic work hardening (docs/model.md, Material), density for dynamic scenes.
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

struct MaterialParams {
  Real youngs_modulus = 2.1e5;  // E [MPa]
  Real poisson_ratio = 0.3;     // nu [-], 0 <= nu < 0.5
  bool plastic = false;         // false: linear elastic, no plastic state is tracked
  Real yield_stress = 0.0;      // initial uniaxial yield stress sigma_y0 [MPa], > 0 when plastic
  Real tangent_modulus = 0.0;   // E_T [MPa], 0 <= E_T < E (E_T = 0: perfect plasticity)
  Real density = 0.0;           // rho [t/mm^3], needed only when strip inertia is on
  StressIntegration integration = StressIntegration::ReturnMapping;
  int n_substeps = 10;  // sub-steps of the Substep integration, >= 1

  // Derived quantities.
  Real shear_modulus() const;  // G = E / (2(1+nu))
  Real bulk_modulus() const;   // K = E / (3(1-2nu))
  Real lame_lambda() const;    // lambda = E nu / ((1+nu)(1-2nu))
  // Plastic modulus of the uniaxial curve, H' = E E_T / (E - E_T): the slope of yield stress
  // versus equivalent plastic strain.
  Real plastic_modulus() const;

  // True when every field is admissible; otherwise false and *why names the field, its value
  // and the violated rule.
  bool is_valid(std::string* why) const;
  // E* = E / (1 - nu^2): the stiffness of line contact (Hertz) and of the plane-strain strip.
  Real plane_strain_modulus() const { return youngs_modulus / (1.0 - poisson_ratio * poisson_ratio); }
};

}  // namespace roller
