#pragma once
// What a steady pass of the scene's roller carries, for the solves that take the pass as a whole
// (roller shakedown-limit, the stationary pass; docs/model.md): the segment of [[roller.path]]
// along which the roller rolls or slides (the one with the largest |dx|), the steps of the press
// before it, its vertical force and the tangential traction q/p.
#include <optional>

#include "roller/io/scene.hpp"

namespace roller {

struct SteadyLoad {
  const PathSegment* travel = nullptr;
  int press_steps = 0;        // steps before the travel segment
  std::optional<Real> force;  // the travel segment's fy [N/mm]: absent when it prescribes the height
  Real traction = 0.0;        // q/p along the travel: the friction coefficient when it slides or creeps
  std::optional<Real> creep;  // s of a segment that rolls with creep (0 < s < 1) and no traction given
  Real travel_sign = 1.0;     // +1: the roller moves towards +x over the strip
};

// `traction`: q/p given by the user; absent: mu of the travel segment when it slides (slip = 1 at
// both ends), 0 when it rolls freely (slip = 0), mu and the creep when it rolls with one creep
// (0 < slip < 1: Carter's traction, analysis/carter.hpp). Throws InputError naming the scene when
// there is no roller, no segment with dx != 0, no press before it, or a creep that changes along
// the segment.
SteadyLoad steady_load(const Scene& scene, std::optional<Real> traction);

// The scene with its strip linear elastic (every layer), small-strain, quasi-static and
// frictionless, one pass, no monitor and no initial state: the elastic solutions of the steady
// solves. Steps and path are the caller's to set.
Scene elastic_frictionless_scene(const Scene& scene);

}  // namespace roller
