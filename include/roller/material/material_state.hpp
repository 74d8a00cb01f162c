#pragma once
// State stored at each integration point and committed only after an increment converges.
#include <array>

#include "roller/core/types.hpp"
#include "roller/material/material_params.hpp"

namespace roller {

inline std::array<Vec4, kMaxBackStresses> zero_back_stresses() {
  std::array<Vec4, kMaxBackStresses> a;
  a.fill(Vec4::Zero());
  return a;
}

struct MaterialState {
  // Cauchy stress [xx, yy, zz, xy] in the configuration at the start of the increment, which
  // is the updated-Lagrangian reference; with that reference it is also the second
  // Piola-Kirchhoff stress at the start of the step.
  Vec4 stress = Vec4::Zero();
  Real eq_plastic_strain = 0.0;  // equivalent plastic strain, eps_p = int sqrt(2/3 dep:dep)
  Real plastic_work = 0.0;       // W_pl = int tau:d(eps_p) per unit volume [MPa = mJ/mm^3]
  Real yield_stress = 0.0;       // current size of the yield surface sigma_Y(eps_p) (0 for elastic)
  // Back-stresses alpha_i [xx, yy, zz, xy] (deviatoric; the centre of the yield surface is their
  // sum); the first MaterialParams::n_back_stresses() are used, the rest stay zero.
  std::array<Vec4, kMaxBackStresses> back_stress = zero_back_stresses();
};

}  // namespace roller
