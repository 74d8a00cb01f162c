#include "run_outputs.hpp"

#include <cmath>

#include <fmt/format.h>

#include "roller/driver/output_columns.hpp"
#include "roller/io/field_output.hpp"

namespace roller {

namespace {

// A table created afresh, or continued after the resumed step.
std::unique_ptr<CsvTable> open_table(const std::filesystem::path& path, std::vector<std::string> columns, bool resume,
                                     int resumed_step) {
  if (resume) return std::make_unique<CsvTable>(path, std::move(columns), resumed_step);
  return std::make_unique<CsvTable>(path, std::move(columns));
}

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

}  // namespace

RunOutputs::RunOutputs(const Scene& scene, const StripModel& model, const DynamicsState& dynamics,
                       const RollerPose& start_pose, int steps_done, const std::filesystem::path& out_dir, bool resume,
                       BackgroundWriter& writer)
    : scene_(scene),
      model_(model),
      dynamics_(dynamics),
      writer_(writer),
      out_dir_(out_dir),
      step_start_displacement_(model.total_displacement()),
      series_(out_dir / "fields.pvd") {
  if (scene.roller) roller_series_.emplace(out_dir / "roller.pvd");
  const Simulation::StepRecord empty;
  solver_csv_ =
      open_table(out_dir / "solver.csv", names_of(solver_row(empty, MonitorReport{}, 0.0)), resume, steps_done);
  if (scene.roller) {
    contact_csv_ =
        open_table(out_dir / "contact.csv", names_of(contact_row(0, 1, NodeContactRecord{})), resume, steps_done);
    Simulation::RollerRecord start;
    start.pose = start_pose;
    start.anchor_y = start_pose.centre.y();
    roller_csv_ = open_table(out_dir / "roller.csv", names_of(roller_row(0, 1, 0.0, start)), resume, steps_done);
    if (!resume) roller_csv_->add_row(cells_of(roller_row(0, 1, 0.0, start)));
  }
  if (scene.passes.count > 1) {
    passes_csv_ = open_table(out_dir / "passes.csv", names_of(pass_row(0, PassRecord{})), resume, steps_done);
    depth_csv_ =
        open_table(out_dir / "residual_depth.csv", names_of(depth_row(0, 1, 0.0, DepthSample{})), resume, steps_done);
  }
  if (resume) {
    for (int step = 0; step <= steps_done; ++step) {
      if (std::filesystem::exists(vtu_path(step))) series_.add(step * scene.steps.dt, vtu_path(step));
      if (roller_series_ && std::filesystem::exists(vtp_path(step)))
        roller_series_->add(step * scene.steps.dt, vtp_path(step));
    }
  } else {
    write_fields(0, 1, {}, scene.roller ? std::optional<RollerPose>(start_pose) : std::nullopt);
  }
}

std::filesystem::path RunOutputs::vtu_path(int step) const { return out_dir_ / fmt::format("step_{:04d}.vtu", step); }
std::filesystem::path RunOutputs::vtp_path(int step) const { return out_dir_ / fmt::format("roller_{:04d}.vtp", step); }

namespace {

// What a file of step `step` is (ParaView shows field data under Information): step, pass, time.
std::vector<VtuField> step_field_data(int step, int pass, Real time) {
  std::vector<VtuField> data(3);
  data[0].name = "step";
  data[0].values = {static_cast<Real>(step)};
  data[1].name = "pass";
  data[1].values = {static_cast<Real>(pass)};
  data[2].name = "time";
  data[2].values = {time};
  return data;
}

}  // namespace

void RunOutputs::write_fields(int step, int pass, const std::vector<NodeContactRecord>& contact,
                              const std::optional<RollerPose>& roller) {
  if (!scene_.output.vtu) return;
  StripFields f = strip_fields(model_, model_.total_displacement() - step_start_displacement_);
  if (scene_.roller) append_contact_fields(contact, model_.mesh().n_nodes(), f.point_data);
  if (scene_.dynamics.strip_inertia) {
    f.point_data.push_back(nodal_vector("velocity", dynamics_.velocity()));
    f.point_data.push_back(nodal_vector("acceleration", dynamics_.acceleration()));
  }
  const Real time = step * scene_.steps.dt;
  // The mesh and its reference coordinates never change; the fields are this step's copies. One
  // job writes the step's files (the strip's and the roller's: the writer keeps few jobs queued),
  // and a series lists a file once it is complete.
  std::optional<RollerPose> pose = roller;
  writer_.submit(
      [this, step, time, pose, &mesh = model_.mesh(), f = std::move(f), info = step_field_data(step, pass, time)] {
        write_vtu(vtu_path(step), mesh, mesh.nodes, f.point_data, f.cell_data, VtuCompression::ZLib, info);
        if (pose) write_roller_vtp(vtp_path(step), pose->centre, scene_.roller->radius, pose->angle, info);
        const std::lock_guard<std::mutex> lock(series_mutex_);
        series_.add(time, vtu_path(step));
        if (pose && roller_series_) roller_series_->add(time, vtp_path(step));
      });
}

void RunOutputs::write_solver_row(const Simulation::StepRecord& step, const MonitorReport& monitor, double wall_s) {
  solver_csv_->add_row(cells_of(solver_row(step, monitor, wall_s)));
}

void RunOutputs::write_step(const Simulation::StepRecord& step) {
  if (step.pass_end && passes_csv_) {
    const PassRecord& r = step.pass_end->record;
    passes_csv_->add_row(cells_of(pass_row(step.step, r)));
    for (const DepthSample& d : step.pass_end->profile)
      depth_csv_->add_row(cells_of(depth_row(step.step, r.pass, step.pass_end->profile_x, d)));
  }
  if (step.roller) {
    for (const auto& c : step.contact) contact_csv_->add_row(cells_of(contact_row(step.step, step.pass, c)));
    roller_csv_->add_row(cells_of(roller_row(step.step, step.pass, step.time, *step.roller)));
  }
  if (step.step % scene_.output.every == 0 || step.step == scene_.total_steps())
    write_fields(step.step, step.pass, step.contact,
                 step.roller ? std::optional<RollerPose>(step.roller->pose) : std::nullopt);
  step_start_displacement_ = model_.total_displacement();
}

}  // namespace roller
