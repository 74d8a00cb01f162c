#pragma once
// A scene: everything one run needs, as plain structs filled by the scene loader
// (io/scene_keys.hpp declares every key of a scene file, docs/scenes.md documents them).
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "roller/analysis/fatigue.hpp"
#include "roller/contact/contact_options.hpp"
#include "roller/contact/roller.hpp"
#include "roller/core/enum_names.hpp"
#include "roller/fem/kinematics.hpp"
#include "roller/material/layered_material.hpp"
#include "roller/material/material_params.hpp"
#include "roller/mesh/strip_mesher.hpp"

namespace roller {

// Repeated passes of the roller ([passes]; docs/scenes.md, Repeated passes): the scene's steps
// 1..steps.count and its [[roller.path]] describe one pass, repeated `count` times, each from the
// same start or, alternating, back from where the previous one ended (io/roller_program.hpp).
enum class PassDirection { Same, Alternate };
template <>
struct EnumNames<PassDirection> {
  static constexpr std::array<std::pair<PassDirection, const char*>, 2> names{
      {{PassDirection::Same, "same"}, {PassDirection::Alternate, "alternate"}}};
};

// How a pass is computed: marched increment by increment over the scene's steps, or solved at
// once as the steady state in the roller's frame (docs/model.md, Stationary pass), one step a pass.
enum class PassMethod { Transient, Stationary };
template <>
struct EnumNames<PassMethod> {
  static constexpr std::array<std::pair<PassMethod, const char*>, 2> names{
      {{PassMethod::Transient, "transient"}, {PassMethod::Stationary, "stationary"}}};
};

// The load of a stationary pass: the Hertz pressure of the travel force (and q = mu p when the
// roller slides), or the rigid roller's contact solved in every iteration (frictionless).
enum class StationaryContact { Hertz, Roller };
template <>
struct EnumNames<StationaryContact> {
  static constexpr std::array<std::pair<StationaryContact, const char*>, 2> names{
      {{StationaryContact::Hertz, "hertz"}, {StationaryContact::Roller, "roller"}}};
};

struct PassSpec {
  int count = 1;  // passes in the run
  PassDirection direction = PassDirection::Same;
  PassMethod method = PassMethod::Transient;
  StationaryContact stationary_contact = StationaryContact::Roller;
  int stationary_phases = 1;       // places of the roller between two nodes solved together (docs/model.md, Phases)
  int stationary_path_parts = 16;  // a lane's yielding step walked in this many parts (docs/model.md, The sweep)
  bool until_verdict = false;      // stop after the first pass that decides the shakedown verdict
};

// Selects nodes by set name ("top", "left", ...) or by the thesis's 1-based node numbers.
struct NodeSelector {
  std::string set_name;          // used when numbers is empty and near is absent
  std::vector<Index> numbers;    // thesis node numbers (1-based)
  std::optional<Vec2> near;      // the node nearest to this point of the initial mesh [mm]
                                 // (stays valid under refinement, unlike a node number)
  std::string describe() const;  // for messages: "set 'left'" or "nodes [5, 101]"
};

// A prescribed ramp: the quantity reaches `value` at the end of step `ramp_last`, rising
// linearly from 0 at the end of step ramp_first-1, and stays constant afterwards. Or, when
// `history` is given, a piecewise-linear history through (0, 0) and its (step, value) points,
// held after the last (a load cycle).
struct Ramp {
  Real value = 0.0;
  int ramp_first = 1;
  int ramp_last = 1;
  std::vector<std::array<Real, 2>> history;  // (step, value), steps increasing
  Real at_step(int step) const;              // cumulative value at the end of `step` (steps are 1-based)
  Real peak() const;                         // the largest |value| the ramp or the history reaches
  bool operator==(const Ramp& o) const {
    return value == o.value && ramp_first == o.ramp_first && ramp_last == o.ramp_last && history == o.history;
  }
  bool operator!=(const Ramp& o) const { return !(*this == o); }
};

// Prescribed displacement of the selected nodes in x and/or y (a component that is absent is
// free). Values are total displacements from the initial configuration, in mm.
struct DisplacementBC {
  NodeSelector nodes;
  std::optional<Ramp> x;
  std::optional<Ramp> y;
};

// Nodal forces applied to each selected node [N per mm of strip width].
struct NodalLoad {
  NodeSelector nodes;
  std::optional<Ramp> fx;
  std::optional<Ramp> fy;
};

struct StepControl {
  int n_steps = 1;   // scene steps (output is written at the end of each)
  Real dt = 1.0;     // time step [s] (the step counter for quasistatic scenes)
  int max_cuts = 4;  // a failed step is split in 2, 4, ... up to 2^max_cuts sub-increments
};

struct OutputOptions {
  int every = 1;         // write fields every N steps (and always the last step)
  bool mid_pass = true;  // pass runs: also each pass's loaded state (transient: the roller at mid-track)
  bool vtu = true;
  bool monitor = true;           // run-time monotonicity monitor (one extra assembly and
                                 // factorisation of the strip tangent per step)
  int checkpoint_every = 1;      // write checkpoint.cbor (the full state, for --resume) every N
                                 // steps; 0 = never
  std::vector<int> save_states;  // steps whose full state is kept as state_NNNN.cbor
                                 // (state_final.cbor is always written at the end)
};

// Strip inertia (docs/model.md, Strip inertia). The roller's suspension is switched on by [roller.suspension].
struct DynamicsOptions {
  bool strip_inertia = false;  // Houbolt inertia of the strip (needs material.density > 0)
  bool lumped_mass = false;    // row-sum lumped instead of consistent mass
};
// The names of lumped_mass in scene files (dynamics.mass).
enum class MassMatrix { Consistent, Lumped };
template <>
struct EnumNames<MassMatrix> {
  static constexpr std::array<std::pair<MassMatrix, const char*>, 2> names{
      {{MassMatrix::Consistent, "consistent"}, {MassMatrix::Lumped, "lumped"}}};
};

struct Scene {
  std::filesystem::path file;  // where it was loaded from (empty for scenes built in code)
  std::string name;            // file stem unless given
  std::string title;
  StripMeshSpec mesh;
  MaterialParams material;
  // [[layer]] bands from the top over [material], and [material] yield_profile
  // (docs/model.md, Layered strips and hardness profiles); strip_material() combines them.
  std::vector<MaterialLayer> layers;
  YieldProfile yield_profile;
  bool mesh_follows_layers = false;  // [mesh] follow_layers: grid lines on the layers' boundaries
  ElementOptions element;
  StepControl steps;
  NewtonOptions newton;
  OutputOptions output;
  std::vector<DisplacementBC> displacements;
  std::vector<NodalLoad> loads;
  DynamicsOptions dynamics;
  std::optional<RollerSpec> roller;  // absent: no contact
  PassSpec passes;                   // the roller's path repeated (steps.count steps per pass)
  ContactOptions contact;
  // [fatigue]: the fatigue indices of every pass (docs/model.md, Fatigue); absent: none.
  std::optional<FatigueParams> fatigue;
  // Start from the strip state saved by another run (state file; roller and friction history
  // start afresh): [restart] from = "...", resolved against the scene file's folder.
  std::filesystem::path initial_state;

  // Steps of the whole run: steps.count times passes.count; one a pass with the stationary method.
  int total_steps() const;
  // The strip's material by depth: [material], the layers and the profile.
  LayeredMaterial strip_material() const { return LayeredMaterial{material, layers, yield_profile}; }
  // E/(1 - nu^2) of the top surface's material: what the roller's contact sees (Hertz's half-width).
  // With an elastic roller, the two bodies' 1/E* = 1/E*_strip + 1/E*_roller.
  Real contact_modulus() const;
  // [mesh] with the layers' boundaries pinned as grid lines when follow_layers is on.
  StripMeshSpec strip_mesh_spec() const;
};

}  // namespace roller
