#include "roller_couplings.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "roller/contact/force_control.hpp"

namespace roller {

void couple_placed(IncrementSolve& solve) { solve.solve_contact(); }

void couple_suspended(IncrementSolve& solve) {
  // The roller hangs at anchor + w; w and the contact converge together (suspension.hpp).
  RollerMotion& motion = solve.motion();
  IncrementReport& report = solve.report();
  const Vec2 anchor = motion.end.centre;
  auto force_at = [&](Real w) -> std::optional<Real> {
    motion.end.centre = anchor + Vec2(0.0, w);
    if (!solve.solve_contact()) return std::nullopt;
    return solve.strip_force().y();
  };
  const Suspension& suspension = *solve.start().suspension;
  // A deflection beyond the reach allowed for the scene's motions (docs/scenes.md, Loading rules).
  const Real max_deflection = 1e3 * solve.settings().body_size;
  if (solve.joint_height()) {
    // The deflection as an unknown of the contact solve: the roller's potential k_eff w^2/2 + h w
    // in w = w0 + offset.
    const Real w0 = suspension.predicted_deflection();
    motion.end.centre = anchor + Vec2(0.0, w0);
    RollerPotential spring;
    spring.stiffness = suspension.effective_stiffness();
    spring.load = suspension.effective_stiffness() * w0 + suspension.history_force();
    if (const auto offset = solve.solve_height_jointly(spring, max_deflection)) {
      report.suspension_passes = 1;
      solve.solution().deflection = w0 + *offset;
      return;
    }
  }
  const CouplingResult cr = couple_suspension(suspension, suspension.predicted_deflection(), force_at,
                                              1e-10 * motion.radius, max_deflection, 40);
  report.suspension_passes = cr.iterations;
  if (!cr.converged()) {
    report.status = cr.status;
    report.message = cr.message;
  }
  solve.solution().deflection = cr.deflection;
}

namespace {

// The root finder's settings per axis. 1e-6 of the largest force of the path: far below what a
// user reads, far above the contact solves' own accuracy where F is continuous. Where a node's
// stick-slip state flips, F jumps by up to ~1e-5 of the load between two solves a round-off apart
// (Q = 0.15 P, docs/scenes.md, Force control): there 1e-4 of it is taken. A horizontal force is
// measured against the vertical one as well (a traction of 0 under a prescribed depth).
ForceControlSettings load_settings(const IncrementSolve& solve, const Vec2& largest, const Vec2& stiffness,
                                   ForceAxis axis) {
  const Real size = solve.settings().body_size;
  ForceControlSettings s;
  s.axis = axis;
  const int k = axis == ForceAxis::Vertical ? 1 : 0;
  // Line contact is about as stiff as E* per unit length, normally and tangentially; later
  // increments use the last slopes.
  const Real e_star = solve.settings().contact_modulus;
  s.stiffness_guess = stiffness(k) > 0.0 ? stiffness(k) : e_star;
  if (axis == ForceAxis::Vertical) {
    s.force_tolerance = 1e-6 * largest.y();
    s.jump_tolerance = 1e-4 * largest.y();
    s.max_offset_change = 1e3 * size;
  } else {
    const Real scale = std::max({largest.x(), largest.y(), solve.start().roller_force.norm()});
    s.force_tolerance = 1e-6 * (scale > 0.0 ? scale : 1e-6 * e_star * solve.start().motion.radius);
    s.jump_tolerance = 100.0 * s.force_tolerance;
    // A roller that must move sideways by its radius within one increment to carry the force
    // is sliding, not held by friction.
    s.max_offset_change = std::min(solve.start().motion.radius, size);
  }
  return s;
}

// The largest force prescribed per axis: the path's, the present one included.
Vec2 largest_forces(const Vec2& path_largest, const PrescribedForce& force) {
  const Vec2 present(force.fx ? std::abs(*force.fx) : 0.0, force.fy ? *force.fy : 0.0);
  return present.cwiseMax(path_largest);
}

// The forces prescribed on the roller, iterated on the centre's offsets from the path.
class LoadedRoller {
 public:
  explicit LoadedRoller(IncrementSolve& solve)
      : solve_(solve),
        force_(solve.start().force),
        path_(solve.motion().end.centre - solve.start().load_offset),
        largest_(largest_forces(solve.settings().largest_force, force_)) {}

