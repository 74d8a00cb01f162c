#pragma once
// The Jacobian of the steady problem in the roller's frame (docs/model.md, "The steady Jacobian"):
// the derivative of the nodal forces sum w B^T sigma of the swept states with respect to the
// displacement, where a point's stress depends on the strains of every point upstream on its lane.
// Dense along a lane if written in the displacement alone (unsymmetric and non-local), it is
// sparse with the lanes' states as unknowns beside it:
//   z_p = [tau, eq. plastic strain, back-stresses] after every yielding step p, with
//   tau = sigma - C eps, so that every point's stress is tau + C eps and the displacement's block
//   is the elastic stiffness K_e;
//   a yielding step ties z_p to the z before it through the derivatives of the step (lane_step,
//   by finite differences: every hardening law alike); an elastic step copies the state, so the
//   points downstream of p up to the lane's next yielding step hold z_p too, and add their forces
//   to its columns (one unknown per point there halved J's factors; docs/benchmarks-log.md).
// So with B_q the point q's rows of the strain operator:
//   [ K_e        sum_q w B_q^T S ] [du]   [r]
//   [ -dz/du     I - dz/dz_prev  ] [dz] = [0]      (S picks tau out of z; q: the points holding z_p)
// whose first block row, after dz is eliminated, is the exact linearisation of the forces.
#include <vector>

#include "roller/assembly/dof_map.hpp"
#include "roller/assembly/stationary_strip.hpp"

namespace roller {

struct SteadyJacobian {
  SparseMatrix matrix;   // square, general: the free dofs first, then the yielding steps' states
  Index n_free = 0;      // the displacement's unknowns
  Index n_yielding = 0;  // points whose step yields
};

// At the iterate with the points' strains `strains` and their swept `states` (from the lanes'
// `upstream` states, one per streamline); `elastic` is K_e over the free dofs.
SteadyJacobian steady_jacobian(const StationaryStrip& strip, const DofMap& dofs, const SparseMatrix& elastic,
                               const std::vector<Vec4>& strains, const std::vector<MaterialState>& upstream,
                               const std::vector<MaterialState>& states);

}  // namespace roller
