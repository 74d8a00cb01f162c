#pragma once
// The residual state a long rolled track leaves, with a point's plastic history (docs/model.md,
// "Stationary pass", Between passes). Far from the track's ends the state is uniform along x; on
// a base held in x and y its displacement then does not depend on x, so its total strain has no
// xx part (nor zz: plane strain, and B-bar's zz part vanishes with the gradient along x), and
// equilibrium with the free surface asks sigma_yy = sigma_xy = 0. A finite strip's ends relieve
// the rolled layer's compression instead (an xx strain of 1e-4 to 3e-4 on the shakedown scenes,
// up to 15 % of the peak residual stress); this takes that relief off elastically.
#include "roller/material/material_params.hpp"
#include "roller/material/material_state.hpp"

namespace roller {

struct LongTrackState {
  MaterialState state;  // the long track's: the plastic history kept, sigma_yy = sigma_xy = 0
  // The pass's total strain [xx, yy, zz, 2xy] on the long track: no xx and no zz part; its yy and
  // shear are the finite strip's with the elastic strain of the stress taken off, so the shear is
  // the pass's plastic shear, which the long track's displacement carries (its ratchet).
  Vec4 pass_strain = Vec4::Zero();
};

// `leaving`: the state of a point of a finite strip after a pass, whose total strain of that pass
// (as the material update sees it: [xx, yy, zz, 2xy], B-bar applied) is `pass_strain` (small
// kinematics, plane strain).
LongTrackState long_track_state(const MaterialState& leaving, const Vec4& pass_strain, const MaterialParams& material);

}  // namespace roller
