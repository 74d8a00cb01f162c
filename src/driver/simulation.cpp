#include "roller/driver/simulation.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "roller/assembly/increment_energy.hpp"
#include "roller/contact/arc_predictor.hpp"
#include "roller/contact/backend_factory.hpp"
#include "roller/contact/contact_set.hpp"
#include "roller/contact/rolling_predictor.hpp"
#include "roller/core/error.hpp"
#include "roller/driver/force_control.hpp"
#include "roller/driver/memory_estimate.hpp"
#include "roller/io/scene_loader.hpp"
#include "roller/solver/blas_buffers.hpp"

namespace roller {

namespace {

// One solve of an increment (Newton or contact) into its counters: the outcome of the last
// solve, the work of all of them (a suspended roller solves the contact several times).
template <class Report>
void add_solve(Simulation::Increment& inc, const Report& r) {
  inc.converged = r.converged();
  inc.iterations += r.iterations;
  inc.factorizations += r.factorizations;
  inc.residual = r.residual;
  inc.message = r.message;
}

// A contact solve also adds its backend's work counters (solver.csv).
void add_solve(Simulation::Increment& inc, const BackendResult& r) {
  add_solve<BackendResult>(inc, r);
  inc.stats.add(r.stats);
}

// The mesh, once the machine is known to hold the run it starts (else a SystemError with advice).
Mesh make_mesh_that_fits(const Scene& scene) {
  // The condensed ipopt solve keeps a constant tangent's factors for the run.
  const bool held = scene.roller && scene.contact.backend == ContactBackendKind::Ipopt &&
                    scene.contact.ipopt.formulation == IpoptFormulation::Condensed &&
                    tangent_is_constant(scene.element.kinematics, scene.material);
  if (const auto available = available_memory()) {
    check_run_memory(scene.mesh, scene.newton.linear, *available,
                     held ? HeldFactors::WholeRun : HeldFactors::PerIncrement);
    if (available->address_space_limit) map_blas_buffers();
  }
  return make_strip_mesh(scene.mesh);
}

// A strip near incompressibility makes the tangent ill-conditioned, which smaller steps do not
// cure: a failed step says so (the bulk modulus K over the shear modulus G).
std::string incompressibility_hint(const MaterialParams& m) {
  if (!(m.poisson_ratio > 0.499)) return "";
  return fmt::format(
      "; material.nu = {} makes the strip nearly incompressible (K/G = {:.3g}) and its tangent "
      "ill-conditioned: use nu <= 0.499 (0.49 gives K/G = 24.7)",
      m.poisson_ratio, m.bulk_modulus() / m.shear_modulus());
}

}  // namespace

Simulation::Simulation(Scene scene)
    : scene_(std::move(scene)),
      model_(std::make_unique<StripModel>(make_mesh_that_fits(scene_), scene_.material, scene_.element)),
      loads_(scene_, model_->mesh()) {
  model_->set_dof_map(loads_.dof_map());
  if (scene_.roller) {
    backend_ = make_contact_backend(scene_.contact, scene_.newton);
    NodeSelector sel;
    sel.set_name = scene_.contact.candidates;
    candidate_nodes_ = resolve_nodes(sel, model_->mesh(), "contact.candidates");
    state_.pose = roller_pose(*scene_.roller, start_centre(), 0.0);
  }
  if (!scene_.initial_state.empty()) load_state(scene_.initial_state, /*strip_only=*/true);
  if (scene_.roller && scene_.roller->touch_strip) {
    start_lift_ = touching_lift();
    state_.pose = roller_pose(*scene_.roller, start_centre(), 0.0);
  }
  if (scene_.roller) check_roller_starts_outside();
  // After the initial state: a restarted strip starts at rest in its new configuration.
  dynamics_ = DynamicsState(*model_, scene_.dynamics.strip_inertia, scene_.dynamics.lumped_mass,
                            scene_.roller ? scene_.roller->suspension : std::nullopt, scene_.steps.dt);
  if (scene_.passes.count > 1) state_.pass_baseline = PassBaseline::of(*model_);
}

void Simulation::check_roller_starts_outside() const {
  // A roller that starts inside the strip has no admissible first increment; the solvers would
  // blame the supports or the step size instead.
  const std::vector<Vec2> x = model_->current_coordinates();
  const Real radius = scene_.roller->radius;
  Real depth = 0.0;
  Index deepest = -1;
  for (Index a : candidate_nodes_) {
    const Real d = radius - (x[a] - state_.pose.centre).norm();
    if (d > depth) {
      depth = d;
      deepest = a;
    }
  }
  // A roller under the strip would press it from below, which no path of ours means.
  Real bottom = x.front().y();
  for (const Vec2& p : x) bottom = std::min(bottom, p.y());
  if (state_.pose.centre.y() + radius < bottom)
    throw InputError(fmt::format(
        "{}: roller.centre = [{}, {}]: the roller lies entirely below the strip (its top at y = {:.6g} mm, the "
        "strip's bottom at y = {:.6g} mm); expected a centre above the strip's top surface",
        scene_.file.string(), state_.pose.centre.x(), state_.pose.centre.y(), state_.pose.centre.y() + radius, bottom));
  // Below 1e-6 R an overlap is the rounding of a touching start (the thesis's Z4 corner: 3e-8 R).
  if (depth > 1e-6 * radius)
    throw InputError(fmt::format(
        "{}: roller.centre = [{}, {}]: the roller starts inside the strip (node {} at ({:.6g}, {:.6g}) mm lies "
        "{:.4g} mm inside it); expected a start on or above the surface: raise the centre by at least {:.4g} mm, "
        "or press in with a [[roller.path]] segment (dy < 0)",
        scene_.file.string(), state_.pose.centre.x(), state_.pose.centre.y(), deepest + 1, x[deepest].x(),
        x[deepest].y(), depth, depth));
}

Vec2 Simulation::given_start_centre() const {
  // Default: touching the top of the strip at mid-length.
  return scene_.roller->start_centre.value_or(
      Vec2(0.5 * scene_.mesh.length, scene_.mesh.height + scene_.roller->radius));
}

Vec2 Simulation::start_centre() const { return given_start_centre() + Vec2(0.0, start_lift_); }

Real Simulation::touching_lift() const {
  // The lowest centre height at the start's x for which no candidate lies inside the circle.
  const std::vector<Vec2> x = model_->current_coordinates();
  const Real radius = scene_.roller->radius;
  const Vec2 given = given_start_centre();
  std::optional<Real> touch;
  for (Index a : candidate_nodes_) {
    const Real dx = x[a].x() - given.x();
    if (std::abs(dx) >= radius) continue;
    const Real y = x[a].y() + std::sqrt(radius * radius - dx * dx);
    touch = std::max(touch.value_or(y), y);
  }
  if (!touch)
    throw InputError(
        fmt::format("{}: roller.touch_strip = true: no contact candidate lies under the roller at x = {} "
                    "(within its radius {} mm); move roller.centre over the strip",
                    scene_.file.string(), given.x(), radius));
  return *touch - given.y();
}

Vec2 Simulation::roller_force() const {
  Vec2 f = Vec2::Zero();
  for (const auto& c : state_.contact) f -= c.force;
  return f;
}

RollerPose Simulation::prescribed_pose(Real s) const {
  const PassPosition at = locate_pass(s, scene_.steps.n_steps);
  return pose_in_pass(at.pass, at.local);
}

RollerPose Simulation::pose_in_pass(int pass, Real local) const {
  Vec2 start;
  const RollerSpec spec =
      roller_of_pass(*scene_.roller, scene_.passes, pass, start_centre(), scene_.steps.n_steps, &start);
  return roller_pose(spec, start, local);
}

PrescribedForce Simulation::prescribed_force(Real s) const {
  if (!scene_.roller) return {};
  const PassPosition at = locate_pass(s, scene_.steps.n_steps);
  Vec2 start;
  return roller::prescribed_force(
      roller_of_pass(*scene_.roller, scene_.passes, at.pass, start_centre(), scene_.steps.n_steps, &start), at.local);
}

std::vector<PressureSample> Simulation::pressure_profile() const {
  std::vector<PressureSample> out;
  for (const auto& c : state_.contact) {
    const bool loaded = c.contact.status != ContactStatus::Open;
    out.push_back(
        {c.position.x() - state_.pose.centre.x(), loaded ? c.contact.normal_force / c.tributary_length : 0.0});
  }
  return out;
}

void Simulation::solve_contact(IncrementEnergy& energy, const VecX& prescribed, const VecX& predictor,
                               RollerMotion& motion, VecX& x, Solution& solution,
                               const std::optional<RollerPotential>& potential) {
  // Nodes farther from the roller than it can travel within the increment cannot touch it.
  const Real reach = 0.05 * motion.radius + 4.0 * motion.dc().norm() + 4.0 * predictor.cwiseAbs().maxCoeff();
  std::vector<ContactCandidate> candidates = make_contact_candidates(*model_, candidate_nodes_, prescribed, predictor,
                                                                     motion.end.centre, motion.radius, reach);
  state_.friction.seed(candidates);
  // A later pass of the same increment (the suspension's or the load's coupling) moved the roller
  // only a little: its friction fixed point starts from the last pass's normal forces, not from
  // the previous increment's, and so needs no more linearisations than the move itself.
  if (solution.contact.converged()) seed_normal_forces(candidates, solution.candidates, solution.contact.contact);
  IncrementProblem problem(energy, candidates, motion, scene_.material.youngs_modulus, scene_.material.poisson_ratio);
  if (potential) problem.free_roller(*potential, 0.0);  // w measured from where `motion` puts the centre
  BackendResult result = backend_->solve(problem, x);
  // The extrapolated predictor misleads when the roller path turns (press -> roll, the
  // harmonic's crests): retry once from the start-of-step configuration before giving up.
  if (!result.converged() && x.squaredNorm() > 0.0) {
    const int spent = result.iterations;
    problem.move_roller(0.0);
    result = backend_->solve(problem, VecX::Zero(x.size()));
    result.iterations += spent;
  }
  if (result.converged()) x = result.x;
  if (result.converged() && potential) motion.end.centre.y() += result.roller_offset.value_or(0.0);
  solution.candidates = std::move(candidates);
  solution.contact = std::move(result);
}

bool Simulation::joint_height() const {
  return scene_.contact.roller_coupling == RollerCoupling::Joint && backend_->solves_roller_height();
}

std::optional<Real> Simulation::solve_height_jointly(IncrementEnergy& energy, const VecX& prescribed,
                                                     const VecX& predictor, RollerMotion& motion, VecX& x,
                                                     Solution& solution, Increment& inc,
                                                     const RollerPotential& potential, Real max_offset) {
  const VecX x0 = x;
  const Real y0 = motion.end.centre.y();
  solve_contact(energy, prescribed, predictor, motion, x, solution, potential);
  add_solve(inc, solution.contact);
  const Real offset = motion.end.centre.y() - y0;
  if (solution.contact.converged() && solution.contact.roller_offset && std::abs(offset) <= max_offset) return offset;
  // Not solved jointly (the condensed formulation failed): everything as it was, for the passes.
  x = x0;
  solution.contact = BackendResult{};
  motion.end.centre.y() = y0;
  return std::nullopt;
}

void Simulation::record_contact(const std::vector<ContactCandidate>& candidates, const BackendResult& result,
                                const VecX& u) {
  state_.contact.clear();
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const ContactCandidate& c = candidates[i];
    const NodeContact& nc = result.contact[i];
    NodeContactRecord rec;
    rec.node = c.node;
    rec.position = c.position + Vec2(u(2 * c.node), u(2 * c.node + 1));
    rec.contact = nc;
    rec.tributary_length = c.tributary_length;
    rec.element_size = c.element_size;
    rec.force = contact_force(nc.normal_force, nc.tangential_force, (rec.position - state_.pose.centre).normalized(),
                              c.tangent);
    state_.contact.push_back(rec);
  }
  state_.friction.record(candidates, result.contact);
}

