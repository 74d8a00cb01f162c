#include "roller/driver/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>

#include <fmt/format.h>

#include "roller/analysis/hertz.hpp"
#include "roller/assembly/increment_energy.hpp"
#include "roller/contact/arc_predictor.hpp"
#include "roller/contact/backend_factory.hpp"
#include "roller/contact/contact_set.hpp"
#include "roller/contact/rolling_predictor.hpp"
#include "roller/core/error.hpp"
#include "roller/driver/memory_estimate.hpp"
#include "roller/driver/scene_warnings.hpp"
#include "roller/driver/steady_load.hpp"
#include "roller/io/scene_loader.hpp"
#include "roller/mesh/mesh.hpp"
#include "roller/solver/blas_buffers.hpp"
#include "roller_start.hpp"
#include "stationary_passes.hpp"

namespace roller {

namespace {

// The mesh, once the machine is known to hold the run it starts (else a SystemError with advice).
Mesh make_mesh_that_fits(const Scene& scene) {
  // The condensed ipopt solve keeps a constant tangent's factors for the run.
  const bool held = scene.roller && scene.contact.backend == ContactBackendKind::Ipopt &&
                    scene.contact.ipopt.formulation == IpoptFormulation::Condensed &&
                    tangent_is_constant(scene.element.kinematics, scene.strip_material().any_plastic());
  if (const auto available = available_memory()) {
    const HeldFactors factors = scene.passes.method == PassMethod::Stationary ? HeldFactors::SteadyJacobian
                                : held                                        ? HeldFactors::WholeRun
                                                                              : HeldFactors::PerIncrement;
    check_run_memory(scene.strip_mesh_spec(), scene.newton.linear, *available, factors);
    if (available->address_space_limit) map_blas_buffers();
  }
  return make_strip_mesh(scene.strip_mesh_spec());
}

// The strip of the scene: each element of the mesh made of its centroid's layer.
std::unique_ptr<StripModel> make_strip(const Scene& scene) {
  check_load_fits_strip(scene);
  check_traction_below_friction(scene);
  Mesh mesh = make_mesh_that_fits(scene);
  ElementMaterials materials = assign_materials(mesh, scene.strip_material());
  return std::make_unique<StripModel>(std::move(mesh), std::move(materials), scene.element);
}

// A strip near incompressibility makes the tangent ill-conditioned, which smaller steps do not
// cure: a failed step says so (the bulk modulus K over the shear modulus G).
std::string incompressibility_hint(const LayeredMaterial& strip) {
  MaterialParams m = strip.base;
  m.poisson_ratio = strip.max_poisson_ratio();  // of the layer closest to incompressible
  if (!(m.poisson_ratio > 0.499)) return "";
  return fmt::format(
      "; material.nu = {} makes the strip nearly incompressible (K/G = {:.3g}) and its tangent "
      "ill-conditioned: use nu <= 0.499 (0.49 gives K/G = 24.7)",
      m.poisson_ratio, m.bulk_modulus() / m.shear_modulus());
}

// The nodes that may touch the roller (contact.candidates); none without a roller.
std::vector<Index> contact_candidate_nodes(const Scene& scene, const Mesh& mesh) {
  if (!scene.roller) return {};
  NodeSelector sel;
  sel.set_name = scene.contact.candidates;
  return resolve_nodes(sel, mesh, "contact.candidates");
}

// The contact of a converged increment, node by node, with the roller centred at `centre`.
std::vector<NodeContactRecord> contact_records(const IncrementSolution& solution, const Vec2& centre) {
  ROLLER_ASSERT(solution.contact.contact.size() == solution.candidates.size(), "one contact result per candidate");
  std::vector<NodeContactRecord> records;
  for (std::size_t i = 0; i < solution.candidates.size(); ++i) {
    const ContactCandidate& c = solution.candidates[i];
    const NodeContact& nc = solution.contact.contact[i];
    NodeContactRecord rec;
    rec.node = c.node;
    rec.position = c.position + Vec2(solution.u(2 * c.node), solution.u(2 * c.node + 1));
    rec.contact = nc;
    rec.tributary_length = c.tributary_length;
    rec.element_size = c.element_size;
    rec.force = contact_force(nc.normal_force, nc.tangential_force, (rec.position - centre).normalized(), c.tangent);
    records.push_back(rec);
  }
  return records;
}

}  // namespace

Simulation::Simulation(Scene scene)
    : scene_(std::move(scene)),
      model_(make_strip(scene_)),
      loads_(scene_, model_->mesh()),
      backend_(make_increment_backend(scene_.roller.has_value(), scene_.contact, scene_.newton)),
      candidate_nodes_(contact_candidate_nodes(scene_, model_->mesh())),
      solver_(scene_, *backend_, candidate_nodes_) {
  model_->set_dof_map(loads_.dof_map());
  if (!scene_.initial_state.empty()) load_state(scene_.initial_state, /*strip_only=*/true);
  Vec2 start_centre = Vec2::Zero();
  if (scene_.roller) {
    start_centre = given_start_centre(scene_);
    // A periodic strip's nodes at their images nearest the roller, as the contact sees them
    // (docs/model.md, Periodic strip): a roller over the seam touches the left edge's nodes too.
    std::vector<Vec2> x = model_->current_coordinates();
    for (Vec2& p : x) p.x() = nearest_image_x(model_->mesh(), p.x(), start_centre.x());
    if (scene_.roller->touch_strip) start_centre.y() += touching_lift(scene_, x, candidate_nodes_);
    check_roller_starts_outside(scene_, x, candidate_nodes_, start_centre);
    state_.pose = roller_pose(*scene_.roller, start_centre, 0.0);
  }
  program_ = RollerProgram(scene_.roller, scene_.passes, scene_.steps.n_steps, start_centre);
  // After the initial state: a restarted strip starts at rest in its new configuration.
  dynamics_ = DynamicsState(*model_, scene_.dynamics.strip_inertia, scene_.dynamics.lumped_mass,
                            scene_.roller ? scene_.roller->suspension : std::nullopt, scene_.steps.dt);
  if (scene_.passes.count > 1) state_.pass_baseline = PassBaseline::of(*model_);
}

IncrementStart Simulation::increment_start(Real s_to) const {
  IncrementStart start;
  start.friction = &state_.friction;
  start.suspension = dynamics_.suspension();
  start.load_offset = state_.load_offset;
  start.load_stiffness = state_.load_stiffness;
  if (!scene_.roller) return start;
  RollerMotion& motion = start.motion;
  motion.radius = scene_.roller->radius;
  motion.start = state_.pose;
  motion.end = program_.pose(s_to);
  motion.end.centre += state_.load_offset;
  motion.friction = program_.friction(s_to, scene_.contact.friction);
  start.force = program_.force(s_to);
  start.roller_force = roller_force();
  return start;
}

IncrementReport Simulation::advance(Real s_from, Real s_to) {
  IncrementReport inc;
  // Prescribed increments: target total minus what the dof already has, so sub-increments
  // never accumulate drift.
  const VecX prescribed = loads_.prescribed_displacement(s_to) - model_->total_displacement();
  IncrementEnergy energy(*model_, prescribed, loads_.external_force(s_to),
                         dynamics_.begin_increment((s_to - s_from) * scene_.steps.dt));
  IncrementStart start = increment_start(s_to);
  const IncrementSolution solution =
      solver_.solve(energy, prescribed, predictor(s_from, s_to, scene_.roller ? &start.motion : nullptr), start, inc);
  if (inc.converged()) commit(solution, start.motion, s_from, s_to, inc);
  return inc;
}

VecX Simulation::predictor(Real s_from, Real s_to, const RollerMotion* motion) const {
  // The previous converged increment scaled to this one's length (a linear extrapolation of the
  // path) starts Newton near the solution on smooth paths.
  VecX predictor = VecX::Zero(model_->n_dofs());
  if (state_.last_increment.size() == model_->n_dofs() && state_.last_length > 0.0)
    predictor = state_.last_increment * ((s_to - s_from) / state_.last_length);
  if (motion && scene_.contact.predictor == IncrementPredictor::Rolling)
    predictor = translate_increment(model_->mesh(), model_->current_coordinates(), predictor,
                                    motion->end.centre.x() - motion->start.centre.x());
  if (motion && scene_.contact.predictor == IncrementPredictor::Arc)
    // Nodes the extrapolation puts inside the roller start on its surface at the arc position
    // (4.25) instead (docs/model.md, Arc predictor).
    apply_arc_predictor(candidate_nodes_, model_->current_coordinates(), model_->dof_map(), *motion, predictor);
  return predictor;
}

void Simulation::commit(const IncrementSolution& solution, const RollerMotion& motion, Real s_from, Real s_to,
                        IncrementReport& inc) {
  ROLLER_ASSERT(inc.converged() && solution.u.size() == model_->n_dofs(), "a converged increment of all dofs");
  ROLLER_ASSERT(s_to > s_from, "an increment moves forward in steps");
  try {
    inc.n_yielded = model_->commit(solution.u);
  } catch (const NumericalError& e) {
    // A solver reported success at a state the strip cannot take (e.g. an inverted element):
    // treat it as a failed increment so the step is cut; nothing was committed.
    inc.status = Termination::Failed;
    inc.message = fmt::format("the increment's solution is not admissible: {}", e.what());
    return;
  }
  state_.last_increment = solution.u;
  state_.last_length = s_to - s_from;
  state_.load_offset = solution.load_offset;
  state_.load_stiffness = solution.load_stiffness;
  dynamics_.commit_increment(model_->total_displacement(), solution.deflection);
  if (scene_.roller) {
    state_.pose = motion.end;
    state_.contact = contact_records(solution, state_.pose.centre);
    state_.friction.record(solution.candidates, solution.contact.contact);
  }
}

std::string Simulation::return_for_pass(int pass) {
  // The roller must have left the strip: no node carries a contact force, and none lies within
  // the roller at the pass's start.
  const Index touching = count_in_contact(state_.contact);
  if (touching > 0)
    return fmt::format(
        "pass {} ends with the roller on the strip ({} nodes in contact): end each pass with a lift (a "
        "[[roller.path]] segment with dy > 0) so that the roller can return for pass {}",
        pass - 1, touching, pass);
  // Not prescribed_pose((pass - 1) N): that step belongs to the previous pass (its end).
  const RollerPose start = program_.pass_start(pass);
  const std::vector<Vec2> x = model_->current_coordinates();
  for (Index a : candidate_nodes_)
    if ((x[a] - start.centre).norm() < (1.0 - 1e-9) * scene_.roller->radius)  // touching is clear
      return fmt::format(
          "pass {} would start with node {} inside the roller at ({:.6g}, {:.6g}): start the pass "
          "clear of the strip (roller.centre) or press in from above",
          pass, a + 1, start.centre.x(), start.centre.y());
  state_.pose = start;
  state_.load_offset.setZero();     // each pass meets the strip as the first did
  state_.last_increment.setZero();  // the lift is no predictor of the press
  state_.contact.clear();
  return "";
}

std::optional<Simulation::StepRecord::PassEnd> Simulation::observe_pass(int step) {
  if (scene_.passes.count < 2) return std::nullopt;
  std::vector<Real> x, p;
  Real force = 0.0;
  for (const auto& c : state_.contact) {
    if (c.contact.status == ContactStatus::Open) continue;
    x.push_back(c.position.x());
    p.push_back(c.contact.normal_force / c.tributary_length);
    force += c.contact.normal_force;
  }
  const Real e_star = scene_.contact_modulus();
  const Real load_half_width = force > 0.0 ? hertz_line_contact(force, scene_.roller->radius, e_star).half_width : 0.0;
  state_.pass_track.observe(state_.pose.centre.x(), x, p, load_half_width);
  if (!program_.ends_pass(step)) return std::nullopt;
  StepRecord::PassEnd end;
  end.record =
      measure_pass(program_.pass_of_step(step), *model_, scene_.mesh.height, state_.pass_track, state_.pass_baseline);
  end.profile_x = 0.5 * (end.record.track_start + end.record.track_end);
  end.profile = depth_profile(*model_, scene_.mesh.height, end.profile_x);
  state_.pass_records.push_back(end.record);
  state_.pass_track = PassTrack{};
  state_.pass_baseline = PassBaseline::of(*model_);
  return end;
}

void Simulation::record_state(StepRecord& res) const {
  res.contact = state_.contact;
  res.kinetic_energy = dynamics_.kinetic_energy();
  if (!scene_.roller) return;
  RollerRecord r;
  r.pose = state_.pose;
  r.force = roller_force();
  r.velocity = state_.roller_velocity;
  // A stationary pass (one step) carries its travel segment's load whole, not the ramp the step's
  // number would read in a transient pass's program.
  const int program_step =
      scene_.passes.method == PassMethod::Stationary ? steady_load(scene_, std::nullopt).travel->last_step : res.step;
  r.anchor_y = program_.pose(program_step).centre.y();
  if (const Suspension* suspension = dynamics_.suspension()) r.deflection = suspension->deflection();
  r.deflection_velocity = dynamics_.suspension_velocity();
  r.deflection_acceleration = dynamics_.suspension_acceleration();
  r.prescribed = program_.force(program_step);
  r.load_offset = state_.load_offset;
  res.roller = r;
}

Simulation::~Simulation() = default;
Simulation::Simulation(Simulation&&) noexcept = default;

Simulation::StepRecord Simulation::advance_step(int step) {
  if (scene_.passes.method == PassMethod::Stationary) return advance_stationary(step);
  StepRecord res;
  res.step = step;
  res.pass = program_.pass_of_step(step);
  res.time = step * scene_.steps.dt;
  // The first step of a pass after the first: the roller returns to the pass's start (undone
  // below if the step fails, so that a failed step changes nothing).
  std::optional<RunState> before_return;
  if (scene_.roller && program_.starts_later_pass(step)) {
    before_return = state_;
    res.message = return_for_pass(program_.pass_of_step(step));
    if (!res.message.empty()) {
      record_state(res);
      return res;
    }
  }
  const Vec2 centre_start = state_.pose.centre;
  // Sub-increments of 1/2^cuts of the step; a failed sub-increment is halved again.
  Real s = step - 1;
  Real ds = 1.0;
  while (s < step - 1e-12) {
    IncrementReport inc = advance(s, s + ds);
    res.counters += inc.counters;
    res.details.add(inc.details);
    res.last = inc;
    if (inc.converged()) {
      s += ds;
      res.max_penetration = std::max(res.max_penetration, inc.max_penetration);
      res.n_yielded = inc.n_yielded;
      continue;
    }
    if (res.cuts >= scene_.steps.max_cuts) {
      res.status = inc.status;  // how the last sub-increment ended: a budget ran out, or it failed
      res.message = fmt::format("step {} failed after {} cuts (sub-increment {:.4g} of the step): {}{}", step, res.cuts,
                                ds, inc.message, incompressibility_hint(scene_.strip_material()));
      if (before_return && s == step - 1) {  // nothing of the step committed: undo the return too
        state_ = std::move(*before_return);
      }
      record_state(res);
      return res;
    }
    ++res.cuts;
    ds *= 0.5;
  }
  res.status = Termination::Converged;
  state_.roller_velocity = (state_.pose.centre - centre_start) / scene_.steps.dt;
  ++state_.steps_done;
  dynamics_.finish_step(model_->total_displacement());
  res.pass_end = observe_pass(step);
  record_state(res);
  return res;
}

}  // namespace roller
