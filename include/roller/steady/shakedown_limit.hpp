#pragma once
// `roller shakedown-limit`: Melan's bound of a scene's strip, roller and traction from one elastic
// solution (docs/model.md, "Melan's bound"). The scene's press (the steps before its rolling or
// sliding segment) is solved once with the strip made linear elastic, small strain and
// frictionless; a sliding traction q = mu p is added as the elastic response to tangential nodal
// forces mu |f_n| in the direction of travel (Johnson's load: the Hertz pressure and q = mu p,
// uncoupled), and a rolling segment's horizontal force fx as Carter's traction (analysis/carter.hpp). Each row of
// integration points at one depth then holds the stress history of a point at that depth as the roller passes
// (analysis/melan.hpp).
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "roller/analysis/melan.hpp"
#include "roller/io/scene.hpp"
#include "roller/steady/steady_load.hpp"

namespace roller {

struct ShakedownLimitSettings {
  // q/p of a uniform traction; absent: the scene's (steady/steady_load.hpp): Carter's of the rolling
  // segment's fx, mu when it slides (slip = 1), 0 when it rolls freely (slip = 0).
  std::optional<Real> traction;
  MelanSearch search = MelanSearch::StrictestRow;
  std::ostream* progress = nullptr;
};

// The load of the elastic solution, in Johnson's measure.
struct ShakedownLoad {
  int press_steps = 0;       // scene steps of the press
  Real load = 0.0;           // P: the vertical force on the roller after the press [N/mm]
  Real half_width = 0.0;     // Hertz a of P [mm]
  Real hertz_peak = 0.0;     // Hertz p0 of P [MPa]: the load measure's p0
  Real computed_peak = 0.0;  // the largest nodal contact pressure of the press [MPa]
  Real traction = 0.0;       // Q/P along the travel
  TractionShape shape = TractionShape::Uniform;
  Real stick_half_width = 0.0;  // c of Carter's traction [mm]
  Real travel_sign = 1.0;       // direction of the rolling segment (+1: +x)
};

struct ShakedownLimitResult {
  ShakedownLoad load;
  MelanLimit elastic;                   // Melan: residual stresses only
  std::optional<MelanLimit> kinematic;  // with a back-stress: when the strip hardens kinematically
  Real top = 0.0;                       // y of the strip's top [mm]
  // Where the mesh cannot resolve the mode that governs (too few elements across the contact).
  std::vector<std::string> warnings;
  // p0/k at the bound's limit (k = sigma_y/sqrt(3) at its critical point), and that of the
  // scene's own load (load factor 1).
  Real p0_over_k(const MelanLimit& bound) const;
  Real scene_p0_over_k(const MelanLimit& bound) const;
};

// Throws InputError when the scene has no roller that rolls or slides after a press, a creep
// (0 < slip < 1) without fx or an explicit traction, or a strip that cannot yield; NumericalError when
// the elastic press does not converge.
ShakedownLimitResult compute_shakedown_limit(const Scene& scene, const ShakedownLimitSettings& settings);

// The limits at each uniform traction q/p of `tractions` (the shakedown map over q/p), from one
// elastic press and one elastic response to a unit traction (the stresses are linear in q/p).
std::vector<ShakedownLimitResult> compute_shakedown_map(const Scene& scene, const std::vector<Real>& tractions,
                                                        const ShakedownLimitSettings& settings);

}  // namespace roller
