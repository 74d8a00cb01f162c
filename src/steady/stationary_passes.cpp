#include "roller/steady/stationary_passes.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <ostream>

#include <fmt/format.h>

#include "roller/analysis/carter.hpp"
#include "roller/core/error.hpp"
#include "roller/io/roller_start.hpp"
#include "roller/material/j2_plasticity.hpp"
#include "roller/material/long_track_state.hpp"
#include "roller/steady/steady_load.hpp"
#include "roller_contact_correction.hpp"

namespace roller {

namespace {

// The travel segment's force, or an InputError: the stationary pass carries a prescribed load.
Real travel_force(const Scene& scene, const SteadyLoad& load) {
  if (!load.force)
    throw InputError(
        fmt::format("{}: passes.method = \"stationary\" needs the force of the segment over steps {}-{} "
                    "(fy, or p0 / p0_over_k): the stationary pass carries the Hertz pressure of it",
                    scene.file.string(), load.travel->first_step, load.travel->last_step));
  return std::abs(*load.force);
}

// Where the contact sits in the roller's frame: the middle of the travel segment.
Real contact_centre(const Scene& scene, const SteadyLoad& load) {
  const Real mid = load.travel->first_step - 1 + 0.5 * (load.travel->last_step - load.travel->first_step + 1);
  return roller_pose(*scene.roller, given_start_centre(scene), mid).centre.x();
}

// The residual strip is a long track's on a base held in x and y (material/long_track_state.hpp):
// an InputError when some node of the strip's bottom row is free in x or y.
void require_held_base(const Scene& scene, const StripModel& model) {
  const Mesh& mesh = model.mesh();
  Real bottom = mesh.nodes.front().y();
  for (const Vec2& p : mesh.nodes) bottom = std::min(bottom, p.y());
  for (Index a = 0; a < mesh.n_nodes(); ++a) {
    if (mesh.nodes[a].y() != bottom) continue;
    if (model.dof_map().is_constrained(2 * a) && model.dof_map().is_constrained(2 * a + 1)) continue;
    throw InputError(
        fmt::format("{}: passes.method = \"stationary\" needs the strip's base held in x and y (a [[displacement]] "
                    "with x = 0.0 and y = 0.0 on nodes = \"bottom\"): its residual strip is a long track's, whose "
                    "state on such a base is known; the node at ({}, {}) is free. Use passes.method = \"transient\"",
                    scene.file.string(), mesh.nodes[a].x(), mesh.nodes[a].y()));
  }
}

// The strip's copies for passes.stationary_phases, copy k moved against the travel by k/P of the
// element under the contact's centre.
PhasedStrip phased_of(const Scene& scene, const StripModel& model, const SteadyLoad& steady, Real travel) {
  const int phases = scene.passes.stationary_phases;
  const Real h = contact_element_length(model.mesh(), contact_centre(scene, steady));
  return phased_strip(model.mesh(), model.materials(), model.dof_map(), phases, -travel * h / phases);
}

// Per streamline its point nearest the extraction column x, of the first copy (whose points, the
// first `base_points`, are the strip's).
std::vector<Index> extraction_points(const StationaryStrip& strip, Index base_points, Real x) {
  std::vector<Index> out;
  for (const Streamline& s : strip.streamlines()) {
    Index nearest = -1;
    for (const Index p : s.points)
      if (p < base_points &&
          (nearest < 0 || std::abs(strip.point_position(p).x() - x) < std::abs(strip.point_position(nearest).x() - x)))
        nearest = p;
    ROLLER_ASSERT(nearest >= 0, "every lane passes the first copy");
    out.push_back(nearest);
  }
  return out;
}

// The Hertz pressure of the travel and its traction q along it (q = traction p, or Carter's when
// the roller rolls under a horizontal force) as the work-equivalent nodal forces on every copy
// (all dofs), and as contact records of the first copy's top nodes (contact.csv), by x.
struct TravelLoad {
  VecX forces;
  std::vector<NodeContactRecord> contact;
};
TravelLoad travel_load(const PhasedStrip& phased, const Mesh& mesh, const HertzSolution& hertz,
                       const SteadyLoad& steady, Real travel, Real centre_x) {
  std::optional<CarterTraction> carter;
  if (steady.shape == TractionShape::Carter) carter = carter_traction(hertz, steady.traction, steady.friction);
  TravelLoad out;
  out.forces = VecX::Zero(phased.mesh.n_dofs());
  for (int k = 0; k < phased.phases; ++k) {
    std::vector<Index> top = mesh.node_set("contact");
    for (Index& a : top) a += k * phased.base_nodes;
    const auto& nodes = phased.mesh.nodes;
    std::sort(top.begin(), top.end(), [&](Index a, Index b) { return travel * nodes[a].x() < travel * nodes[b].x(); });
    std::vector<Real> along;  // from the contact's centre along the travel, increasing
    for (const Index a : top) along.push_back(travel * (nodes[a].x() - centre_x));
    const std::vector<Real> f = hertz_nodal_forces(hertz, along);
    std::vector<Real> q;
    if (carter) {
      q = carter_nodal_forces(*carter, along);
    } else {
      for (const Real fi : f) q.push_back(steady.traction * fi);
    }
    for (std::size_t i = 0; i < top.size(); ++i) {
      if (f[i] == 0.0) continue;
      const Vec2 force(travel * q[i], -f[i]);
      out.forces.segment<2>(2 * top[i]) = force;
      if (k > 0) continue;  // contact.csv: the first copy's, the strip's own nodes
      NodeContactRecord c;
      c.node = top[i];
      c.position = mesh.nodes[top[i]];
      c.contact.normal_force = f[i];
      c.contact.tangential_force = q[i];
      const bool slips = traction_slips(steady, hertz, along[i]);
      c.contact.status = slips ? ContactStatus::Slip : ContactStatus::Stick;
      c.tributary_length =
          0.5 * std::abs((i + 1 < top.size() ? along[i + 1] : along[i]) - (i > 0 ? along[i - 1] : along[i]));
      c.force = force;
      out.contact.push_back(c);
    }
  }
  std::sort(out.contact.begin(), out.contact.end(),
            [](const NodeContactRecord& a, const NodeContactRecord& b) { return a.position.x() < b.position.x(); });
  return out;
}

}  // namespace

StationaryPasses::~StationaryPasses() = default;

StationaryPasses::StationaryPasses(const Scene& scene, const StripModel& model, const SteadyLoad& steady)
    : roller_y_(given_start_centre(scene).y()),
      travel_(steady.travel_sign),
      phased_(phased_of(scene, model, steady, travel_)),
      strip_(phased_.mesh, phased_.materials, model.options(), travel_, phased_.phases,
             scene.passes.stationary_path_parts),
      elastic_materials_(linear_elastic(phased_.materials)),
      linear_solver_(scene.newton.linear) {
  require_held_base(scene, model);
  require_stationary_load(scene, steady);
  hertz_ = hertz_line_contact(travel_force(scene, steady), scene.roller->radius, scene.contact_modulus());
  centre_x_ = contact_centre(scene, steady);
  // Half-way between the contact's trailing edge and the strip's downstream end.
  extraction_x_ = 0.5 * (centre_x_ - travel_ * hertz_.half_width + strip_.end_x(StationaryStrip::End::Downstream));
  const Index base_points = model.mesh().n_elements() * strip_.points_per_element();
  base_points_ = base_points;
  extraction_ = extraction_points(strip_, base_points, extraction_x_);
  TravelLoad load = travel_load(phased_, model.mesh(), hertz_, steady, travel_, centre_x_);
  contact_ = std::move(load.contact);
  StripModel elastic(phased_.mesh, elastic_materials_, model.options());  // assembles K_e
  elastic.set_dof_map(phased_.dofs);
  elastic.evaluate(VecX::Zero(phased_.mesh.n_dofs()), nullptr, &elastic_free_);
  if (!solver_.factorize(elastic_free_)) throw NumericalError("the stationary pass: the elastic stiffness is singular");
  hertz_load_ = std::move(load.forces);
  // The roller k/P of an element further along copy k, which moved back as far (phased_.shift).
  if (scene.passes.stationary_contact == StationaryContact::Roller)
    roller_correction_ = make_roller_contact_correction(
        scene, model.mesh(), steady, RollerPlaces{centre_x_, phased_.phases, phased_.shift}, hertz_.load);
}

RollerPose StationaryPasses::roller_pose() const {
  if (pose_) return *pose_;
  RollerPose pose;
  pose.centre = Vec2(centre_x_, roller_y_);
  return pose;
}

std::vector<MaterialState> StationaryPasses::upstream_of(const StripModel& strip) const {
  std::vector<MaterialState> out;
  for (const Index p : extraction_) out.push_back(strip.states()[p]);
  return out;
}

const VecX& StationaryPasses::elastic_displacement(const DofMap& dofs, const VecX& load) {
  if (elastic_load_.size() != load.size() || elastic_load_ != load) {  // the Hertz load: once a pass
    elastic_load_ = load;
    elastic_displacement_ = VecX::Zero(load.size());
    if (load.any()) dofs.scatter_free(solver_.solve(dofs.gather_free(load)), elastic_displacement_);
  }
  return elastic_displacement_;
}

std::vector<LongTrackState> StationaryPasses::leaving(const VecX& u, const std::vector<MaterialState>& states,
                                                      const VecX& elastic) const {
  // The roller lifts (unloading is elastic): its field comes off; then what the mesh's ends
  // relieved (the pass's xx strain) comes off too.
  const std::vector<Vec4> load_strain = strip_.strains(elastic, extraction_);
  const std::vector<Vec4> residual_strain = strip_.strains(u - elastic, extraction_);
  std::vector<LongTrackState> out;
  for (std::size_t s = 0; s < extraction_.size(); ++s) {
    const Index p = extraction_[s];
    const MaterialParams& m = elastic_materials_.of(p / strip_.points_per_element());
    MaterialState state = states[p];
    state.stress -= update_material(m, load_strain[s], initial_state(m)).trial.stress;
    out.push_back(long_track_state(state, residual_strain[s], m));
  }
  return out;
}

namespace {

std::vector<MaterialState> states_of(const std::vector<LongTrackState>& track) {
  std::vector<MaterialState> out;
  for (const LongTrackState& t : track) out.push_back(t.state);
  return out;
}

std::vector<Vec4> strains_of(const std::vector<LongTrackState>& track) {
  std::vector<Vec4> out;
  for (const LongTrackState& t : track) out.push_back(t.pass_strain);
  return out;
}

}  // namespace

std::vector<DepthCycle> StationaryPasses::cycles(const std::vector<MaterialState>& states, Real strip_height) const {
  const int per_element = strip_.points_per_element();
  std::map<Index, std::vector<const Streamline*>> rows;  // by the row's first element
  for (const Streamline& lane : strip_.streamlines())
    if (!lane.points.empty() && lane.points.front() < base_points_)
      rows[lane.points.front() / per_element].push_back(&lane);
  std::vector<DepthCycle> out;
  for (const auto& [first, lanes] : rows) {
    DepthCycle cycle;
    Real y = 0.0;
    const std::size_t n = lanes.front()->points.size();
    for (std::size_t k = 0; k < n; ++k) {
      Vec4 mean = Vec4::Zero();
      for (const Streamline* lane : lanes) {
        mean += states[static_cast<std::size_t>(lane->points[k])].stress;
        y += strip_.point_position(lane->points[k]).y();
      }
      cycle.stress.push_back(mean / static_cast<Real>(lanes.size()));
    }
    cycle.depth = strip_height - y / static_cast<Real>(n * lanes.size());
    out.push_back(std::move(cycle));
  }
  std::sort(out.begin(), out.end(), [](const DepthCycle& p, const DepthCycle& q) { return p.depth < q.depth; });
  return out;
}

StationaryPasses::Pass StationaryPasses::run(const StripModel& strip, const VecX& start, std::ostream* progress,
                                             const std::atomic<int>* stop) {
  StationarySettings settings;
  settings.progress = progress;
  settings.stop = stop;
  Pass out;
  const std::vector<MaterialState> upstream = upstream_of(strip);
  SteadyJacobianSettings newton;
  newton.tolerance = settings.tolerance;
  newton.linear_solver = linear_solver_;
  const DofMap& dofs = phased_.dofs;
  PrescribedLoadCorrection hertz(dofs, solver_, hertz_load_);
  StationaryCorrection* carrier = &hertz;  // K_e's correction, which finds the load
  // The roller's contact starts afresh every pass: a pass then depends on the strip it starts
  // from alone (the roller height and contact of the pass before are not in the state files), so
  // that a run resumed from a checkpoint gives the same passes. Its factorisations are the same
  // every pass, and kept.
  RollerCorrection* roller_correction = roller_correction_.get();
  if (roller_correction) {
    roller_correction->restart();
    carrier = roller_correction;
  }
  SteadyJacobianCorrection correction(strip_, dofs, elastic_free_, *carrier, upstream, newton);
  const LeavingStates leaving_states = [&](const VecX& u, const std::vector<MaterialState>& states, const VecX& load) {
    return states_of(leaving(u, states, elastic_displacement(dofs, load)));
  };
  out.solve = solve_stationary_pass(strip_, dofs, correction, upstream, settings, leaving_states, start);
  out.factorizations = correction.factorizations();
  if (!out.solve.converged()) return out;
  // The next pass starts from this one's displacement once this one's upstream was rolled: the
  // passes then differ less and less (docs/benchmarks-log.md, "Warm starts"). From a virgin
  // upstream, the first pass's large flow is a worse start for the second than none.
  const bool rolled =
      std::any_of(upstream.begin(), upstream.end(), [](const MaterialState& s) { return s.eq_plastic_strain > 0.0; });
  if (rolled) out.next_start = out.solve.displacement;
  if (roller_correction) {
    contact_ = roller_correction->contact();
    pose_ = roller_correction->pose();
    creep_ = roller_correction->creep();
  }
  const VecX& elastic = elastic_displacement(dofs, out.solve.load);
  const std::vector<LongTrackState> track = leaving(out.solve.displacement, out.solve.states, elastic);
  // The strip's: the first copy's points and dofs.
  out.residual = strip_.spread(states_of(track));
  out.residual.resize(static_cast<std::size_t>(strip.mesh().n_elements() * strip_.points_per_element()));
  out.permanent_displacement = strip_.uniform_displacement(strains_of(track)).head(strip.n_dofs());
  return out;
}

}  // namespace roller
