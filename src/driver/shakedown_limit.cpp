#include "roller/driver/shakedown_limit.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <ostream>

#include <fmt/format.h>

#include "roller/analysis/carter.hpp"
#include "roller/analysis/hertz.hpp"
#include "roller/assembly/element_materials.hpp"
#include "roller/core/error.hpp"
#include "roller/driver/simulation.hpp"
#include "roller/driver/steady_load.hpp"
#include "roller/solver/sparse_solver.hpp"

namespace roller {

namespace {

// The scene's press with a linear elastic, small-strain strip and no friction.
Scene elastic_press_scene(const Scene& scene, int press_steps) {
  Scene s = elastic_frictionless_scene(scene);
  s.steps.n_steps = press_steps;
  return s;
}

// Adds the elastic response to tangential nodal forces (x, one per contact record).
void add_traction(StripModel& strip, const std::vector<NodeContactRecord>& contact, const std::vector<Real>& fx) {
  const DofMap& dofs = strip.dof_map();
  VecX force = VecX::Zero(strip.n_dofs());
  for (std::size_t i = 0; i < contact.size(); ++i) force[2 * contact[i].node] += fx[i];
  SparseMatrix k;
  strip.evaluate(VecX::Zero(strip.n_dofs()), nullptr, &k);
  SparseSolver solver(MumpsSolver::Symmetry::Symmetric);
  if (!solver.factorize(k)) throw NumericalError("shakedown-limit: the elastic strip's stiffness is singular");
  VecX u = VecX::Zero(strip.n_dofs());
  dofs.scatter_free(solver.solve(dofs.gather_free(force)), u);
  strip.commit(u);  // linear and small strain: the stresses add
}

// The largest von Mises measure a material's back-stress reaches: sum of C/gamma, infinite when a
// term is linear (gamma = 0); zero without kinematic hardening.
Real back_stress_bound(const MaterialParams& m) {
  if (!m.plastic || m.n_back_stresses() == 0) return 0.0;
  Real bound = 0.0;
  for (int i = 0; i < m.n_back_stresses(); ++i) {
    const BackStressLaw law = m.back_stress_law(i);
    if (law.recovery == 0.0) return std::numeric_limits<Real>::infinity();
    bound += law.modulus / law.recovery;
  }
  return bound;
}

// The rows of elements by centroid depth (initial mesh), each element with its mean stress and the
// plastic strip's yield stress. Element means, not the integration points: a Q4's two rows of Gauss
// points carry an error of opposite sign that the mean cancels (docs/validation.md, Melan's bound:
// at 0.5 a under the Hertz load the two rows give p0/k 4.16 and 3.82, their elements 4.0).
std::vector<MelanRow> depth_rows(const StripModel& elastic, const ElementMaterials& plastic, Real top) {
  const Mesh& mesh = elastic.mesh();
  std::map<long long, MelanRow> rows;  // keyed by depth in nm: the elements of a row share it to rounding
  for (Index e = 0; e < mesh.n_elements(); ++e) {
    Real x = 0.0;
    for (const Index a : mesh.elements[e]) x += mesh.nodes[a].x();
    x /= static_cast<Real>(mesh.elements[e].size());
    const Real depth = centroid_depth(mesh, e, top);  // as assign_materials takes it
    Vec4 stress = Vec4::Zero();
    for (int q = 0; q < elastic.points_per_element(); ++q) stress += elastic.state(e, q).stress;
    stress /= elastic.points_per_element();
    const MaterialParams& m = plastic.of(e);
    MelanRow& row = rows[std::llround(depth * 1e6)];
    row.back_stress_bound =
        row.x.empty() ? back_stress_bound(m) : std::min(row.back_stress_bound, back_stress_bound(m));
    row.depth = depth;
    row.x.push_back(x);
    row.stress.push_back(stress);
    row.yield_stress.push_back(m.yield_stress);
  }
  std::vector<MelanRow> out;
  for (auto& [key, row] : rows) out.push_back(std::move(row));
  return out;
}

ShakedownLoad press_load(const Scene& scene, const Simulation& sim, int press_steps, Real traction, Real sign) {
  ShakedownLoad load;
  load.press_steps = press_steps;
  load.load = std::abs(sim.roller_force().y());
  const MaterialParams surface = scene.strip_material().surface();
  const HertzSolution h = hertz_line_contact(load.load, scene.roller->radius, surface.plane_strain_modulus());
  load.half_width = h.half_width;
  load.hertz_peak = h.peak;
  for (const NodeContactRecord& c : sim.state().contact)
    if (c.tributary_length > 0.0)
      load.computed_peak = std::max(load.computed_peak, std::abs(c.force.y()) / c.tributary_length);
  load.traction = traction;
  load.travel_sign = sign;
  return load;
}

}  // namespace

Real ShakedownLimitResult::p0_over_k(const MelanLimit& bound) const {
  if (bound.critical_row < 0) return std::numeric_limits<Real>::infinity();
  return bound.load_factor() * scene_p0_over_k(bound);
}

Real ShakedownLimitResult::scene_p0_over_k(const MelanLimit& bound) const {
  if (bound.critical_row < 0) return 0.0;
  return load.hertz_peak / (bound.rows[bound.critical_row].critical_yield_stress / std::sqrt(3.0));
}

ShakedownLimitResult compute_shakedown_limit(const Scene& scene, const ShakedownLimitSettings& settings) {
  if (!scene.roller) throw InputError(fmt::format("{}: shakedown-limit needs a [roller]", scene.file.string()));
  const SteadyLoad steady = steady_load(scene, settings.traction);
  if (!scene.strip_material().any_plastic())
    throw InputError(fmt::format("{}: [material]: the strip is elastic (no yield_stress): it has no shakedown limit",
                                 scene.file.string()));
  const Real traction = steady.traction;
  const int press_steps = steady.press_steps;
  const auto start = std::chrono::steady_clock::now();
  Simulation sim(elastic_press_scene(scene, press_steps));
  for (int step = 1; step <= press_steps; ++step) {
    const Simulation::StepRecord r = sim.advance_step(step);
    if (!r.converged())
      throw NumericalError(
          fmt::format("shakedown-limit: the elastic press did not converge at step {}: {}", step, r.message));
  }
  ShakedownLimitResult out;
  out.load = press_load(scene, sim, press_steps, traction, steady.travel_sign);
  if (traction != 0.0) {
    const HertzSolution hertz{out.load.load, out.load.half_width, out.load.hertz_peak};
    add_traction(sim.model(), sim.state().contact,
                 traction_forces(steady, sim.state().contact, hertz, sim.state().pose.centre.x()));
    if (steady.shape == TractionShape::Carter) {
      out.load.shape = TractionShape::Carter;
      out.load.stick_half_width = carter_traction(hertz, traction, steady.friction).stick_half_width;
    }
  }
  out.top = mesh_top(sim.model().mesh());
  if (settings.progress)
    *settings.progress << fmt::format(
        "roller: elastic press to P = {:.6g} N/mm in {} steps ({:.1f} s); Melan's bound over the rows\n", out.load.load,
        press_steps, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  const ElementMaterials plastic = assign_materials(sim.model().mesh(), scene.strip_material());
  const std::vector<MelanRow> rows = depth_rows(sim.model(), plastic, out.top);
  out.elastic = melan_limit(rows, ShakedownBound::Elastic, settings.search);
  const bool kinematic =
      std::any_of(rows.begin(), rows.end(), [](const MelanRow& r) { return r.back_stress_bound > 0.0; });
  if (kinematic) out.kinematic = melan_limit(rows, ShakedownBound::Kinematic, settings.search);
  return out;
}

}  // namespace roller
