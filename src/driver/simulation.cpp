#include "roller/driver/simulation.hpp"

#include <cmath>

#include <fmt/format.h>

#include "roller/assembly/increment_energy.hpp"
#include "roller/contact/arc_predictor.hpp"
#include "roller/contact/contact_set.hpp"
#include "roller/core/error.hpp"
#include "roller/io/scene_loader.hpp"

namespace roller {

namespace {

// M restricted to the free dofs (rows and columns in free numbering).
SparseMatrix restrict_to_free(const SparseMatrix& m, const DofMap& dofs) {
  std::vector<Triplet> t;
  for (int k = 0; k < m.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(m, k); it; ++it) {
      const Index i = dofs.free_index(it.row()), j = dofs.free_index(it.col());
      if (i >= 0 && j >= 0) t.emplace_back(static_cast<int>(i), static_cast<int>(j), it.value());
    }
  SparseMatrix out(dofs.n_free(), dofs.n_free());
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

}  // namespace

Simulation::Simulation(Scene scene)
    : scene_(std::move(scene)),
      model_(std::make_unique<StripModel>(make_strip_mesh(scene_.mesh), scene_.material, scene_.element)),
      loads_(scene_, model_->mesh()) {
  model_->set_dof_map(loads_.dof_map());
  if (scene_.roller) {
    backend_ = make_contact_backend(scene_.contact, scene_.newton);
    NodeSelector sel;
    sel.set_name = scene_.contact.candidates;
    candidate_nodes_ = resolve_nodes(sel, model_->mesh(), "contact.candidates");
    pose_ = roller_pose(*scene_.roller, start_centre(), 0.0);
  }
  if (!scene_.initial_state.empty()) load_state(scene_.initial_state, /*strip_only=*/true);
  start_dynamics();
}

void Simulation::start_dynamics() {
  const Real dt = scene_.steps.dt;
  if (scene_.dynamics.strip_inertia) {
    // The Lagrangian mass rho0 dV0 is constant: built once on the mesh at the start.
    mass_ = model_->mass_matrix(scene_.dynamics.lumped_mass);
    mass_free_ = restrict_to_free(mass_, model_->dof_map());
    // The strip starts at rest in its current configuration (a restarted strip included).
    strip_step_history_ = HouboltHistory::at_rest(model_->total_displacement(), dt);
    strip_history_ = strip_step_history_;
    velocity_ = VecX::Zero(model_->n_dofs());
    acceleration_ = VecX::Zero(model_->n_dofs());
  }
  if (scene_.roller && scene_.roller->suspension) {
    suspension_step_ = Suspension(*scene_.roller->suspension, HouboltHistory::at_rest(VecX::Zero(1), dt));
    suspension_ = suspension_step_;
  }
}

Vec2 Simulation::start_centre() const {
  if (scene_.roller->start_centre) return *scene_.roller->start_centre;
  // Default: touching the top of the strip at mid-length.
  return Vec2(0.5 * scene_.mesh.length, scene_.mesh.height + scene_.roller->radius);
}

Vec2 Simulation::roller_force() const {
  Vec2 f = Vec2::Zero();
  for (const auto& c : contact_) f -= c.force;
  return f;
}

Real Simulation::kinetic_energy() const {
  if (velocity_.size() == 0) return 0.0;
  return 0.5 * velocity_.dot(mass_ * velocity_);
}

std::vector<PressureSample> Simulation::pressure_profile() const {
  std::vector<PressureSample> out;
  for (const auto& c : contact_) {
    const bool loaded = c.contact.status != ContactStatus::Open;
    out.push_back({c.position.x() - pose_.centre.x(), loaded ? c.contact.normal_force / c.tributary_length : 0.0});
  }
  return out;
}

BackendResult Simulation::solve_contact(IncrementEnergy& energy, const VecX& prescribed, const VecX& predictor,
                                        RollerMotion& motion, VecX& x, std::vector<ContactCandidate>& candidates) {
  // Nodes farther from the roller than it can travel within the increment cannot touch it.
  const Real reach = 0.05 * motion.radius + 4.0 * motion.dc().norm() + 4.0 * predictor.cwiseAbs().maxCoeff();
  candidates = make_contact_candidates(*model_, candidate_nodes_, prescribed, predictor, motion.end.centre,
                                       motion.radius, reach);
  for (auto& c : candidates) {
    const auto h = history_.find(c.node);
    if (h == history_.end()) continue;
    c.tangential_force = h->second.tangential_force;
    c.normal_force_guess = h->second.normal_force;
  }
  IncrementProblem problem(energy, candidates, motion, scene_.material.youngs_modulus,
                           scene_.material.poisson_ratio);
  BackendResult result = backend_->solve(problem, x);
  // The extrapolated predictor misleads when the roller path turns (press -> roll, the
  // harmonic's crests): retry once from the start-of-step configuration before giving up.
  if (!result.converged() && x.squaredNorm() > 0.0) {
    const int spent = result.iterations;
    result = backend_->solve(problem, VecX::Zero(x.size()));
    result.iterations += spent;
  }
  if (result.converged()) x = result.x;
  return result;
}

void Simulation::record_contact(const std::vector<ContactCandidate>& candidates, const BackendResult& result,
                                const VecX& u) {
  contact_.clear();
  history_.clear();
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const ContactCandidate& c = candidates[i];
    const NodeContact& nc = result.contact[i];
    NodeContactRecord rec;
    rec.node = c.node;
    rec.position = c.position + Vec2(u(2 * c.node), u(2 * c.node + 1));
    rec.contact = nc;
    rec.tributary_length = c.tributary_length;
    rec.element_size = c.element_size;
    rec.force = contact_force(nc.normal_force, nc.tangential_force, (rec.position - pose_.centre).normalized(),
                              c.tangent);
    contact_.push_back(rec);
    if (nc.status != ContactStatus::Open) history_[c.node] = nc;
  }
}

Simulation::Increment Simulation::advance(Real s_from, Real s_to) {
  Increment inc;
  const Real h = (s_to - s_from) * scene_.steps.dt;  // time of this increment
  // Prescribed increments: target total minus what the dof already has, so sub-increments
  // never accumulate drift.
  const VecX prescribed = loads_.prescribed_displacement(s_to) - model_->total_displacement();
  std::optional<InertiaTerm> inertia;
  if (scene_.dynamics.strip_inertia) {
    if (strip_history_.dt() != h) strip_history_ = strip_history_.resampled(h);
    inertia = InertiaTerm{&mass_, &mass_free_, strip_history_.acceleration_coefficient(),
                          mass_ * (strip_history_.acceleration_coefficient() * strip_history_.u_n() +
                                   strip_history_.acceleration_offset())};
  }
  if (suspension_ && suspension_->history().dt() != h)
    suspension_->history() = suspension_->history().resampled(h);
  IncrementEnergy energy(*model_, prescribed, loads_.external_force(s_to), std::move(inertia));
  // Predictor: the previous converged increment scaled to this one's length (a linear
  // extrapolation of the path), which starts Newton near the solution on smooth paths.
  VecX predictor = VecX::Zero(model_->n_dofs());
  if (last_increment_.size() == model_->n_dofs() && last_length_ > 0.0)
    predictor = last_increment_ * ((s_to - s_from) / last_length_);
  VecX x = model_->dof_map().restrict_to_free(predictor);

  VecX u;
  std::vector<ContactCandidate> candidates;
  BackendResult contact_result;
  RollerMotion motion;
  Real deflection = 0.0;
  auto take = [&inc](const auto& r) {
    inc.converged = r.converged();
    inc.iterations += r.iterations;
    inc.factorizations += r.factorizations;
    inc.residual = r.residual;
    inc.message = r.message;
  };
  if (!scene_.roller) {
    take(minimise_newton(energy, x, scene_.newton));
    u = energy.full_increment(x);
  } else {
    motion.radius = scene_.roller->radius;
    motion.start = pose_;
    motion.end = roller_pose(*scene_.roller, start_centre(), s_to);
    motion.friction = scene_.contact.friction;
    if (scene_.contact.predictor == IncrementPredictor::Arc) {
      // Thesis §4.2.3: nodes the extrapolated predictor puts inside the roller start on its
      // surface at the arc position (4.25) instead.
      apply_arc_predictor(candidate_nodes_, model_->current_coordinates(), model_->dof_map(), motion, predictor);
      x = model_->dof_map().restrict_to_free(predictor);
    }
    if (!suspension_) {
      contact_result = solve_contact(energy, prescribed, predictor, motion, x, candidates);
      take(contact_result);
    } else {
      // The roller hangs at anchor + w; w and the contact converge together (suspension.hpp).
      const Vec2 anchor = motion.end.centre;
      auto force_at = [&](Real w) -> std::optional<Real> {
        motion.end.centre = anchor + Vec2(0.0, w);
        contact_result = solve_contact(energy, prescribed, predictor, motion, x, candidates);
        take(contact_result);
        if (!contact_result.converged()) return std::nullopt;
        const VecX uw = energy.full_increment(contact_result.x);
        Real fy = 0.0;
        for (std::size_t i = 0; i < candidates.size(); ++i) {
          const ContactCandidate& c = candidates[i];
          const Vec2 xi = c.position + Vec2(uw(2 * c.node), uw(2 * c.node + 1));
          const Vec2 n = (xi - motion.end.centre).normalized();
          fy -= contact_force(contact_result.contact[i].normal_force, contact_result.contact[i].tangential_force, n,
                              c.tangent)
                    .y();
        }
        return fy;
      };
      const CouplingResult cr =
          couple_suspension(*suspension_, suspension_->deflection(), force_at, 1e-10 * motion.radius, 40);
      inc.suspension_passes = cr.iterations;
      if (!cr.converged) {
        inc.converged = false;
        inc.message = cr.message;
      }
      deflection = cr.deflection;
    }
    inc.max_penetration = contact_result.max_penetration;
    inc.stats = contact_result.stats;
    if (inc.converged) u = energy.full_increment(contact_result.x);
  }
  if (!inc.converged) return inc;

  try {
    model_->commit(u);
  } catch (const NumericalError& e) {
    // A solver reported success at a state the strip cannot take (e.g. an inverted element):
    // treat it as a failed increment so the step is cut; nothing was committed.
    inc.converged = false;
    inc.message = fmt::format("the increment's solution is not admissible: {}", e.what());
    return inc;
  }
  last_increment_ = u;
  last_length_ = s_to - s_from;
  if (scene_.dynamics.strip_inertia) strip_history_.advance(model_->total_displacement());
  if (scene_.roller) {
    pose_ = motion.end;
    if (suspension_) suspension_->history().advance(VecX::Constant(1, deflection));
    record_contact(candidates, contact_result, u);
  }
  return inc;
}

void Simulation::finish_step() {
  ++steps_done_;
  // Velocities and accelerations by Houbolt's formulas on the step-level history, which then
  // advances by one step (the working histories return to the step spacing).
  if (scene_.dynamics.strip_inertia) {
    const VecX& u = model_->total_displacement();
    velocity_ = strip_step_history_.velocity(u);
    acceleration_ = strip_step_history_.acceleration(u);
    strip_step_history_.advance(u);
    strip_history_ = strip_step_history_;
  }
  if (suspension_) {
    const Real w = suspension_->deflection();
    suspension_velocity_ = suspension_step_->velocity(w);
    suspension_acceleration_ = suspension_step_->acceleration(w);
    suspension_step_->history().advance(VecX::Constant(1, w));
    suspension_ = suspension_step_;
  }
}

Simulation::StepResult Simulation::advance_step(int step) {
  StepResult res;
  const Vec2 centre_start = pose_.centre;
  // Sub-increments of 1/2^cuts of the step; a failed sub-increment is halved again.
  Real s = step - 1;
  Real ds = 1.0;
  while (s < step - 1e-12) {
    Increment inc = advance(s, s + ds);
    res.iterations += inc.iterations;
    res.factorizations += inc.factorizations;
    res.last = inc;
    if (inc.converged) {
      s += ds;
      res.max_penetration = std::max(res.max_penetration, inc.max_penetration);
      continue;
    }
    if (res.cuts >= scene_.steps.max_cuts) {
      res.message = fmt::format("step {} failed after {} cuts (sub-increment {:.4g} of the step): {}", step,
                                res.cuts, ds, inc.message);
      return res;
    }
    ++res.cuts;
    ds *= 0.5;
  }
  res.converged = true;
  roller_velocity_ = (pose_.centre - centre_start) / scene_.steps.dt;
  finish_step();
  return res;
}

}  // namespace roller
