#include "run_outputs.hpp"

#include <cmath>

#include <fmt/format.h>

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

// Contact pressure and tangential traction of a node [MPa]: its forces over its tributary length
// (contact.csv's p_n, p_t and the VTU's contact fields).
Vec2 tractions(const NodeContactRecord& c) {
  return Vec2(c.contact.normal_force, c.contact.tangential_force) / c.tributary_length;
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

// One table row: each column's name beside its value, so that the header and the rows come
// from the same list (the header is the names of a row of an empty record).
using Row = std::vector<std::pair<const char*, CsvTable::Cell>>;

std::vector<std::string> names_of(const Row& row) {
  std::vector<std::string> names;
  for (const auto& [name, cell] : row) names.emplace_back(name);
  return names;
}

std::vector<CsvTable::Cell> cells_of(const Row& row) {
  std::vector<CsvTable::Cell> cells;
  for (const auto& [name, cell] : row) cells.push_back(cell);
  return cells;
}

Row solver_row(const Simulation::StepRecord& r, const MonitorReport& monitor, double wall_s) {
  const IpoptDetails& stats = r.details.get<IpoptDetails>();
  const StripMonotonicity& mono = monitor.pointwise;
  const Index not_checked = -1;
  return {{"step", Index{r.step}},
          {"pass", Index{r.pass}},
          {"time", r.time},
          {"iterations", Index{r.counters.iterations}},
          {"residual", r.last.residual},
          {"max_penetration", r.max_penetration},
          {"wall_s", wall_s},
          {"cuts", Index{r.cuts}},
          {"yielded_points", r.n_yielded},
          {"factorizations", Index{r.counters.factorizations}},
          {"complementarity", stats.complementarity},
          {"constraint_violation", stats.constraint_violation},
          {"fixed_point_iterations", static_cast<Real>(stats.fixed_point_iterations)},
          {"contact_nodes", r.n_contact()},
          {"a_not_pd_points", monitor.checked ? mono.n_not_pd : not_checked},
          {"a_lambda_min", std::isfinite(mono.lambda_min) ? mono.lambda_min : 0.0},
          {"k_eff_positive_definite",
           monitor.checked ? static_cast<Index>(monitor.assembled.positive_definite() ? 1 : 0) : not_checked},
          {"k_eff_negative_pivots", monitor.checked ? monitor.assembled.n_negative : not_checked},
          {"dt_restore", std::isfinite(mono.dt_restore_all) ? mono.dt_restore_all : 0.0},
          {"kinetic_energy", r.kinetic_energy},
          {"suspension_passes", static_cast<Real>(r.last.suspension_passes)},
          {"load_passes", static_cast<Real>(r.last.load_passes)},
          {"linearisations", static_cast<Real>(stats.linearisations)},
          {"nlp_solves", static_cast<Real>(stats.nlp_solves)},
          {"condensed_dofs", static_cast<Real>(stats.condensed_dofs)},
          {"ipopt_time_s", stats.ipopt_time_s},
          {"cold_restarts", static_cast<Real>(stats.cold_restarts)},
          {"status", std::string(r.converged ? "converged" : "failed")}};
}

Row contact_row(int step, int pass, const NodeContactRecord& c) {
  const Vec2 p = tractions(c);
  return {{"step", Index{step}},   {"pass", Index{pass}}, {"node", c.node + 1},
          {"x", c.position.x()},   {"y", c.position.y()}, {"gap", c.contact.gap},
          {"p_n", p.x()},          {"p_t", p.y()},        {"status", std::string(to_string(c.contact.status))},
          {"slip", c.contact.slip}};
}

// The prescribed forces, or empty cells in a step whose motion is prescribed.
CsvTable::Cell optional_cell(const std::optional<Real>& value) {
  return value ? CsvTable::Cell(*value) : CsvTable::Cell(std::string());
}

Row roller_row(int step, int pass, Real time, const Simulation::RollerRecord& r) {
  return {{"step", Index{step}},
          {"pass", Index{pass}},
          {"time", time},
          {"xc", r.pose.centre.x()},
          {"yc", r.pose.centre.y()},
          {"phi", r.pose.angle},
          {"fx", r.force.x()},
          {"fy", r.force.y()},
          {"vx", r.velocity.x()},
          {"vy", r.velocity.y()},
          {"anchor_y", r.anchor_y},
          {"deflection", r.deflection},
          {"deflection_velocity", r.deflection_velocity},
          {"deflection_acceleration", r.deflection_acceleration},
          {"fx_prescribed", optional_cell(r.prescribed.fx)},
          {"fy_prescribed", optional_cell(r.prescribed.fy)},
          {"load_offset_x", r.load_offset.x()},
          {"load_offset_y", r.load_offset.y()}};
}

Row pass_row(int step, const PassRecord& r) {
  return {{"step", Index{step}},
          {"pass", Index{r.pass}},
          {"max_plastic_increment", r.max_plastic_increment},
          {"mean_plastic_increment", r.mean_plastic_increment},
          {"band_plastic_increment", r.band_plastic_increment},
          {"surface_ux", r.surface_ux},
          {"surface_uy", r.surface_uy},
          {"surface_dux", r.surface_dux},
          {"surface_duy", r.surface_duy},
          {"shear_depth", r.shear_depth},
          {"residual_shear_strain", r.residual_shear_strain},
          {"residual_shear_increment", r.residual_shear_increment},
          {"peak_pressure", r.peak_pressure},
          {"contact_half_width", r.contact_half_width},
          {"track_start", r.track_start},
          {"track_end", r.track_end}};
}

Row depth_row(int step, int pass, Real x, const DepthSample& d) {
  return {{"step", Index{step}}, {"pass", Index{pass}}, {"x", x},
          {"depth", d.depth},    {"sxx", d.stress(0)},  {"syy", d.stress(1)},
          {"szz", d.stress(2)},  {"sxy", d.stress(3)},  {"eq_plastic_strain", d.plastic_strain}};
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
    for (int step = 0; step <= steps_done; ++step)
      if (std::filesystem::exists(vtu_path(step))) series_.add(step * scene.steps.dt, vtu_path(step));
  } else {
    write_fields(0, {});
  }
}

std::filesystem::path RunOutputs::vtu_path(int step) const { return out_dir_ / fmt::format("step_{:04d}.vtu", step); }

void RunOutputs::write_fields(int step, const std::vector<NodeContactRecord>& contact) {
  if (!scene_.output.vtu) return;
  StripFields f = strip_fields(model_, model_.total_displacement() - step_start_displacement_);
  if (scene_.roller) append_contact_fields(contact, model_.mesh().n_nodes(), f.point_data);
  if (scene_.dynamics.strip_inertia) {
    f.point_data.push_back(nodal_vector("velocity", dynamics_.velocity()));
    f.point_data.push_back(nodal_vector("acceleration", dynamics_.acceleration()));
  }
  // The mesh's topology never changes; the coordinates and fields are this step's copies. The
  // series lists the file once it is complete.
  writer_.submit([this, path = vtu_path(step), time = step * scene_.steps.dt, &mesh = model_.mesh(),
                  x = model_.current_coordinates(), f = std::move(f)] {
    write_vtu(path, mesh, x, f.point_data, f.cell_data);
    const std::lock_guard<std::mutex> lock(series_mutex_);
    series_.add(time, path);
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
  if (step.step % scene_.output.every == 0 || step.step == scene_.total_steps()) write_fields(step.step, step.contact);
  step_start_displacement_ = model_.total_displacement();
}

}  // namespace roller