Simulation::Increment Simulation::advance(Real s_from, Real s_to) {
  Increment inc;
  // Prescribed increments: target total minus what the dof already has, so sub-increments
  // never accumulate drift.
  const VecX prescribed = loads_.prescribed_displacement(s_to) - model_->total_displacement();
  IncrementEnergy energy(*model_, prescribed, loads_.external_force(s_to),
                         dynamics_.begin_increment((s_to - s_from) * scene_.steps.dt));
  RollerMotion motion;
  if (scene_.roller) {
    motion.radius = scene_.roller->radius;
    motion.start = state_.pose;
    motion.end = prescribed_pose(s_to);
    motion.end.centre += state_.load_offset;
    const Real local = locate_pass(s_to, scene_.steps.n_steps).local;
    motion.friction =
        friction_in_step(*scene_.roller, static_cast<int>(std::ceil(local - 1e-12)), scene_.contact.friction);
  }
  const Solution solution =
      solve_increment(energy, prescribed, predictor(s_from, s_to, scene_.roller ? &motion : nullptr), motion,
                      prescribed_force(s_to), inc);
  if (inc.converged) commit(solution, motion, s_from, s_to, inc);
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

Simulation::Solution Simulation::solve_increment(IncrementEnergy& energy, const VecX& prescribed, VecX predictor,
                                                 RollerMotion& motion, const PrescribedForce& force, Increment& inc) {
  VecX x = model_->dof_map().restrict_to_free(predictor);
  Solution solution;
  solution.load_offset = state_.load_offset;
  solution.load_stiffness = state_.load_stiffness;
  if (!scene_.roller) {
    add_solve(inc, newton_.minimise(energy, x, scene_.newton));
    solution.u = energy.full_increment(x);
    return solution;
  }
  if (dynamics_.suspension()) {
    solution = solve_suspended(energy, prescribed, predictor, motion, x, inc);
  } else if (force.any()) {
    solution = solve_loaded(force, energy, prescribed, predictor, motion, x, inc);
  } else {
    solve_contact(energy, prescribed, predictor, motion, x, solution);
    add_solve(inc, solution.contact);
  }
  inc.max_penetration = solution.contact.max_penetration;
  if (inc.converged) solution.u = energy.full_increment(solution.contact.x);
  return solution;
}

Simulation::Solution Simulation::solve_suspended(IncrementEnergy& energy, const VecX& prescribed, const VecX& predictor,
                                                 RollerMotion& motion, VecX& x, Increment& inc) {
  // The roller hangs at anchor + w; w and the contact converge together (suspension.hpp).
  Solution solution;
  const Vec2 anchor = motion.end.centre;
  auto force_at = [&](Real w) -> std::optional<Real> {
    motion.end.centre = anchor + Vec2(0.0, w);
    solve_contact(energy, prescribed, predictor, motion, x, solution);
    add_solve(inc, solution.contact);
    if (!solution.contact.converged()) return std::nullopt;
    return strip_force(solution, motion, energy).y();
  };
  const Suspension& suspension = *dynamics_.suspension();
  // A deflection beyond the reach allowed for the scene's motions (docs/scenes.md, Loading rules).
  const Real max_deflection = 1e3 * std::max(scene_.mesh.length, scene_.mesh.height);
  if (joint_height()) {
    // The deflection as an unknown of the contact solve: the roller's potential k_eff w^2/2 + h w
    // in w = w0 + offset.
    const Real w0 = suspension.predicted_deflection();
    motion.end.centre = anchor + Vec2(0.0, w0);
    RollerPotential spring;
    spring.stiffness = suspension.effective_stiffness();
    spring.load = suspension.effective_stiffness() * w0 + suspension.history_force();
    if (const auto offset =
            solve_height_jointly(energy, prescribed, predictor, motion, x, solution, inc, spring, max_deflection)) {
      inc.suspension_passes = 1;
      solution.deflection = w0 + *offset;
      return solution;
    }
  }
  const CouplingResult cr = couple_suspension(suspension, suspension.predicted_deflection(), force_at,
                                              1e-10 * motion.radius, max_deflection, 40);
  inc.suspension_passes = cr.iterations;
  if (!cr.converged) {
    inc.converged = false;
    inc.message = cr.message;
  }
  solution.deflection = cr.deflection;
  return solution;
}

Vec2 Simulation::strip_force(const Solution& solution, const RollerMotion& motion, IncrementEnergy& energy) const {
  const BackendResult& r = solution.contact;
  const VecX u = energy.full_increment(r.x);
  Vec2 f = Vec2::Zero();
  for (std::size_t i = 0; i < solution.candidates.size(); ++i) {
    const ContactCandidate& c = solution.candidates[i];
    const Vec2 xi = c.position + Vec2(u(2 * c.node), u(2 * c.node + 1));
    const Vec2 n = (xi - motion.end.centre).normalized();
    f -= contact_force(r.contact[i].normal_force, r.contact[i].tangential_force, n, c.tangent);
  }
  return f;
}

Simulation::Solution Simulation::solve_loaded(const PrescribedForce& force, IncrementEnergy& energy,
                                              const VecX& prescribed, const VecX& predictor, RollerMotion& motion,
                                              VecX& x, Increment& inc) {
  // The centre sits at the path's position plus an offset that carries the forces
  // (force_control.hpp).
  Solution solution;
  solution.load_offset = state_.load_offset;
  solution.load_stiffness = state_.load_stiffness;
  const Vec2 path = motion.end.centre - state_.load_offset;
  // 1e-6 of the largest force of the path: far below what a user reads, far above the contact
  // solves' own accuracy. A horizontal force is measured against the vertical one as well (a
  // traction of 0 under a prescribed depth).
  Vec2 largest(force.fx ? std::abs(*force.fx) : 0.0, force.fy ? *force.fy : 0.0);
  for (const PathSegment& seg : scene_.roller->path) {
    if (seg.fx) largest.x() = std::max(largest.x(), std::abs(*seg.fx));
    if (seg.fy) largest.y() = std::max(largest.y(), *seg.fy);
  }
  // Line contact is about as stiff as E* per unit length, normally and tangentially; later
  // increments use the last slopes.
  auto settings = [&](ForceAxis axis) {
    ForceControlSettings s;
    s.axis = axis;
    const int k = axis == ForceAxis::Vertical ? 1 : 0;
    s.stiffness_guess =
        solution.load_stiffness(k) > 0.0 ? solution.load_stiffness(k) : scene_.material.plane_strain_modulus();
    if (axis == ForceAxis::Vertical) {
      s.force_tolerance = 1e-6 * largest.y();
      s.max_offset_change = 1e3 * std::max(scene_.mesh.length, scene_.mesh.height);
    } else {
      const Real scale = std::max({largest.x(), largest.y(), roller_force().norm()});
      s.force_tolerance = 1e-6 * (scale > 0.0 ? scale : 1e-6 * scene_.material.plane_strain_modulus() * motion.radius);
      // A roller that must move sideways by its radius within one increment to carry the force
      // is sliding, not held by friction.
      s.max_offset_change = std::min(motion.radius, std::max(scene_.mesh.length, scene_.mesh.height));
    }
    return s;
  };
  std::string failure;  // the first failure's message (an inner one says more than the outer)
  auto fail = [&](const std::string& message) {
    if (failure.empty()) failure = message;
    return std::nullopt;
  };
  // One contact solve at the centre's current x, under the prescribed vertical force if any:
  // the strip's force on the roller, or nullopt.
  auto solve_at_x = [&]() -> std::optional<Vec2> {
    auto solve = [&]() -> std::optional<Vec2> {
      solve_contact(energy, prescribed, predictor, motion, x, solution);
      add_solve(inc, solution.contact);
      if (!solution.contact.converged()) return std::nullopt;
      return strip_force(solution, motion, energy);
    };
    if (!force.fy) {
      const std::optional<Vec2> f = solve();
      if (!f) return fail(fmt::format("the contact solve failed: {}", solution.contact.message));
      return f;
    }
    // The roller on the strip already (the last increment's contact): the height as an unknown of
    // the contact solve, the load's potential F w (IncrementProblem::free_roller with stiffness 0), so
    // F_y = F at the solution. A roller still to meet the strip finds it by passes: nothing sets
    // the joint solve's length scale and working set before contact.
    if (state_.friction.touching() && joint_height()) {
      const Real w0 = solution.load_offset.y();
      motion.end.centre.y() = path.y() + w0;
      RollerPotential load;
      load.load = *force.fy;
      ++inc.load_passes;
      if (const auto offset = solve_height_jointly(energy, prescribed, predictor, motion, x, solution, inc, load,
                                                   settings(ForceAxis::Vertical).max_offset_change)) {
        solution.load_offset.y() = w0 + *offset;
        return strip_force(solution, motion, energy);
      }
    }
    std::optional<Vec2> last;
    auto fy_at = [&](Real w) -> std::optional<Real> {
      motion.end.centre.y() = path.y() + w;
      last = solve();
      if (!last) return std::nullopt;
      return last->y();
    };
    const ForceControlResult fc =
        solve_for_force(*force.fy, solution.load_offset.y(), settings(ForceAxis::Vertical), fy_at);
    inc.load_passes += fc.iterations;
    if (!fc.converged) return fail(fc.message);
    solution.load_offset.y() = fc.offset;
    solution.load_stiffness.y() = fc.stiffness;
    return last;
  };
  if (!force.fx) {
    if (!solve_at_x()) {
      inc.converged = false;
      inc.message = failure;
    }
    return solution;
  }
  auto fx_at = [&](Real w) -> std::optional<Real> {
    motion.end.centre.x() = path.x() + w;
    const std::optional<Vec2> f = solve_at_x();
    if (!f) return std::nullopt;
    if (!force.fy) ++inc.load_passes;  // a solve per x; counted within the vertical iteration otherwise
    return f->x();
  };
  const ForceControlResult fc =
      solve_for_force(*force.fx, state_.load_offset.x(), settings(ForceAxis::Horizontal), fx_at);
  if (!fc.converged) {
    inc.converged = false;
    inc.message = failure.empty() ? fc.message : failure;
    return solution;
  }
  solution.load_offset.x() = fc.offset;
  solution.load_stiffness.x() = fc.stiffness;
  return solution;
}

void Simulation::commit(const Solution& solution, const RollerMotion& motion, Real s_from, Real s_to, Increment& inc) {
  try {
    inc.n_yielded = model_->commit(solution.u);
  } catch (const NumericalError& e) {
    // A solver reported success at a state the strip cannot take (e.g. an inverted element):
    // treat it as a failed increment so the step is cut; nothing was committed.
    inc.converged = false;
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
    record_contact(solution.candidates, solution.contact, solution.u);
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
  const RollerPose start = pose_in_pass(pass, 0.0);
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
  for (const auto& c : state_.contact) {
    if (c.contact.status == ContactStatus::Open) continue;
    x.push_back(c.position.x());
    p.push_back(c.contact.normal_force / c.tributary_length);
  }
  state_.pass_track.observe(state_.pose.centre.x(), x, p);
  if (step % scene_.steps.n_steps != 0) return std::nullopt;
  StepRecord::PassEnd end;
  end.record = measure_pass(pass_of_step(step), *model_, scene_.mesh.height, state_.pass_track, state_.pass_baseline);
  end.profile_x = 0.5 * (end.record.track_start + end.record.track_end);
  end.profile = depth_profile(*model_, scene_.mesh.height, end.profile_x);
  state_.pass_records.push_back(end.record);
  state_.pass_track = PassTrack{};
  state_.pass_baseline = PassBaseline::of(*model_);
  return end;
}

int Simulation::pass_of_step(int step) const { return locate_pass(step, scene_.steps.n_steps).pass; }

void Simulation::record_state(StepRecord& res) const {
  res.contact = state_.contact;
  res.kinetic_energy = dynamics_.kinetic_energy();
  if (!scene_.roller) return;
  RollerRecord r;
  r.pose = state_.pose;
  r.force = roller_force();
  r.velocity = state_.roller_velocity;
  r.anchor_y = prescribed_pose(res.step).centre.y();
  if (const Suspension* suspension = dynamics_.suspension()) r.deflection = suspension->deflection();
  r.deflection_velocity = dynamics_.suspension_velocity();
  r.deflection_acceleration = dynamics_.suspension_acceleration();
  r.prescribed = prescribed_force(res.step);
  r.load_offset = state_.load_offset;
  res.roller = r;
}

Simulation::StepRecord Simulation::advance_step(int step) {
  StepRecord res;
  res.step = step;
  res.pass = pass_of_step(step);
  res.time = step * scene_.steps.dt;
  // The first step of a pass after the first: the roller returns to the pass's start (undone
  // below if the step fails, so that a failed step changes nothing).
  std::optional<RunState> before_return;
  if (scene_.roller && step > 1 && (step - 1) % scene_.steps.n_steps == 0) {
    before_return = state_;
    res.message = return_for_pass(pass_of_step(step));
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
    Increment inc = advance(s, s + ds);
    res.iterations += inc.iterations;
    res.factorizations += inc.factorizations;
    res.stats.add(inc.stats);
    res.last = inc;
    if (inc.converged) {
      s += ds;
      res.max_penetration = std::max(res.max_penetration, inc.max_penetration);
      res.n_yielded = inc.n_yielded;
      continue;
    }
    if (res.cuts >= scene_.steps.max_cuts) {
      res.message = fmt::format("step {} failed after {} cuts (sub-increment {:.4g} of the step): {}{}", step, res.cuts,
                                ds, inc.message, incompressibility_hint(scene_.material));
      if (before_return && s == step - 1) {  // nothing of the step committed: undo the return too
        state_ = std::move(*before_return);
      }
      record_state(res);
      return res;
    }
    ++res.cuts;
    ds *= 0.5;
  }
  res.converged = true;
  state_.roller_velocity = (state_.pose.centre - centre_start) / scene_.steps.dt;
  ++state_.steps_done;
  dynamics_.finish_step(model_->total_displacement());
  res.pass_end = observe_pass(step);
  record_state(res);
  return res;
}

}  // namespace roller
