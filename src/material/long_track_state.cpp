#include "roller/material/long_track_state.hpp"

namespace roller {

MaterialState long_track_state(const MaterialState& leaving, const Vec4& pass_strain, const MaterialParams& material) {
  // An elastic strain d at fixed plastic strain: d_xx and d_zz take the pass's xx and zz strains
  // off, d_yy and d_xy bring sigma_yy and sigma_xy to zero.
  const Real lambda = material.lame_lambda(), g = material.shear_modulus();
  const Real d_xx = -pass_strain(0), d_zz = -pass_strain(2);
  const Real d_yy = (-leaving.stress(1) - lambda * (d_xx + d_zz)) / (lambda + 2.0 * g);
  const Real volumetric = lambda * (d_xx + d_yy + d_zz);
  MaterialState out = leaving;
  out.stress(0) += volumetric + 2.0 * g * d_xx;
  out.stress(1) = 0.0;
  out.stress(2) += volumetric + 2.0 * g * d_zz;
  out.stress(3) = 0.0;
  return out;
}

}  // namespace roller