  void couple() {
    IncrementReport& report = solve_.report();
    if (!force_.fx) {
      if (!solve_at_x()) {
        if (report.converged()) report.status = Termination::Failed;
        report.message = failure_;
      }
      return;
    }
    // A horizontal force: an outer iteration on x whose every solve carries the vertical one.
    auto fx_at = [&](Real w) -> std::optional<Real> {
      solve_.motion().end.centre.x() = path_.x() + w;
      const std::optional<Vec2> f = solve_at_x();
      if (!f) return std::nullopt;
      if (!force_.fy) ++report.load_passes;  // a solve per x; counted within the vertical iteration otherwise
      return f->x();
    };
    const ForceControlResult fc =
        solve_for_force(*force_.fx, solve_.start().load_offset.x(), settings(ForceAxis::Horizontal), fx_at);
    if (!fc.converged()) {
      report.status = failure_.empty() ? fc.status : Termination::Failed;
      report.message = failure_.empty() ? fc.message : failure_;
      return;
    }
    solve_.solution().load_offset.x() = fc.offset;
    solve_.solution().load_stiffness.x() = fc.stiffness;
  }

 private:
  ForceControlSettings settings(ForceAxis axis) const {
    return load_settings(solve_, largest_, solve_.solution().load_stiffness, axis);
  }

  // Keeps the first failure's message (an inner one says more than the outer).
  std::nullopt_t fail(const std::string& message) {
    if (failure_.empty()) failure_ = message;
    return std::nullopt;
  }

  // One contact solve at the centre's present place: the strip's force on the roller, or nullopt.
  std::optional<Vec2> solve_once() {
    if (!solve_.solve_contact()) return std::nullopt;
    return solve_.strip_force();
  }

  // The contact at the centre's present x, under the prescribed vertical force if any: the strip's
  // force on the roller, or nullopt.
  std::optional<Vec2> solve_at_x() {
    if (!force_.fy) {
      const std::optional<Vec2> f = solve_once();
      if (!f) return fail(fmt::format("the contact solve failed: {}", solve_.solution().contact.message));
      return f;
    }
    IncrementSolution& solution = solve_.solution();
    RollerMotion& motion = solve_.motion();
    // The roller on the strip already (the last increment's contact): the height as an unknown of
    // the contact solve, the load's potential F w (IncrementProblem::free_roller with stiffness 0),
    // so F_y = F at the solution. A roller still to meet the strip finds it by passes: nothing sets
    // the joint solve's length scale and working set before contact.
    if (solve_.start().friction->touching() && solve_.joint_height()) {
      const Real w0 = solution.load_offset.y();
      motion.end.centre.y() = path_.y() + w0;
      RollerPotential load;
      load.load = *force_.fy;
      ++solve_.report().load_passes;
      if (const auto offset = solve_.solve_height_jointly(load, settings(ForceAxis::Vertical).max_offset_change)) {
        solution.load_offset.y() = w0 + *offset;
        return solve_.strip_force();
      }
    }
    std::optional<Vec2> last;
    auto fy_at = [&](Real w) -> std::optional<Real> {
      motion.end.centre.y() = path_.y() + w;
      last = solve_once();
      if (!last) return std::nullopt;
      return last->y();
    };
    const ForceControlResult fc =
        solve_for_force(*force_.fy, solution.load_offset.y(), settings(ForceAxis::Vertical), fy_at);
    solve_.report().load_passes += fc.iterations;
    if (!fc.converged()) return fail(fc.message);
    solution.load_offset.y() = fc.offset;
    solution.load_stiffness.y() = fc.stiffness;
    return last;
  }

  IncrementSolve& solve_;
  const PrescribedForce force_;
  const Vec2 path_;  // the path's centre at the increment's end, without the load offset
  const Vec2 largest_;
  std::string failure_;
};

}  // namespace

void couple_loaded(IncrementSolve& solve) { LoadedRoller(solve).couple(); }

}  // namespace roller
