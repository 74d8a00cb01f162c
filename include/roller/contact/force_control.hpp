#pragma once
// A roller under a prescribed force (docs/model.md, Force-controlled roller): the centre's height
// (vertical force) or x (horizontal force) is an unknown of the increment. The centre sits at the
// path's position plus an offset w along that axis, and the increment's contact solve gives the
// strip's force component F(w) on the roller, which falls as w grows (lifting relieves the
// contact; moving on in x makes the strip hold the roller back). solve_for_force() finds w with
// F(w) = target by a safeguarded secant on the contact solves, as the suspension coupling does
// (dynamics/suspension.hpp), so both contact backends are driven the same way.
#include <functional>
#include <optional>
#include <string>

#include "roller/core/types.hpp"
#include "roller/solver/termination.hpp"

namespace roller {

enum class ForceAxis {
  Vertical,   // F = f_y >= 0: the contact only pushes, F = 0 means the roller is off the strip
  Horizontal  // F = f_x of either sign, carried by friction (and by the indentation's flanks)
};

struct ForceControlSettings {
  ForceAxis axis = ForceAxis::Vertical;
  Real force_tolerance = 0.0;  // |F(w) - P| that is converged [N per mm]
  // Where F jumps across P within round-off of w (a node's stick-slip state flips between two
  // solves a round-off apart), the bracket's better end is taken if |F - P| is within this.
  Real jump_tolerance = 0.0;
  Real stiffness_guess = 0.0;    // dF/d(-w) for the first step [N/mm per mm], > 0
  Real max_offset_change = 0.0;  // |w - w0| beyond this: nothing carries the load [mm]
  int max_iterations = 40;       // contact solves
};

struct ForceControlResult {
  Termination status = Termination::Failed;
  int iterations = 0;    // contact solves
  Real offset = 0.0;     // w at the last solve
  Real force = 0.0;      // F(w) there
  Real stiffness = 0.0;  // converged: the slope dF/d(-w) last used (> 0), a guess for the next increment
  std::string message;
  bool converged() const { return status == Termination::Converged; }
};

// Finds w with F(w) = target, starting at w0. `force_at(w)` solves the increment with the centre
// at offset w and returns F, or nullopt when that solve fails. While the root is not bracketed
// the step is the secant (or the guess) slope's Newton step, doubled while F does not change (the
// roller above the strip, vertical axis only); once bracketed, Illinois regula falsi. A bracket
// that closes to round-off ends at its better end when that is within jump_tolerance (solved
// again there). Fails with a message when a solve fails, when w would move more than max_offset_change (a load nothing
// carries: the roller pulled off the strip, or a strip that collapses under it) or after max_iterations.
ForceControlResult solve_for_force(Real target, Real w0, const ForceControlSettings& settings,
                                   const std::function<std::optional<Real>(Real)>& force_at);

}  // namespace roller
