#pragma once
// The roller pressed on an elastic strip: shakedown-limit's elastic press, solved through the
// contact session (contact/contact_session.hpp), one increment a press. The strip is the
// scene's made linear elastic, small-strain and frictionless (elastic_frictionless_scene). A press
// starts where the last one ended (the roller's pose and load offset, the friction history, an
// elastic roller's rim, the last increment as its predictor), so that a sequence of presses
// warm-starts.
#include <memory>
#include <vector>

#include "roller/contact/backend.hpp"
#include "roller/contact/contact_records.hpp"
#include "roller/contact/contact_session.hpp"
#include "roller/contact/friction_history.hpp"
#include "roller/io/load_program.hpp"
#include "roller/io/roller_program.hpp"
#include "roller/io/scene.hpp"

namespace roller {

class ElasticPress {
 public:
  // `elastic`: a scene made by elastic_frictionless_scene, its roller path the press's program;
  // `mesh`: the strip's. InputError as a run of the scene would give before its first step.
  ElasticPress(Scene elastic, const Mesh& mesh);
  ~ElasticPress();

  // One increment of the strip from its present state to the program's step s_to (the roller's
  // pose or force there, the displacements prescribed there): the report; when it converged, the
  // strip, the roller and the contact are the increment's.
  IncrementReport press(Real s_from, Real s_to);

  StripModel& strip() { return *strip_; }
  const StripModel& strip() const { return *strip_; }
  const std::vector<NodeContactRecord>& contact() const { return contact_; }
  const RollerPose& pose() const { return pose_; }
  Vec2 roller_force() const { return force_on_roller(contact_); }

 private:
  Scene scene_;
  std::unique_ptr<StripModel> strip_;
  LoadProgram loads_;
  std::unique_ptr<ContactBackend> backend_;
  ContactSession session_;
  RollerProgram program_;
  // What the last press left for the next.
  RollerPose pose_;
  Vec2 load_offset_ = Vec2::Zero(), load_stiffness_ = Vec2::Zero();
  VecX last_increment_;
  Real last_length_ = 0.0;
  std::vector<NodeContactRecord> contact_;
  FrictionHistory friction_;
  VecX rim_;  // an elastic roller's rim displacements (empty: a rigid roller, or none yet)
};

}  // namespace roller
