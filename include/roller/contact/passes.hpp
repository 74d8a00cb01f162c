#pragma once
// Repeated passes of the roller ([passes]; docs/scenes.md, Repeated passes): the scene's steps
// 1..steps.count and its [[roller.path]] describe one pass; the run repeats it `count` times. Between
// passes the roller, clear of the strip after the pass's lift, returns to the pass's start
// (the same start for every pass, or the previous pass's end when the direction alternates,
// the path then mirrored in x). Global steps run 1..count * steps.count.
#include <array>
#include <utility>

#include "roller/contact/roller.hpp"
#include "roller/core/enum_names.hpp"

namespace roller {

enum class PassDirection { Same, Alternate };
template <>
struct EnumNames<PassDirection> {
  static constexpr std::array<std::pair<PassDirection, const char*>, 2> names{
      {{PassDirection::Same, "same"}, {PassDirection::Alternate, "alternate"}}};
};

struct PassSpec {
  int count = 1;  // passes in the run
  PassDirection direction = PassDirection::Same;
};

// Where a global (fractional) step s lies: pass (1-based) and the step within it, s in
// ((pass - 1) N, pass N] belonging to that pass (s = 0: pass 1, local 0).
struct PassPosition {
  int pass = 1;
  Real local = 0.0;
};
PassPosition locate_pass(Real s, int steps_per_pass);

// The roller of pass `pass` (1-based): the scene's, or for an even pass with alternating
// direction the path mirrored in x (dx -> -dx, fx -> -fx) and started where the scene's path ends.
RollerSpec roller_of_pass(const RollerSpec& spec, const PassSpec& passes, int pass, const Vec2& start_centre,
                          int steps_per_pass, Vec2* pass_start);

}  // namespace roller
