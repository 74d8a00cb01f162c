// The transient method (step_method.hpp): a step is solved as increments of the strip under the
// moving roller, cut into 2, 4, ... sub-increments when one fails, up to steps.max_cuts times.
#include <algorithm>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "pass_fatigue.hpp"
#include "roller/analysis/hertz.hpp"
#include "roller/contact/contact_records.hpp"
#include "step_method.hpp"
#include "transient_increments.hpp"

namespace roller {

namespace {

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

class TransientSteps final : public StepMethod {
 public:
  TransientSteps(RunModel& run, TransientIncrements& increments) : run_(run), increments_(increments) {}

  StepRecord advance(int step, const StepOptions& /*control*/) override {
    StepRecord res;
    res.step = step;
    res.pass = run_.program.pass_of_step(step);
    res.time = step * run_.scene.steps.dt;
    // The first step of a pass after the first: the roller returns to the pass's start (undone
    // below if the step fails, so that a failed step changes nothing).
    std::optional<RunState> before_return;
    if (run_.scene.roller && run_.program.starts_later_pass(step)) {
      before_return = run_.state;
      res.message = return_for_pass(run_.program.pass_of_step(step));
      if (!res.message.empty()) {
        run_.record_state(res, step);
        return res;
      }
    }
    const Vec2 centre_start = run_.state.pose.centre;
    // Sub-increments of 1/2^cuts of the step; a failed sub-increment is halved again.
    Real s = step - 1;
    Real ds = 1.0;
    while (s < step - 1e-12) {
      IncrementReport inc = increments_.advance(s, s + ds);
      res.counters += inc.counters;
      res.details.add(inc.details);
      res.last = inc;
      if (inc.converged()) {
        s += ds;
        res.max_penetration = std::max(res.max_penetration, inc.max_penetration);
        res.n_yielded = inc.n_yielded;
        continue;
      }
      if (res.cuts >= run_.scene.steps.max_cuts) {
        res.status = inc.status;  // how the last sub-increment ended: a budget ran out, or it failed
        res.message = fmt::format("step {} failed after {} cuts (sub-increment {:.4g} of the step): {}{}", step,
                                  res.cuts, ds, inc.message, incompressibility_hint(run_.scene.strip_material()));
        if (before_return && s == step - 1) {  // nothing of the step committed: undo the return too
          run_.state = std::move(*before_return);
        }
        run_.record_state(res, step);
        return res;
      }
      ++res.cuts;
      ds *= 0.5;
    }
    res.status = Termination::Converged;
    run_.state.roller_velocity = (run_.state.pose.centre - centre_start) / run_.scene.steps.dt;
    ++run_.state.steps_done;
    run_.dynamics.finish_step(run_.strip->total_displacement());
    res.pass_end = observe_pass(step);
    run_.record_state(res, step);
    return res;
  }

 private:
  // Before the first step of pass `pass` > 1: the roller, clear of the strip, returns to the
  // pass's start; a message (and nothing changed) when it is not clear.
  std::string return_for_pass(int pass) {
    // The roller must have left the strip: no node carries a contact force, and none lies within
    // the roller at the pass's start.
    const Index touching = count_in_contact(run_.state.contact);
    if (touching > 0)
      return fmt::format(
          "pass {} ends with the roller on the strip ({} nodes in contact): end each pass with a lift (a "
          "[[roller.path]] segment with dy > 0) so that the roller can return for pass {}",
          pass - 1, touching, pass);
    // Not prescribed_pose((pass - 1) N): that step belongs to the previous pass (its end).
    const RollerPose start = run_.program.pass_start(pass);
    const std::vector<Vec2> x = run_.strip->current_coordinates();
    for (Index a : increments_.candidate_nodes())
      if ((x[a] - start.centre).norm() < (1.0 - 1e-9) * run_.scene.roller->radius)  // touching is clear
        return fmt::format(
            "pass {} would start with node {} inside the roller at ({:.6g}, {:.6g}): start the pass "
            "clear of the strip (roller.centre) or press in from above",
            pass, a + 1, start.centre.x(), start.centre.y());
    run_.state.pose = start;
    run_.state.load_offset.setZero();     // each pass meets the strip as the first did
    run_.state.last_increment.setZero();  // the lift is no predictor of the press
    run_.state.contact.clear();
    return "";
  }

  // After a converged step: observes the contact; at a pass's last step, measures the pass.
  std::optional<StepRecord::PassEnd> observe_pass(int step) {
    if (run_.scene.passes.count < 2) return std::nullopt;
    std::vector<Real> x, p;
    Real force = 0.0;
    for (const auto& c : run_.state.contact) {
      if (c.contact.status == ContactStatus::Open) continue;
      x.push_back(c.position.x());
      p.push_back(c.contact.normal_force / c.tributary_length);
      force += c.contact.normal_force;
    }
    const Real e_star = run_.scene.contact_modulus();
    const Real load_half_width =
        force > 0.0 ? hertz_line_contact(force, run_.scene.roller->radius, e_star).half_width : 0.0;
    run_.state.pass_track.observe(run_.state.pose.centre.x(), x, p, load_half_width);
    run_.state.pass_track.observe_force(-force_on_roller(run_.state.contact));  // the roller's on the strip
    run_.state.pass_track.observe_motion(run_.state.pose.centre.x(), run_.state.pose.angle, run_.scene.roller->radius,
                                         !x.empty());
    const int pass = run_.program.pass_of_step(step);
    if (run_.scene.fatigue) run_.state.pass_cycles.observe(*run_.strip, run_.scene.mesh.height);
    if (!run_.program.ends_pass(step)) return std::nullopt;
    StepRecord::PassEnd end;
    end.record =
        measure_pass(pass, *run_.strip, run_.scene.mesh.height, run_.state.pass_track, run_.state.pass_baseline);
    end.profile_x = 0.5 * (end.record.track_start + end.record.track_end);
    end.profile = depth_profile(*run_.strip, run_.scene.mesh.height, end.profile_x);
    if (run_.scene.fatigue) {
      end.fatigue = fatigue_of_pass(run_.scene, end.record, run_.state.pass_cycles.x, run_.state.pass_cycles.depths,
                                    run_.state.pass_track.largest_force);
      run_.state.fatigue = answer_of(*end.fatigue);
      // The next pass's cycle starts where this one ends: the roller lifted.
      if (pass < run_.scene.passes.count)
        run_.state.pass_cycles = start_cycles(run_.scene, run_.program, pass + 1, *run_.strip);
    }
    run_.state.pass_records.push_back(end.record);
    run_.state.pass_track = PassTrack{};
    run_.state.pass_baseline = PassBaseline::of(*run_.strip);
    return end;
  }

  RunModel& run_;
  TransientIncrements& increments_;
};

}  // namespace

std::unique_ptr<StepMethod> make_transient_steps(RunModel& run, TransientIncrements& increments) {
  return std::make_unique<TransientSteps>(run, increments);
}

}  // namespace roller
