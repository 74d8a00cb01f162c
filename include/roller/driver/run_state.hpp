#pragma once
// Everything a later step of a run reads that is neither the strip's committed state (assembly/
// strip_model.hpp, its own transactional commit) nor the dynamics histories (dynamics/
// dynamics_state.hpp): one value, so that a copy is the undo of a step and the state files
// serialise it whole (driver/state_file.cpp).
#include <optional>
#include <string>
#include <vector>

#include "roller/analysis/hertz.hpp"
#include "roller/analysis/pass_metrics.hpp"
#include "roller/analysis/pressure_profile.hpp"
#include "roller/contact/backend.hpp"
#include "roller/contact/contact_records.hpp"
#include "roller/contact/friction_history.hpp"
#include "roller/contact/roller.hpp"
#include "roller/core/types.hpp"

namespace roller {

// What the run's steps cost, over every step of the run since its first (a resumed run's included:
// the totals are in the state files).
struct RunTotals {
  int iterations = 0;
  int cuts = 0;
  Real max_penetration = 0.0;
};

struct RunState {
  int steps_done = 0;
  RunTotals totals;
  // The roller at the end of the last committed increment, and its centre's velocity over the
  // last step (backward difference) [mm/s].
  RollerPose pose;
  Vec2 roller_velocity = Vec2::Zero();
  // Force control: the centre's offset from the path that carries the prescribed forces [mm],
  // and -dF/dw per axis at the last force-controlled increment (0: none yet).
  Vec2 load_offset = Vec2::Zero();
  Vec2 load_stiffness = Vec2::Zero();
  // What a step hands the next, by the run's method. The transient: the last converged increment
  // (all dofs) and its length in steps, the next one's predictor. The stationary: the next pass's
  // first iterate (all dofs, or empty: zero; steady/stationary_passes.hpp).
  VecX last_increment;
  Real last_length = 0.0;
  VecX next_pass_start;
  // The contact of the last increment, and the friction history it leaves.
  std::vector<NodeContactRecord> contact;
  FrictionHistory friction;
  // An elastic roller's rim displacements at the end of the last increment (empty: none yet).
  VecX rim;
  // Multi-pass runs: the contact seen in the current pass, the strip at its start, the records
  // of the passes done.
  PassTrack pass_track;
  PassBaseline pass_baseline;
  std::vector<PassRecord> pass_records;
  // With [fatigue]: the transient pass's stress cycle so far (at the track's middle), and the last
  // pass's answer.
  PassCycles pass_cycles;
  std::optional<FatigueAnswer> fatigue;
  // The run-time monitor's warnings so far (each kind once; summary.json lists them), and whether
  // the once-a-run warning of operator A's pointwise loss is among them.
  std::vector<std::string> warnings;
  bool pointwise_loss_reported = false;
};

}  // namespace roller
