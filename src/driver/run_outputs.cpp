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

}  // namespace

RunOutputs::RunOutputs(const Simulation& sim, const std::filesystem::path& out_dir, bool resume,
                       BackgroundWriter& writer)
    : sim_(sim),
      writer_(writer),
      out_dir_(out_dir),
      step_start_displacement_(sim.model().total_displacement()),
      series_(out_dir / "fields.pvd") {
  const int done = sim.steps_done();
  solver_csv_ = open_table(out_dir / "solver.csv",
                           {"step",
                            "pass",
                            "time",
                            "iterations",
                            "residual",
                            "max_penetration",
                            "wall_s",
                            "cuts",
                            "yielded_points",
                            "factorizations",
                            "complementarity",
                            "constraint_violation",
                            "fixed_point_iterations",
                            "contact_nodes",
                            "a_not_pd_points",
                            "a_lambda_min",
                            "k_eff_positive_definite",
                            "k_eff_negative_pivots",
                            "dt_restore",
                            "kinetic_energy",
                            "suspension_passes",
                            "load_passes",
                            "linearisations",
                            "nlp_solves",
                            "condensed_dofs",
                            "ipopt_time_s",
                            "cold_restarts",
                            "status"},
                           resume, done);
  if (sim.scene().roller) {
    contact_csv_ = open_table(out_dir / "contact.csv",
                              {"step", "pass", "node", "x", "y", "gap", "p_n", "p_t", "status", "slip"}, resume, done);
    roller_csv_ = open_table(out_dir / "roller.csv",
                             {"step", "pass", "time", "xc", "yc", "phi", "fx", "fy", "vx", "vy", "anchor_y",
                              "deflection", "deflection_velocity", "deflection_acceleration", "fx_prescribed",
                              "fy_prescribed", "load_offset_x", "load_offset_y"},
                             resume, done);
    if (!resume) {
      const RollerPose& pose = sim.pose();
      roller_csv_->add_row({Index{0}, Index{1}, 0.0, pose.centre.x(), pose.centre.y(), pose.angle, 0.0, 0.0, 0.0, 0.0,
                            pose.centre.y(), 0.0, 0.0, 0.0, std::string(), std::string(), 0.0, 0.0});
    }
  }
  if (sim.scene().passes.count > 1) {
    passes_csv_ =
        open_table(out_dir / "passes.csv",
                   {"step", "pass", "max_plastic_increment", "mean_plastic_increment", "band_plastic_increment",
                    "surface_ux", "surface_uy", "surface_dux", "surface_duy", "shear_depth", "residual_shear_strain",
                    "residual_shear_increment", "peak_pressure", "contact_half_width", "track_start", "track_end"},
                   resume, done);
    depth_csv_ =
        open_table(out_dir / "residual_depth.csv",
                   {"step", "pass", "x", "depth", "sxx", "syy", "szz", "sxy", "eq_plastic_strain"}, resume, done);
  }
  if (resume) {
    for (int step = 0; step <= done; ++step)
      if (std::filesystem::exists(vtu_path(step))) series_.add(step * sim.scene().steps.dt, vtu_path(step));
  } else {
    write_fields(0);
  }
}

std::filesystem::path RunOutputs::vtu_path(int step) const { return out_dir_ / fmt::format("step_{:04d}.vtu", step); }

void RunOutputs::write_fields(int step) {
  const Scene& scene = sim_.scene();
  if (!scene.output.vtu) return;
  StripFields f = strip_fields(sim_.model(), sim_.model().total_displacement() - step_start_displacement_);
  if (scene.roller) append_contact_fields(sim_.contact(), sim_.model().mesh().n_nodes(), f.point_data);
  if (scene.dynamics.strip_inertia) {
    f.point_data.push_back(nodal_vector("velocity", sim_.velocity()));
    f.point_data.push_back(nodal_vector("acceleration", sim_.acceleration()));
  }
  // The mesh's topology never changes; the coordinates and fields are this step's copies. The
  // series lists the file once it is complete.
  writer_.submit([this, path = vtu_path(step), time = step * scene.steps.dt, &mesh = sim_.model().mesh(),
                  x = sim_.model().current_coordinates(), f = std::move(f)] {
    write_vtu(path, mesh, x, f.point_data, f.cell_data);
    const std::lock_guard<std::mutex> lock(series_mutex_);
    series_.add(time, path);
  });
}

