#include "roller/steady/steady_load.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include <fmt/format.h>

#include "roller/analysis/carter.hpp"
#include "roller/core/error.hpp"

namespace roller {

SteadyLoad steady_load(const Scene& scene, std::optional<Real> traction) {
  if (!scene.roller) throw InputError(fmt::format("{}: a steady pass needs a [roller]", scene.file.string()));
  const PathSegment* it = travel_segment(*scene.roller);
  if (!it)
    throw InputError(
        fmt::format("{}: roller.path: a steady pass needs a segment that rolls or slides the roller "
                    "along the strip (dx != 0); none has one",
                    scene.file.string()));
  if (it->first_step <= 1)
    throw InputError(
        fmt::format("{}: roller.path: the segment with dx = {} starts at step 1; a steady pass "
                    "needs the press before it (the steps that bring the roller to its load)",
                    scene.file.string(), it->dx));
  SteadyLoad load;
  load.travel = it;
  load.press_steps = it->first_step - 1;
  load.force = it->fy;
  load.travel_sign = it->dx > 0.0 ? 1.0 : -1.0;
  load.friction = friction_in_step(*scene.roller, it->first_step, scene.contact.friction);
  load.segment =
      fmt::format("{}: roller.path: the segment over steps {}-{}", scene.file.string(), it->first_step, it->last_step);
  load.creep = it->slip_end;
  const std::string& where = load.segment;
  if (traction) {
    load.traction = *traction;
  } else if (const std::optional<Real> fx = segment_end_fx(*it)) {
    if (!it->fy)
      throw InputError(fmt::format("{} prescribes fx = {} without fy: a steady pass needs both forces", where, *fx));
    // fx: the strip's force on the roller (no -0 when it is zero); q/p is the traction itself
    load.traction = it->q_over_p ? *it->q_over_p : *fx == 0.0 ? 0.0 : -load.travel_sign * *fx / std::abs(*it->fy);
    load.shape = TractionShape::Carter;
    if (std::abs(load.traction) > load.friction)
      throw InputError(
          fmt::format("{}: the traction |q/p| = |fx|/fy = {:.6g} exceeds mu = {}: the roller would slide, it "
                      "cannot roll steadily under this force",
                      where, std::abs(load.traction), load.friction));
  } else if (std::max(it->slip_start, it->slip_end) == 0.0) {
    load.traction = 0.0;  // free rolling: no tangential load
  } else if (std::min(it->slip_start, it->slip_end) >= 1.0) {
    load.traction = load.friction;
  } else {
    load.shape = TractionShape::Creep;  // the traction an outcome: the roller's contact alone carries it
  }
  return load;
}

void require_given_traction(const SteadyLoad& load) {
  if (load.shape != TractionShape::Creep) return;
  throw InputError(fmt::format(
      "{} rolls with creep (slip {}..{}); the traction a creep carries depends on the strip's plastic flow and on "
      "nu (Carter's law holds for an elastic strip with nu = 0.5), so a load laid on the strip takes the force "
      "instead: give the segment fx, the strip's horizontal force on the roller (Carter's traction; the creep is then "
      "an outcome), or the traction q/p (shakedown-limit --traction); the stationary pass on the roller's contact "
      "(passes.stationary_contact = \"roller\") rolls with the creep itself",
      load.segment, load.travel->slip_start, load.travel->slip_end));
}

void require_rollable(const SteadyLoad& load) {
  if (load.shape != TractionShape::Carter || !(load.friction > 0.0) || std::abs(load.traction) < load.friction) return;
  throw InputError(fmt::format(
      "{}: |q/p| = |fx|/fy = {:.6g} is mu = {}: on the roller's contact no creep carries it rolling; give the "
      "segment slip = 1 (the roller slides) instead of the force",
      load.segment, std::abs(load.traction), load.friction));
}

void require_stationary_load(const Scene& scene, const SteadyLoad& load) {
  if (scene.passes.stationary_contact == StationaryContact::Hertz)
    require_given_traction(load);
  else
    require_rollable(load);
}

std::vector<Real> traction_forces(const SteadyLoad& load, const std::vector<NodeContactRecord>& contact,
                                  const HertzSolution& hertz, Real centre_x) {
  const Real travel = load.travel_sign;
  std::vector<Real> out;
  for (const NodeContactRecord& c : contact) out.push_back(travel * load.traction * std::abs(c.force.y()));
  if (load.shape == TractionShape::Uniform) return out;
  const CarterTraction t = carter_traction(hertz, load.traction, load.friction);
  std::vector<std::size_t> order(contact.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  auto along = [&](std::size_t k) { return travel * (contact[k].position.x() - centre_x); };
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return along(i) < along(j); });
  std::vector<Real> sorted;
  for (const std::size_t k : order) sorted.push_back(along(k));
  const std::vector<Real> relief = stick_relief_forces(t, sorted);
  for (std::size_t i = 0; i < order.size(); ++i)
    out[order[i]] = travel * t.direction() * t.friction * (std::abs(contact[order[i]].force.y()) - relief[i]);
  return out;
}

bool traction_slips(const SteadyLoad& load, const HertzSolution& hertz, Real along) {
  if (load.traction == 0.0) return false;
  if (load.shape == TractionShape::Uniform) return true;
  return !carter_traction(hertz, load.traction, load.friction).sticks(along);
}

Scene elastic_frictionless_scene(const Scene& scene) {
  Scene s = scene;
  s.element.kinematics = Kinematics::Small;
  s.material.plastic = false;
  for (MaterialLayer& layer : s.layers) layer.material.plastic = false;
  s.dynamics = DynamicsOptions{};
  s.contact.friction = 0.0;
  if (s.roller)
    for (PathSegment& seg : s.roller->path) {  // no friction carries no traction: the x follows the path
      seg.friction = 0.0;
      seg.fx.reset();
      seg.q_over_p.reset();
    }
  s.passes = PassSpec{};
  s.output.monitor = false;
  s.initial_state.clear();
  return s;
}

}  // namespace roller
