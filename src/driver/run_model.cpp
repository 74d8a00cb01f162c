#include "run_model.hpp"

#include "roller/analysis/roller_flattening.hpp"

namespace roller {

void RunModel::record_state(StepRecord& res, int program_step) const {
  res.contact = state.contact;
  res.kinetic_energy = dynamics.kinetic_energy();
  if (!scene.roller) return;
  RollerRecord r;
  r.pose = state.pose;
  r.force = roller_force();
  r.velocity = state.roller_velocity;
  r.anchor_y = program.pose(program_step).centre.y();
  if (const Suspension* suspension = dynamics.suspension()) r.deflection = suspension->deflection();
  r.deflection_velocity = dynamics.suspension_velocity();
  r.deflection_acceleration = dynamics.suspension_acceleration();
  r.prescribed = program.force(program_step);
  r.load_offset = state.load_offset;
  const RollerFlattening rim =
      roller_flattening(state.contact, state.pose.centre, scene.roller->radius, scene.roller->elastic());
  r.flattening = rim.flattening;
  r.effective_radius = rim.effective_radius;
  res.roller = r;
}

}  // namespace roller
