#pragma once
// What a steady pass of the scene's roller carries, for the solves that take the pass as a whole
// (roller shakedown-limit, the stationary pass; docs/model.md): the segment of [[roller.path]]
// along which the roller rolls or slides (the one with the largest |dx|), the steps of the press
// before it, its vertical force and the tangential traction q/p.
#include <optional>
#include <string>
#include <vector>

#include "roller/analysis/hertz.hpp"
#include "roller/contact/contact_records.hpp"
#include "roller/io/scene.hpp"

namespace roller {

// How the tangential traction spreads over the contact.
enum class TractionShape {
  Uniform,  // q = (Q/P) p: sliding (Q = mu P), or a traction ratio the user gives
  Carter,   // rolling under a tangential force: Carter's stick zone at the leading edge (analysis/carter.hpp)
  Creep,    // rolling with a creep 0 < slip < 1: the traction an outcome of the roller's contact alone
};

struct SteadyLoad {
  const PathSegment* travel = nullptr;
  int press_steps = 0;        // steps before the travel segment
  std::optional<Real> force;  // the travel segment's fy [N/mm]: absent when it prescribes the height
  Real traction = 0.0;        // Q/P along the travel (> 0: the strip dragged along it)
  TractionShape shape = TractionShape::Uniform;
  Real friction = 0.0;     // mu of the travel segment
  Real travel_sign = 1.0;  // +1: the roller moves towards +x over the strip
  Real creep = 0.0;        // the travel segment's slip at its end: the roller's creep where no force sets it
  std::string segment;     // "FILE: roller.path: the segment over steps A-B", for messages
};

// `traction`: q/p given by the user (uniform); absent: Carter's traction of the travel segment's
// horizontal force fx when it has one (the creep then turns the roller but does not set the load),
// mu (uniform) when it slides (slip = 1 at both ends), 0 when it rolls freely (slip = 0), and the
// shape Creep for a creep 0 < slip < 1 without fx. Throws InputError naming the scene and key when
// there is no roller, no segment with dx != 0, no press before it, or an fx without fy or beyond
// mu fy.
SteadyLoad steady_load(const Scene& scene, std::optional<Real> traction);

// Throws InputError for the shape Creep: a load laid on the strip (the Hertz pressure,
// shakedown-limit's press) needs its traction, and the traction a creep carries depends on the
// strip's plastic flow and on nu (Carter's law is an elastic strip's with nu = 0.5).
void require_given_traction(const SteadyLoad& load);

// Throws InputError for a horizontal force the roller's own contact cannot carry rolling:
// |q/p| >= mu (no creep does; the segment slides: slip = 1).
void require_rollable(const SteadyLoad& load);

// The stationary pass's checks of its load before any pass (a run's set-up): require_given_traction
// under the Hertz load, require_rollable on the roller's contact.
void require_stationary_load(const Scene& scene, const SteadyLoad& load);

// The tangential nodal forces in x, one per record of `contact`, of the load's traction on the
// contact's normal forces: (Q/P) |f_n| along the travel, or Carter's, mu |f_n| less the stick zone's
// relief (analysis/carter.hpp) placed by the Hertz solution `hertz` of P about the contact's centre
// `centre_x` (shakedown-limit on its elastic press, the stationary pass on the roller's contact).
std::vector<Real> traction_forces(const SteadyLoad& load, const std::vector<NodeContactRecord>& contact,
                                  const HertzSolution& hertz, Real centre_x);

// Whether the load's traction slips at `along` [mm] from the contact's centre along the travel:
// everywhere under a uniform q/p, behind Carter's stick zone under fx, nowhere without a traction.
bool traction_slips(const SteadyLoad& load, const HertzSolution& hertz, Real along);

// The scene with its strip linear elastic (every layer), small-strain, quasi-static and
// frictionless (no segment keeps a traction), one pass, no monitor and no initial state: the
// elastic solutions of the steady solves. Steps and path are the caller's to set.
Scene elastic_frictionless_scene(const Scene& scene);

}  // namespace roller
