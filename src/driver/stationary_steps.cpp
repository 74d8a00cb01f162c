// The stationary method (step_method.hpp): one step is one pass (steady/stationary_passes.hpp).
#include <algorithm>

#include <fmt/format.h>

#include "pass_fatigue.hpp"
#include "roller/analysis/pass_metrics.hpp"
#include "roller/contact/contact_records.hpp"
#include "roller/io/field_output.hpp"
#include "roller/steady/stationary_passes.hpp"
#include "roller/steady/steady_load.hpp"
#include "run_outputs.hpp"
#include "step_method.hpp"

namespace roller {

namespace {

class StationarySteps final : public StepMethod {
 public:
  // A stationary pass (one step) carries its travel segment's load whole, not the ramp the step's
  // number would read in a transient pass's program.
  explicit StationarySteps(RunModel& run)
      : run_(run), steady_(steady_load(run.scene, std::nullopt)), program_step_(steady_.travel->last_step) {
    require_stationary_load(run.scene, steady_);  // before the first step: a load the set-up refuses
  }

  StepRecord advance(int step, const StepOptions& control) override {
    const bool built = !passes_;  // K_e is factorised once, when the set-up is built
    if (built) passes_ = std::make_unique<StationaryPasses>(run_.scene, *run_.strip, steady_);
    StationaryPasses& passes = *passes_;
    StepRecord res;
    res.step = step;
    res.pass = step;
    res.time = step * run_.scene.steps.dt;
    const PassBaseline baseline = PassBaseline::of(*run_.strip);
    const std::vector<DepthSample> at_start =  // the fatigue cycle's start
        run_.scene.fatigue ? depth_profile(*run_.strip, run_.scene.mesh.height, passes.extraction_x())
                           : std::vector<DepthSample>{};
    const StationaryPasses::Pass pass =
        passes.run(*run_.strip, run_.state.next_pass_start, control.progress, control.stop);
    res.counters.iterations = pass.solve.iterations;
    res.counters.factorizations = (built ? 1 : 0) + pass.factorizations;  // K_e once a run, J's a pass
    res.n_yielded = pass.solve.n_yielded;
    res.status = pass.solve.status;
    res.last.status = pass.solve.status;
    res.last.residual = pass.solve.residual;  // |r|/F of the stationary iteration
    res.last.counters = res.counters;
    run_.state.pose = passes.roller_pose();
    run_.state.contact = passes.contact();
    if (!pass.solve.converged()) {
      res.message = fmt::format("pass {}: {}", step, pass.solve.message);
      run_.record_state(res, program_step_);
      return res;
    }
    const VecX before = run_.strip->total_displacement();
    if (run_.scene.output.mid_pass && fields_written(run_.scene, step)) {  // the loaded state, for its fields
      // With phases the pass is solved on P copies of the strip, each its own block of nodes and
      // elements; the first, not shifted, is this strip.
      const VecX u = pass.solve.displacement.head(run_.strip->n_dofs());
      std::vector<MaterialState> states(
          pass.solve.states.begin(),
          pass.solve.states.begin() + static_cast<std::ptrdiff_t>(run_.strip->states().size()));
      run_.strip->restore(run_.strip->reference_coordinates(), before + u, std::move(states));
      res.loaded_fields = strip_fields(*run_.strip, u);
    }
    run_.strip->restore(run_.strip->reference_coordinates(), before + pass.permanent_displacement, pass.residual);
    ++run_.state.steps_done;
    run_.state.next_pass_start = pass.next_start;  // in the state files, so that a resumed run starts alike
    // The pass's record over the residual strip, which is uniform along x: measured at the
    // extraction column as the transient method measures the middle of its track.
    PassTrack track;
    const Real a = passes.hertz().half_width;
    track.touched = true;
    track.x_min = passes.extraction_x() - 2.0 * a;
    track.x_max = passes.extraction_x() + 2.0 * a;
    track.half_width = a;
    track.load_half_width = a;
    track.peak_pressure = passes.hertz().peak;
    // With the roller's contact: the pressure it carried.
    if (run_.scene.passes.stationary_contact == StationaryContact::Roller) {
      track.peak_pressure = 0.0;
      for (const PressureSample& s : pressure_profile(passes.contact(), passes.roller_pose()))
        track.peak_pressure = std::max(track.peak_pressure, s.p);
    }
    if (passes.creep()) track.set_creep(*passes.creep());
    StepRecord::PassEnd end;
    end.record = measure_pass(step, *run_.strip, run_.scene.mesh.height, track, baseline);
    end.profile_x = passes.extraction_x();
    end.profile = depth_profile(*run_.strip, run_.scene.mesh.height, end.profile_x);
    if (run_.scene.fatigue) {  // the cycle every point of a row takes through the steady pass
      end.fatigue =
          fatigue_of_pass(run_.scene, end.record, end.profile_x,
                          framed(passes.cycles(pass.solve.states, run_.scene.mesh.height), at_start, end.profile),
                          -force_on_roller(passes.contact()));
      run_.state.fatigue = answer_of(*end.fatigue);
    }
    run_.state.pass_records.push_back(end.record);
    if (run_.scene.passes.count > 1) res.pass_end = end;
    run_.record_state(res, program_step_);
    return res;
  }

 private:
  RunModel& run_;
  SteadyLoad steady_;  // the scene's travel and its load, computed once
  int program_step_;
  std::unique_ptr<StationaryPasses> passes_;  // the method's set-up, built at its first pass
};

}  // namespace

std::unique_ptr<StepMethod> make_stationary_steps(RunModel& run) { return std::make_unique<StationarySteps>(run); }

}  // namespace roller
