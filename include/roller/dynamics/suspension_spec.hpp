#pragma once
#include "roller/core/types.hpp"

namespace roller {

// Viscoelastic vertical suspension of the roller (thesis (4.20); docs/model.md, Roller
// suspension), per mm of roller length: the centre is the prescribed path (the anchor, i.e. the
// bearing housing) plus a deflection w with  m w'' + c w' + k w = F_y  (F_y: the strip's vertical
// force on the roller).
struct SuspensionSpec {
  Real mass = 0.0;       // m [t per mm]
  Real damping = 0.0;    // c [N s/mm per mm]
  Real stiffness = 0.0;  // k [N/mm per mm]
};

}  // namespace roller