void RunOutputs::write_solver_row(int step, const Simulation::StepResult& res, const MonitorReport& monitor,
                                  double wall_s, Index n_contact) {
  const BackendStats& stats = res.stats;
  const StripMonotonicity& mono = monitor.pointwise;
  const Index not_checked = -1;
  solver_csv_->add_row(
      {static_cast<Index>(step),
       static_cast<Index>(sim_.pass_of_step(step)),
       step * sim_.scene().steps.dt,
       static_cast<Index>(res.iterations),
       res.last.residual,
       res.max_penetration,
       wall_s,
       static_cast<Index>(res.cuts),
       res.n_yielded,
       static_cast<Index>(res.factorizations),
       stats.complementarity,
       stats.constraint_violation,
       static_cast<Real>(stats.fixed_point_iterations),
       n_contact,
       monitor.checked ? mono.n_not_pd : not_checked,
       std::isfinite(mono.lambda_min) ? mono.lambda_min : 0.0,
       monitor.checked ? static_cast<Index>(monitor.assembled.positive_definite() ? 1 : 0) : not_checked,
       monitor.checked ? monitor.assembled.n_negative : not_checked,
       std::isfinite(mono.dt_restore_all) ? mono.dt_restore_all : 0.0,
       sim_.kinetic_energy(),
       static_cast<Real>(res.last.suspension_passes),
       static_cast<Real>(res.last.load_passes),
       static_cast<Real>(stats.linearisations),
       static_cast<Real>(stats.nlp_solves),
       static_cast<Real>(stats.condensed_dofs),
       stats.ipopt_time_s,
       static_cast<Real>(stats.cold_restarts),
       std::string(res.converged ? "converged" : "failed")});
}

void RunOutputs::write_step(int step, const std::optional<Simulation::StepResult::PassEnd>& pass_end) {
  if (pass_end && passes_csv_) {
    const PassRecord& r = pass_end->record;
    const Index s = step, pass = r.pass;
    passes_csv_->add_row({s, pass, r.max_plastic_increment, r.mean_plastic_increment, r.band_plastic_increment,
                          r.surface_ux, r.surface_uy, r.surface_dux, r.surface_duy, r.shear_depth,
                          r.residual_shear_strain, r.residual_shear_increment, r.peak_pressure, r.contact_half_width,
                          r.track_start, r.track_end});
    for (const DepthSample& d : pass_end->profile)
      depth_csv_->add_row({s, pass, pass_end->profile_x, d.depth, d.stress(0), d.stress(1), d.stress(2), d.stress(3),
                           d.plastic_strain});
  }
  const Scene& scene = sim_.scene();
  if (scene.roller) {
    const Index pass = sim_.pass_of_step(step);
    for (const auto& c : sim_.contact()) {
      const Vec2 p = tractions(c);
      contact_csv_->add_row({static_cast<Index>(step), pass, c.node + 1, c.position.x(), c.position.y(), c.contact.gap,
                             p.x(), p.y(), std::string(to_string(c.contact.status)), c.contact.slip});
    }
    const Vec2 f = sim_.roller_force();
    const RollerPose& pose = sim_.pose();
    const Vec2 v = sim_.roller_velocity();
    const Real anchor_y = sim_.prescribed_pose(step).centre.y();
    const Suspension* suspension = sim_.suspension();
    // The prescribed forces, or empty cells in a step whose motion is prescribed.
    const PrescribedForce force = sim_.prescribed_force(step);
    auto cell = [](const std::optional<Real>& value) {
      return value ? CsvTable::Cell(*value) : CsvTable::Cell(std::string());
    };
    roller_csv_->add_row({static_cast<Index>(step), pass, step * scene.steps.dt, pose.centre.x(), pose.centre.y(),
                          pose.angle, f.x(), f.y(), v.x(), v.y(), anchor_y, suspension ? suspension->deflection() : 0.0,
                          sim_.suspension_velocity(), sim_.suspension_acceleration(), cell(force.fx), cell(force.fy),
                          sim_.load_offset().x(), sim_.load_offset().y()});
  }
  if (step % scene.output.every == 0 || step == scene.total_steps()) write_fields(step);
  step_start_displacement_ = sim_.model().total_displacement();
}

}  // namespace roller
