#pragma once
// The record of one scene step, whichever method advanced it (driver/step_method.hpp): its
// outcome and work, the contact and the roller at its end, what a pass left.
#include <optional>
#include <string>
#include <vector>

#include "roller/analysis/pass_metrics.hpp"
#include "roller/contact/backend.hpp"
#include "roller/contact/contact_records.hpp"
#include "roller/contact/increment_types.hpp"
#include "roller/contact/roller.hpp"
#include "roller/io/field_output.hpp"

namespace roller {

// The roller at the end of a converged step, as the outputs write it (roller.csv).
struct RollerRecord {
  RollerPose pose;
  Vec2 force = Vec2::Zero();     // of the strip on the roller [N per mm width]
  Vec2 velocity = Vec2::Zero();  // of the centre over the step (backward difference) [mm/s]
  Real anchor_y = 0.0;           // the prescribed pose's height: a suspension's anchor
  Real deflection = 0.0, deflection_velocity = 0.0, deflection_acceleration = 0.0;  // suspension
  PrescribedForce prescribed;  // the forces the step prescribed (none: its motion)
  Vec2 load_offset = Vec2::Zero();
  // An elastic roller's rim in the contact (analysis/roller_flattening.hpp); a rigid roller's:
  // 0 and its radius.
  Real flattening = 0.0;
  std::optional<Real> effective_radius;
};

// What a scene step did and left: every value the outputs write about it (driver/run_outputs.hpp),
// the prescribed pose and forces included.
struct StepRecord {
  int step = 0;
  int pass = 1;
  Real time = 0.0;
  Termination status = Termination::Failed;
  int cuts = 0;
  SolveCounters counters;  // of the step's sub-increments
  BackendDetails details;  // of the step's sub-increments: their work summed, the rest of the last one
  Real max_penetration = 0.0;
  Index n_yielded = 0;   // integration points that yielded in the step's last converged increment
  IncrementReport last;  // the last increment tried
  std::string message;   // why the step failed
  bool converged() const { return status == Termination::Converged; }
  // The step ended a pass of a multi-pass run: what the pass left (analysis/pass_metrics.hpp),
  // with the residual state by depth under the middle of its track (at x = profile_x).
  struct PassEnd {
    PassRecord record;
    Real profile_x = 0.0;
    std::vector<DepthSample> profile;
    std::optional<PassFatigue> fatigue;  // with [fatigue]
  };
  std::optional<PassEnd> pass_end;
  // The state at the end of the step (as it stands after a failed one): the contact of its
  // last increment, the roller, the strip's kinetic energy.
  std::vector<NodeContactRecord> contact;
  Index n_contact() const { return count_in_contact(contact); }
  std::optional<RollerRecord> roller;
  Real kinetic_energy = 0.0;
  // A stationary pass's loaded state, when its fields are written (output.mid_pass).
  std::optional<StripFields> loaded_fields;
};

}  // namespace roller
