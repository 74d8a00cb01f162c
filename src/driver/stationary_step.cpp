// Simulation::advance_step of the stationary method: one step is one pass (stationary_passes.hpp).
#include <algorithm>

#include <fmt/format.h>

#include "roller/analysis/pass_metrics.hpp"
#include "roller/driver/simulation.hpp"
#include "roller/io/field_output.hpp"
#include "roller_contact_correction.hpp"
#include "run_outputs.hpp"

namespace roller {

Simulation::StepRecord Simulation::advance_stationary(int step) {
  const bool built = !stationary_;  // K_e is factorised once, when the set-up is built
  if (built) stationary_ = std::make_unique<StationaryPasses>(scene_, *model_, make_roller_contact_correction);
  StationaryPasses& passes = *stationary_;
  StepRecord res;
  res.step = step;
  res.pass = step;
  res.time = step * scene_.steps.dt;
  const PassBaseline baseline = PassBaseline::of(*model_);
  const StationaryPasses::Pass pass = passes.run(*model_, state_.last_increment, progress_, stop_);
  res.counters.iterations = pass.solve.iterations;
  res.counters.factorizations = (built ? 1 : 0) + pass.factorizations;  // K_e once a run, J's a pass
  res.n_yielded = pass.solve.n_yielded;
  res.status = pass.solve.status;
  res.last.status = pass.solve.status;
  res.last.residual = pass.solve.residual;  // |r|/F of the stationary iteration
  res.last.counters = res.counters;
  state_.pose = passes.roller_pose();
  state_.contact = passes.contact();
  if (!pass.solve.converged()) {
    res.message = fmt::format("pass {}: {}", step, pass.solve.message);
    record_state(res);
    return res;
  }
  const VecX before = model_->total_displacement();
  if (scene_.output.mid_pass && fields_written(scene_, step)) {  // the loaded state, for its fields
    // With phases the pass is solved on P copies of the strip, each its own block of nodes and
    // elements; the first, not shifted, is this strip.
    const VecX u = pass.solve.displacement.head(model_->n_dofs());
    std::vector<MaterialState> states(pass.solve.states.begin(),
                                      pass.solve.states.begin() + static_cast<std::ptrdiff_t>(model_->states().size()));
    model_->restore(model_->reference_coordinates(), before + u, std::move(states));
    res.loaded_fields = strip_fields(*model_, u);
  }
  model_->restore(model_->reference_coordinates(), before + pass.permanent_displacement, pass.residual);
  ++state_.steps_done;
  state_.last_increment = pass.next_start;  // in the state files, so that a resumed run starts alike
  state_.last_length = 0.0;
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
  if (scene_.passes.stationary_contact == StationaryContact::Roller) {  // the pressure the roller's contact carried
    track.peak_pressure = 0.0;
    for (const PressureSample& s : pressure_profile(passes.contact(), passes.roller_pose()))
      track.peak_pressure = std::max(track.peak_pressure, s.p);
  }
  StepRecord::PassEnd end;
  end.record = measure_pass(step, *model_, scene_.mesh.height, track, baseline);
  end.profile_x = passes.extraction_x();
  end.profile = depth_profile(*model_, scene_.mesh.height, end.profile_x);
  state_.pass_records.push_back(end.record);
  if (scene_.passes.count > 1) res.pass_end = end;
  record_state(res);
  return res;
}

}  // namespace roller
