#include "roller/material/long_track_state.hpp"

namespace roller {

LongTrackState long_track_state(const MaterialState& leaving, const Vec4& pass_strain, const MaterialParams& material) {
  // An elastic strain d at fixed plastic strain: d_xx and d_zz take the pass's xx and zz strains
  // off, d_yy and d_xy bring sigma_yy and sigma_xy to zero.
  const Real lambda = material.lame_lambda(), g = material.shear_modulus();
  const Real d_xx = -pass_strain(0), d_zz = -pass_strain(2);
  const Real d_yy = (-leaving.stress(1) - lambda * (d_xx + d_zz)) / (lambda + 2.0 * g);
  const Real d_xy = -leaving.stress(3) / g;  // engineering shear
  const Real volumetric = lambda * (d_xx + d_yy + d_zz);
  LongTrackState out;
  out.state = leaving;
  out.state.stress(0) += volumetric + 2.0 * g * d_xx;
  out.state.stress(1) = 0.0;
  out.state.stress(2) += volumetric + 2.0 * g * d_zz;
  out.state.stress(3) = 0.0;
  out.pass_strain = pass_strain + Vec4(d_xx, d_yy, d_zz, d_xy);
  return out;
}

}  // namespace roller
