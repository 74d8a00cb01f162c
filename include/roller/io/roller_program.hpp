#pragma once
// What the scene prescribes for the roller at every (fractional) global step s of a run: its pose,
// the forces on it, the friction coefficient, and the pass s belongs to ([passes]; docs/scenes.md,
// Repeated passes). The scene's steps 1..N (steps.count) and its [[roller.path]] describe one
// pass; global steps run 1..passes.count * N, and s in ((pass - 1) N, pass N] belongs to `pass`
// (s = 0: pass 1). Between passes the roller, clear of the strip after the pass's lift, returns
// to the pass's start: the scene's start for every pass or, when the direction alternates, for an
// even pass the point where the scene's path ends, with the path mirrored in x (dx -> -dx,
// fx -> -fx; heights, vertical forces, slips and harmonics as in the scene).
#include <optional>

#include "roller/contact/roller.hpp"
#include "roller/io/scene.hpp"

namespace roller {

struct PassPosition {
  int pass = 1;
  Real local = 0.0;  // the step within the pass, in [0, N]
};

class RollerProgram {
 public:
  RollerProgram() = default;  // no roller, one step per pass: set before use
  // `start_centre`: where the first pass starts (the scene's roller.centre, or its default, moved
  // by roller.touch_strip). Without a roller the program only counts passes.
  RollerProgram(const std::optional<RollerSpec>& roller, const PassSpec& passes, int steps_per_pass,
                const Vec2& start_centre);

  PassPosition locate(Real s) const;
  int pass_of_step(int step) const { return locate(step).pass; }
  // The step is the first of a pass after the first (the roller returns before it), or the last
  // of a pass.
  bool starts_later_pass(int step) const { return step > 1 && (step - 1) % steps_per_pass_ == 0; }
  bool ends_pass(int step) const { return step % steps_per_pass_ == 0; }

  // The roller's prescribed pose at s: for a suspended roller its anchor, under force control
  // (a segment's fy or fx) the path without the offset that carries the forces.
  RollerPose pose(Real s) const;
  RollerPose pass_start(int pass) const { return pose_in_pass(pass, 0.0); }
  // The forces prescribed at s (none per direction: its motion is prescribed); none without a roller.
  PrescribedForce force(Real s) const;
  // The friction coefficient at s: its segment's, else `fallback` (contact.friction).
  Real friction(Real s, Real fallback) const;

 private:
  RollerPose pose_in_pass(int pass, Real local) const;
  // The roller and start of pass `pass`: the scene's, or mirrored for an even alternate pass.
  bool mirrored(int pass) const { return alternate_ && pass % 2 == 0; }

  std::optional<RollerSpec> forward_, backward_;
  bool alternate_ = false;
  int steps_per_pass_ = 1;
  Vec2 start_ = Vec2::Zero();
  Vec2 backward_start_ = Vec2::Zero();
};

}  // namespace roller
