#include "roller/steady/shakedown_limit.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "roller/analysis/carter.hpp"
#include "roller/analysis/half_plane_surface.hpp"
#include "roller/analysis/hertz.hpp"
#include "roller/assembly/element_materials.hpp"
#include "roller/assembly/phased_strip.hpp"
#include "roller/core/error.hpp"
#include "roller/fem/shape_functions.hpp"
#include "roller/io/scene_strip.hpp"
#include "roller/solver/sparse_solver.hpp"
#include "roller/steady/elastic_press.hpp"
#include "roller/steady/steady_load.hpp"

namespace roller {

namespace {

// The scene's press with a linear elastic, small-strain strip and no friction: an ElasticPress
// through its press steps, each cut into 2, 4, ... increments when one fails, up to steps.max_cuts
// times as a run's (a NumericalError naming the step that fails then).
std::unique_ptr<ElasticPress> elastic_press(const Scene& scene, int press_steps) {
  Scene s = elastic_frictionless_scene(scene);
  s.steps.n_steps = press_steps;
  const int max_cuts = s.steps.max_cuts;
  const std::unique_ptr<StripModel> strip = make_scene_strip(s);  // the scene's checks first
  auto press = std::make_unique<ElasticPress>(std::move(s), strip->mesh());
  for (int step = 1; step <= press_steps; ++step) {
    Real at = step - 1, length = 1.0;
    for (int cuts = 0; at < step - 1e-12;) {
      const IncrementReport r = press->press(at, at + length);
      if (r.converged()) {
        at += length;
      } else if (cuts++ < max_cuts) {
        length *= 0.5;
      } else {
        throw NumericalError(
            fmt::format("shakedown-limit: the elastic press did not converge at step {} after {} cuts: {}", step,
                        max_cuts, r.message));
      }
    }
  }
  return press;
}

// Every integration point's stress [xx, yy, zz, xy], in the strip's order (element by element).
std::vector<Vec4> point_stresses(const StripModel& strip) {
  std::vector<Vec4> out;
  for (Index e = 0; e < strip.mesh().n_elements(); ++e)
    for (int q = 0; q < strip.points_per_element(); ++q) out.push_back(strip.state(e, q).stress);
  return out;
}

// The elastic response of the strip (linear, small strain, unloaded) to tangential nodal forces
// (x, one per contact record): its stress at every integration point.
std::vector<Vec4> traction_stresses(const StripModel& pressed, const std::vector<NodeContactRecord>& contact,
                                    const std::vector<Real>& fx) {
  StripModel strip(pressed.mesh(), pressed.materials(), pressed.options());
  strip.set_dof_map(pressed.dof_map());
  const DofMap& dofs = strip.dof_map();
  VecX force = VecX::Zero(strip.n_dofs());
  for (std::size_t i = 0; i < contact.size(); ++i) force[2 * contact[i].node] += fx[i];
  SparseMatrix k;
  strip.evaluate(VecX::Zero(strip.n_dofs()), nullptr, &k);
  SparseSolver solver(MumpsSolver::Symmetry::Symmetric);
  if (!solver.factorize(k)) throw NumericalError("shakedown-limit: the elastic strip's stiffness is singular");
  VecX u = VecX::Zero(strip.n_dofs());
  dofs.scatter_free(solver.solve(dofs.gather_free(force)), u);
  strip.commit(u);
  return point_stresses(strip);
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
std::vector<MelanRow> depth_rows(const Mesh& mesh, const std::vector<Vec4>& stress, int points_per_element,
                                 const ElementMaterials& plastic, Real top) {
  std::map<long long, MelanRow> rows;  // keyed by depth in nm: the elements of a row share it to rounding
  for (Index e = 0; e < mesh.n_elements(); ++e) {
    const Real x = element_centroid(mesh, e).x();
    const Real depth = centroid_depth(mesh, e, top);  // as assign_materials takes it
    Vec4 mean = Vec4::Zero();
    for (int q = 0; q < points_per_element; ++q) mean += stress[e * points_per_element + q];
    mean /= points_per_element;
    const MaterialParams& m = plastic.of(e);
    if (!m.plastic) continue;  // an elastic layer's points never yield: no constraint of the bound
    MelanRow& row = rows[std::llround(depth * 1e6)];
    row.back_stress_bound =
        row.x.empty() ? back_stress_bound(m) : std::min(row.back_stress_bound, back_stress_bound(m));
    row.depth = depth;
    row.x.push_back(x);
    row.stress.push_back(mean);
    row.yield_stress.push_back(m.lowest_yield_stress());
  }
  std::vector<MelanRow> out;
  for (auto& [key, row] : rows) out.push_back(std::move(row));
  return out;
}

// The surface itself as a row (depth 0): the half-plane's surface stress (analysis/
// half_plane_surface.hpp) under the contact's pressure, as the semi-ellipse of the press's nodal
// forces, and the shear tractions, sampled finely across the contact and beside it; each point
// with the yield stress of the top element above which it lies, the out-of-plane stress
// nu (sigma_xx + sigma_yy). The elements cannot give it: the top row's centroids lie half an
// element below the surface, where a traction's surface mode (Johnson's 1/mu) is missed, and they
// smooth the square-root edges of sigma_xx, whose swing the kinematic bound's cycle spans
// (docs/model.md, Melan's bound).
MelanRow surface_row(const Mesh& mesh, const ElementMaterials& plastic, Real top, const EllipticLoad& pressure,
                     const std::vector<EllipticLoad>& shears) {
  std::vector<std::pair<Real, Index>> top_elements;  // their smallest x and the element, by x
  for (Index e = 0; e < mesh.n_elements(); ++e) {
    Real lo = std::numeric_limits<Real>::infinity();
    bool on_top = false;
    for (const Index a : mesh.elements[e]) {
      lo = std::min(lo, mesh.nodes[a].x());
      on_top = on_top || std::abs(mesh.nodes[a].y() - top) <= 1e-9 * std::max(1.0, std::abs(top));
    }
    if (on_top) top_elements.emplace_back(lo, e);
  }
  std::sort(top_elements.begin(), top_elements.end());
  MelanRow row;
  row.depth = 0.0;
  if (top_elements.empty() || !(pressure.peak > 0.0)) return row;
  constexpr int kSamples = 400;  // over 3 half-widths either side: the edges and the peak among them
  std::vector<Real> xs{pressure.centre, pressure.centre - pressure.half_width, pressure.centre + pressure.half_width};
  for (const EllipticLoad& t : shears) xs.insert(xs.end(), {t.centre - t.half_width, t.centre + t.half_width});
  for (int i = 0; i <= kSamples; ++i) xs.push_back(pressure.centre + pressure.half_width * (-3.0 + 6.0 * i / kSamples));
  std::sort(xs.begin(), xs.end());
  for (const Real x : xs) {
    auto above = std::upper_bound(top_elements.begin(), top_elements.end(), std::make_pair(x, mesh.n_elements()));
    if (above == top_elements.begin()) continue;  // beyond the strip
    const MaterialParams& m = plastic.of(std::prev(above)->second);
    if (!m.plastic) continue;  // an elastic surface layer never yields
    Vec4 s = half_plane_surface_stress(x, pressure, shears);
    s[2] = m.poisson_ratio * (s[0] + s[1]);  // plane strain, linear elastic
    row.x.push_back(x);
    row.stress.push_back(s);
    row.yield_stress.push_back(m.lowest_yield_stress());
    row.back_stress_bound =
        row.x.size() == 1 ? back_stress_bound(m) : std::min(row.back_stress_bound, back_stress_bound(m));
  }
  return row;
}

ShakedownLoad press_load(const Scene& scene, const ElasticPress& press, int press_steps, Real traction, Real sign) {
  ShakedownLoad load;
  load.press_steps = press_steps;
  load.load = std::abs(press.roller_force().y());
  // With an elastic roller, the two bodies' modulus (docs/model.md, Elastic roller).
  const HertzSolution h = hertz_line_contact(load.load, scene.roller->radius, scene.contact_modulus());
  load.half_width = h.half_width;
  load.hertz_peak = h.peak;
  for (const NodeContactRecord& c : press.contact())
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

namespace {

// The scene, when it has a roller to press: shakedown-limit's first check.
const Scene& roller_scene(const Scene& scene) {
  if (!scene.roller) throw InputError(fmt::format("{}: shakedown-limit needs a [roller]", scene.file.string()));
  return scene;
}

// The scene's elastic press and the elastic response to its traction, solved once: the stresses at
// any traction q/p of the scene's shape are the press's plus q/p times the unit traction's (a
// uniform traction), or plus the traction's (Carter's, whose shape depends on Q).
class PressedStrip {
 public:
  PressedStrip(const Scene& scene, const ShakedownLimitSettings& settings)
      : steady_(steady_load(roller_scene(scene), settings.traction)) {
    require_given_traction(steady_);
    if (!scene.strip_material().any_plastic())
      throw InputError(fmt::format("{}: [material]: the strip is elastic (no yield_stress): it has no shakedown limit",
                                   scene.file.string()));
    const auto start = std::chrono::steady_clock::now();
    press_strip_ = elastic_press(scene, steady_.press_steps);
    load_ = press_load(scene, *press_strip_, steady_.press_steps, steady_.traction, steady_.travel_sign);
    top_ = mesh_top(mesh());
    plastic_ = assign_materials(mesh(), scene.strip_material());
    press_ = point_stresses(press_strip_->strip());
    std::vector<Real> x, f, l;
    for (const NodeContactRecord& c : press_strip_->contact()) {
      x.push_back(c.position.x());
      f.push_back(std::abs(c.force.y()));
      l.push_back(c.tributary_length);
    }
    pressure_ = elliptic_fit(x, f, l);
    if (steady_.shape == TractionShape::Carter) {
      const HertzSolution hertz{load_.load, load_.half_width, load_.hertz_peak};
      load_.shape = TractionShape::Carter;
      load_.stick_half_width = carter_traction(hertz, steady_.traction, steady_.friction).stick_half_width;
    }
    if (settings.progress)
      *settings.progress << fmt::format(
          "roller: elastic press to P = {:.6g} N/mm in {} steps ({:.1f} s); Melan's bound over the rows\n", load_.load,
          steady_.press_steps, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }

  const Mesh& mesh() const { return press_strip_->strip().mesh(); }
  Real centre_x() const { return press_strip_->pose().centre.x(); }  // of the contact
  const ShakedownLoad& load() const { return load_; }
  Real top() const { return top_; }
  // Carter's traction has one q/p, the scene's; a uniform one any.
  bool any_traction() const { return steady_.shape == TractionShape::Uniform; }

  // The shear tractions on the strip at q/p = `traction`, as semi-ellipses about the contact's
  // pressure (steady_load.hpp's traction_forces, continuous): (q/p) p along the travel, or
  // Carter's, mu p less the stick zone's ellipse at the leading edge.
  std::vector<EllipticLoad> shears(Real traction) const {
    const Real travel = steady_.travel_sign;
    if (traction == 0.0) return {};
    if (steady_.shape == TractionShape::Uniform)
      return {{pressure_.centre, pressure_.half_width, travel * traction * pressure_.peak}};
    const HertzSolution fit{0.5 * M_PI * pressure_.half_width * pressure_.peak, pressure_.half_width, pressure_.peak};
    const CarterTraction carter = carter_traction(fit, traction, steady_.friction);
    const Real slide = travel * carter.direction() * carter.friction * pressure_.peak;
    std::vector<EllipticLoad> out{{pressure_.centre, pressure_.half_width, slide}};
    if (carter.stick_half_width > 0.0)
      out.push_back({pressure_.centre + travel * carter.stick_centre(), carter.stick_half_width,
                     -slide * carter.stick_half_width / pressure_.half_width});
    return out;
  }

  // The rows at q/p = `traction`: the surface first, then the rows of elements by depth.
  std::vector<MelanRow> rows(Real traction) {
    const std::vector<NodeContactRecord>& contact = press_strip_->contact();
    const Real factor = any_traction() ? traction : 1.0;  // Carter's response is solved at its own Q
    if (factor != 0.0) solve_traction(contact);
    std::vector<Vec4> stress = press_;
    if (factor != 0.0 && !traction_.empty())
      for (std::size_t i = 0; i < stress.size(); ++i) stress[i] += factor * traction_[i];
    const int ppe = press_strip_->strip().points_per_element();
    std::vector<MelanRow> out;
    if (MelanRow surface = surface_row(mesh(), plastic_, top_, pressure_, shears(traction)); !surface.x.empty())
      out.push_back(std::move(surface));
    for (MelanRow& row : depth_rows(mesh(), stress, ppe, plastic_, top_)) out.push_back(std::move(row));
    return out;
  }

 private:
  // The stresses of the elastic response to the unit (uniform) or the scene's (Carter's) traction's
  // nodal forces, solved at the first call: none for free rolling.
  void solve_traction(const std::vector<NodeContactRecord>& contact) {
    if (traction_solved_) return;
    traction_solved_ = true;
    SteadyLoad unit = steady_;
    if (any_traction()) unit.traction = 1.0;
    if (steady_.traction == 0.0 && !any_traction()) return;
    const HertzSolution hertz{load_.load, load_.half_width, load_.hertz_peak};
    traction_ = traction_stresses(press_strip_->strip(), contact, traction_forces(unit, contact, hertz, centre_x()));
  }

  SteadyLoad steady_;
  std::unique_ptr<ElasticPress> press_strip_;
  ShakedownLoad load_;
  Real top_ = 0.0;
  ElementMaterials plastic_;
  std::vector<Vec4> press_, traction_;
  EllipticLoad pressure_;  // the press's contact pressure
  bool traction_solved_ = false;
};

// Fewer than this many elements across the contact's half-width: the peaks of the surface's
// tractions and of the subsurface shear are sampled too coarsely for a limit within about 1 %.
constexpr Real kElementsAcrossHalfWidth = 8.0;

std::vector<std::string> resolution_warnings(const ShakedownLimitResult& r, Real element_size) {
  std::vector<std::string> out;
  const Real per_half_width = r.load.half_width / element_size;
  if (!(per_half_width < kElementsAcrossHalfWidth)) return out;
  for (const MelanLimit* b : {&r.elastic, r.kinematic ? &*r.kinematic : nullptr}) {
    if (!b || b->critical_row < 0) continue;
    const bool surface = b->rows[b->critical_row].depth == 0.0;
    out.push_back(fmt::format(
        "the {} limit is reached {} with {:.1f} elements across the contact's half-width a = {:.4g} mm (element {:.3g} "
        "mm): the {} is resolved too coarsely for a limit within about 1 %; refine the mesh under the contact "
        "(mesh.refine, mesh.x_lines) to at least {:.0f} elements across a",
        enum_name(b->bound), surface ? "at the surface" : "below it", per_half_width, r.load.half_width, element_size,
        surface ? "peak of the surface's traction" : "subsurface stress cycle", kElementsAcrossHalfWidth));
  }
  return out;
}

ShakedownLimitResult limit_at(PressedStrip& press, Real traction, MelanSearch search) {
  ShakedownLimitResult out;
  out.load = press.load();
  out.load.traction = traction;
  out.top = press.top();
  const std::vector<MelanRow> rows = press.rows(traction);
  out.elastic = melan_limit(rows, ShakedownBound::Elastic, search);
  const bool kinematic =
      std::any_of(rows.begin(), rows.end(), [](const MelanRow& r) { return r.back_stress_bound > 0.0; });
  if (kinematic) out.kinematic = melan_limit(rows, ShakedownBound::Kinematic, search);
  return out;
}

}  // namespace

ShakedownLimitResult compute_shakedown_limit(const Scene& scene, const ShakedownLimitSettings& settings) {
  PressedStrip press(scene, settings);
  ShakedownLimitResult out = limit_at(press, press.load().traction, settings.search);
  out.warnings = resolution_warnings(out, contact_element_length(press.mesh(), press.centre_x()));
  return out;
}

std::vector<ShakedownLimitResult> compute_shakedown_map(const Scene& scene, const std::vector<Real>& tractions,
                                                        const ShakedownLimitSettings& settings) {
  ShakedownLimitSettings uniform = settings;
  uniform.traction = 0.0;  // a uniform q/p, swept
  PressedStrip press(scene, uniform);
  const Real element_size = contact_element_length(press.mesh(), press.centre_x());
  std::vector<ShakedownLimitResult> out;
  for (const Real q : tractions) {
    out.push_back(limit_at(press, q, settings.search));
    out.back().warnings = resolution_warnings(out.back(), element_size);
    if (settings.progress)
      *settings.progress << fmt::format(
          "  q/p = {:<5.3g} p0/k = {:.4g} (elastic){}\n", q, out.back().p0_over_k(out.back().elastic),
          out.back().kinematic ? fmt::format(", {:.4g} (kinematic)", out.back().p0_over_k(*out.back().kinematic)) : "");
  }
  return out;
}

}  // namespace roller
