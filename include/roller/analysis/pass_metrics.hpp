#pragma once
// Measuring one pass of the roller (analysis/shakedown.hpp says what and why): the contact seen
// during the pass (PassTrack, fed step by step), the strip at the pass's start (PassBaseline), and
// at its end the PassRecord and the residual stresses versus depth under the middle of the track.
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "roller/analysis/fatigue.hpp"
#include "roller/analysis/shakedown.hpp"
#include "roller/assembly/strip_model.hpp"

namespace roller {

// The contact during a pass: where the roller rolled while touching, how wide and hard it pressed.
struct PassTrack {
  bool touched = false;
  Real x_min = 0.0, x_max = 0.0;      // roller centre x at the steps with contact [mm]
  Real half_width = 0.0;              // largest contact half-width, from the outermost nodes in contact [mm]
  Real load_half_width = 0.0;         // Hertz's half-width of the largest normal contact force [mm]
  Real peak_pressure = 0.0;           // largest nodal contact pressure [MPa]
  Vec2 largest_force = Vec2::Zero();  // the roller's force on the strip at the step it pressed hardest [N/mm]
  // The roller's travel and rim travel R dphi over the steps in contact: its creep 1 + turned / rolled
  // (the transient's slip: 0 rolls, 1 slides), with the last step's centre x and angle.
  Real rolled = 0.0, turned = 0.0;
  bool has_pose = false;
  Real last_x = 0.0, last_angle = 0.0;

  // One step: the centre's x, the x of the nodes in contact with their pressures, and Hertz's
  // half-width of the step's normal contact force.
  void observe(Real centre_x, const std::vector<Real>& contact_x, const std::vector<Real>& contact_pressure,
               Real step_load_half_width);
  // One step's force of the roller on the strip: kept when it presses harder than any before.
  void observe_force(const Vec2& force_on_strip);
  // One step's pose of the roller of `radius`; its motion from the step before counts towards the
  // creep when the roller touches the strip.
  void observe_motion(Real centre_x, Real angle, Real radius, bool in_contact);
  // A steady pass's creep, as one unit of travel.
  void set_creep(Real creep) { rolled = 1.0, turned = creep - 1.0; }
  Real creep() const { return rolled != 0.0 ? 1.0 + turned / rolled : 0.0; }
  nlohmann::json save() const;
  static PassTrack load(const nlohmann::json& j);
};

// Per element, at the start of a pass: mean equivalent plastic strain and mean total shear strain
// 2 eps_xy over its points; and the total displacement of every node.
struct PassBaseline {
  std::vector<Real> plastic_strain;
  std::vector<Real> shear_strain;
  VecX displacement;

  static PassBaseline of(const StripModel& strip);
  nlohmann::json save() const;
  static PassBaseline load(const nlohmann::json& j);
};

// The record of pass `pass` that ended with `strip`; the window is the middle half of the track
// (all of it when the track is shorter than 4 a) down to 4 a, a = the track's load_half_width: a
// scale the contact force fixes, where the outermost node in contact moves a by half an element
// when a node at the edge carries a small force or none (docs/scenes.md, passes.csv). Passes
// without contact leave the window empty and the increments zero.
PassRecord measure_pass(int pass, const StripModel& strip, Real strip_height, const PassTrack& track,
                        const PassBaseline& start);

// Residual state under x (the column of elements whose initial x-range holds it), by depth.
struct DepthSample {
  Real depth = 0.0;                 // of the element's centroid in the initial mesh [mm]
  Vec4 stress = Vec4::Zero();       // mean Cauchy stress [xx, yy, zz, xy] [MPa]
  Real plastic_strain = 0.0;        // mean eps_p
  Vec4 back_stress = Vec4::Zero();  // mean centre of the yield surface, sum of back-stresses [MPa]
};
std::vector<DepthSample> depth_profile(const StripModel& strip, Real strip_height, Real x);

// The stress cycle of a pass at one column of elements (x), depth by depth, fed step by step:
// what the fatigue indices of a transient pass judge (analysis/fatigue.hpp).
struct PassCycles {
  Real x = 0.0;
  std::vector<DepthCycle> depths;  // by depth, as depth_profile orders them

  void observe(const StripModel& strip, Real strip_height);  // appends the column's element means
  nlohmann::json save() const;
  static PassCycles load(const nlohmann::json& j);
};

}  // namespace roller
