#include "run_outputs.hpp"

#include "pass_fatigue.hpp"
#include "roller/analysis/roller_flattening.hpp"

namespace roller {

namespace {

VtuField nodal_vector(const std::string& name, const VecX& v) {
  VtuField f;
  f.name = name;
  f.n_components = 3;
  f.values.assign(3 * (v.size() / 2), 0.0);
  for (Index a = 0; a < v.size() / 2; ++a) {
    f.values[3 * a] = v(2 * a);
    f.values[3 * a + 1] = v(2 * a + 1);
  }
  return f;
}

// tractions() and the status (0 open or not a candidate, 1 stick, 2 slip) at the nodes.
void append_contact_fields(const std::vector<NodeContactRecord>& contact, Index n_nodes,
                           std::vector<VtuField>& point_data) {
  VtuField pressure, traction, status;
  pressure.name = "contact_pressure";
  traction.name = "contact_traction";
  status.name = "contact_status";
  for (VtuField* f : {&pressure, &traction, &status}) {
    f->n_components = 1;
    f->values.assign(n_nodes, 0.0);
  }
  for (const NodeContactRecord& c : contact) {
    const Vec2 p = tractions(c);
    pressure.values[c.node] = p.x();
    traction.values[c.node] = p.y();
    status.values[c.node] = c.contact.status == ContactStatus::Stick  ? 1.0
                            : c.contact.status == ContactStatus::Slip ? 2.0
                                                                      : 0.0;
  }
  point_data.push_back(std::move(pressure));
  point_data.push_back(std::move(traction));
  point_data.push_back(std::move(status));
}

// The step within each pass whose fields output.mid_pass writes: the middle of the travel.
int mid_pass_step(const Scene& scene) {
  if (!scene.output.mid_pass || scene.passes.count < 2 || scene.passes.method != PassMethod::Transient || !scene.roller)
    return 0;
  const PathSegment* travel = travel_segment(*scene.roller);
  return travel ? (travel->first_step + travel->last_step) / 2 : 0;
}

}  // namespace

bool fields_written(const Scene& scene, int step) {
  return scene.output.vtu && (step % scene.output.every == 0 || step == scene.total_steps());
}

RunOutputs::RunOutputs(const Scene& scene, const StripModel& model, const DynamicsState& dynamics,
                       const RollerPose& start_pose, bool fresh, std::vector<OutputSink*> sinks)
    : scene_(scene),
      model_(model),
      dynamics_(dynamics),
      sinks_(std::move(sinks)),
      step_start_displacement_(model.total_displacement()),
      mid_pass_step_(mid_pass_step(scene)) {
  if (scene.output.vtu && !sinks_.empty() && scene.roller && scene.roller->elastic())
    disc_ = std::make_unique<RollerDiscFields>(scene, model.mesh());
  if (!fresh) return;
  if (scene.roller) {
    Simulation::RollerRecord start;
    start.pose = start_pose;
    start.anchor_y = start_pose.centre.y();
    start.effective_radius =
        roller_flattening({}, start_pose.centre, scene.roller->radius, scene.roller->elastic()).effective_radius;
    add_row(OutputTable::Roller, roller_row(0, 1, 0.0, start));
  }
  write_fields(0, 1, {}, scene.roller ? std::optional<RollerPose>(start_pose) : std::nullopt);
}

void RunOutputs::add_row(OutputTable table, const Row& row) {
  for (OutputSink* sink : sinks_) sink->add_row(table, row);
}

void RunOutputs::write_fields(int step, int pass, const std::vector<NodeContactRecord>& contact,
                              const std::optional<RollerPose>& roller, std::vector<VtuField> cells) {
  if (!scene_.output.vtu || sinks_.empty()) return;
  StepFields f{step,
               pass,
               step * scene_.steps.dt,
               strip_fields(model_, model_.total_displacement() - step_start_displacement_),
               roller,
               false,
               nullptr};
  for (VtuField& c : cells) f.strip.cell_data.push_back(std::move(c));
  if (scene_.roller) append_contact_fields(contact, model_.mesh().n_nodes(), f.strip.point_data);
  if (scene_.dynamics.strip_inertia) {
    f.strip.point_data.push_back(nodal_vector("velocity", dynamics_.velocity()));
    f.strip.point_data.push_back(nodal_vector("acceleration", dynamics_.acceleration()));
  }
  if (disc_ && roller) f.roller_body = disc_->at(contact, roller->centre);
  add_fields(std::move(f));
}

void RunOutputs::add_fields(StepFields f) {
  for (std::size_t i = 0; i + 1 < sinks_.size(); ++i) sinks_[i]->add_fields(f);
  sinks_.back()->add_fields(std::move(f));
}

void RunOutputs::write_loaded_fields(const Simulation::StepRecord& step) {
  if (sinks_.empty()) return;  // written only where the step's own fields are (fields_written)
  StepFields f{step.step,
               step.pass,
               (step.step - 0.5) * scene_.steps.dt,
               *step.loaded_fields,
               step.roller ? std::optional<RollerPose>(step.roller->pose) : std::nullopt,
               true,
               nullptr};
  append_contact_fields(step.contact, model_.mesh().n_nodes(), f.strip.point_data);
  if (disc_ && step.roller) f.roller_body = disc_->at(step.contact, step.roller->pose.centre);
  add_fields(std::move(f));
}

void RunOutputs::write_solver_row(const Simulation::StepRecord& step, const MonitorReport& monitor, double wall_s) {
  add_row(OutputTable::Solver, solver_row(step, monitor, wall_s));
}

void RunOutputs::write_step(const Simulation::StepRecord& step) {
  if (step.pass_end) {  // multi-pass runs only
    const PassRecord& r = step.pass_end->record;
    add_row(OutputTable::Passes, pass_row(step.step, r));
    for (const DepthSample& d : step.pass_end->profile)
      add_row(OutputTable::ResidualDepth, depth_row(step.step, r.pass, step.pass_end->profile_x, d));
    if (const std::optional<PassFatigue>& f = step.pass_end->fatigue)
      for (const FatigueAtDepth& d : f->depths) add_row(OutputTable::Fatigue, fatigue_row(step.step, r.pass, f->x, d));
  }
  if (step.roller) {
    for (const auto& c : step.contact) add_row(OutputTable::Contact, contact_row(step.step, step.pass, c));
    add_row(OutputTable::Roller, roller_row(step.step, step.pass, step.time, *step.roller));
  }
  const bool mid_pass = mid_pass_step_ > 0 && (step.step - 1) % scene_.steps.n_steps + 1 == mid_pass_step_;
  if (step.loaded_fields) write_loaded_fields(step);
  if (fields_written(scene_, step.step) || mid_pass) {
    std::vector<VtuField> fatigue;  // only where the fields are written
    if (scene_.output.vtu && step.pass_end && step.pass_end->fatigue)
      fatigue = fatigue_cell_fields(model_.mesh(), scene_.mesh.height, *step.pass_end->fatigue,
                                    step.pass_end->record.track_start, step.pass_end->record.track_end);
    write_fields(step.step, step.pass, step.contact,
                 step.roller ? std::optional<RollerPose>(step.roller->pose) : std::nullopt, std::move(fatigue));
  }
  step_start_displacement_ = model_.total_displacement();
}

}  // namespace roller
