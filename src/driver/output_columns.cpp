#include "roller/driver/output_columns.hpp"

#include <cmath>
#include <optional>

namespace roller {

std::vector<std::string> names_of(const Row& row) {
  std::vector<std::string> names;
  for (const Column& c : row) names.emplace_back(c.name);
  return names;
}

std::vector<CsvTable::Cell> cells_of(const Row& row) {
  std::vector<CsvTable::Cell> cells;
  for (const Column& c : row) cells.push_back(c.value);
  return cells;
}

Vec2 tractions(const NodeContactRecord& c) {
  return Vec2(c.contact.normal_force, c.contact.tangential_force) / c.tributary_length;
}

Row solver_row(const Simulation::StepRecord& r, const MonitorReport& monitor, double wall_s) {
  const IpoptDetails& stats = r.details.get<IpoptDetails>();
  const StripMonotonicity& mono = monitor.pointwise;
  const Index not_checked = -1;
  return {{"step", "-", Index{r.step}},
          {"pass", "-", Index{r.pass}},
          {"time", "s", r.time},
          {"iterations", "-", Index{r.counters.iterations}},
          {"residual", "1", r.last.residual},
          {"max_penetration", "mm", r.max_penetration},
          {"wall_s", "s", wall_s},
          {"cuts", "-", Index{r.cuts}},
          {"yielded_points", "-", r.n_yielded},
          {"factorizations", "-", Index{r.counters.factorizations}},
          {"complementarity", "1", stats.complementarity},
          {"constraint_violation", "mm", stats.constraint_violation},
          {"fixed_point_iterations", "-", static_cast<Real>(stats.fixed_point_iterations)},
          {"contact_nodes", "-", r.n_contact()},
          {"a_not_pd_points", "-", monitor.checked ? mono.n_not_pd : not_checked},
          {"a_lambda_min", "MPa", std::isfinite(mono.lambda_min) ? mono.lambda_min : 0.0},
          {"k_eff_positive_definite", "-",
           monitor.checked ? static_cast<Index>(monitor.assembled.positive_definite() ? 1 : 0) : not_checked},
          {"k_eff_negative_pivots", "-", monitor.checked ? monitor.assembled.n_negative : not_checked},
          {"dt_restore", "s", std::isfinite(mono.dt_restore_all) ? mono.dt_restore_all : 0.0},
          {"kinetic_energy", "N mm/mm", r.kinetic_energy},
          {"suspension_passes", "-", static_cast<Real>(r.last.suspension_passes)},
          {"load_passes", "-", static_cast<Real>(r.last.load_passes)},
          {"linearisations", "-", static_cast<Real>(stats.linearisations)},
          {"nlp_solves", "-", static_cast<Real>(stats.nlp_solves)},
          {"condensed_dofs", "-", static_cast<Real>(stats.condensed_dofs)},
          {"ipopt_time_s", "s", stats.ipopt_time_s},
          {"cold_restarts", "-", static_cast<Real>(stats.cold_restarts)},
          {"status", "-", std::string(enum_name(r.status))}};
}

Row contact_row(int step, int pass, const NodeContactRecord& c) {
  const Vec2 p = tractions(c);
  return {{"step", "-", Index{step}},
          {"pass", "-", Index{pass}},
          {"node", "-", c.node + 1},
          {"x", "mm", c.position.x()},
          {"y", "mm", c.position.y()},
          {"gap", "mm", c.contact.gap},
          {"p_n", "MPa", p.x()},
          {"p_t", "MPa", p.y()},
          {"status", "-", std::string(to_string(c.contact.status))},
          {"slip", "mm", c.contact.slip}};
}

namespace {

// The prescribed forces, or empty cells in a step whose motion is prescribed.
CsvTable::Cell optional_cell(const std::optional<Real>& value) {
  return value ? CsvTable::Cell(*value) : CsvTable::Cell(std::string());
}

}  // namespace

Row roller_row(int step, int pass, Real time, const Simulation::RollerRecord& r) {
  return {{"step", "-", Index{step}},
          {"pass", "-", Index{pass}},
          {"time", "s", time},
          {"xc", "mm", r.pose.centre.x()},
          {"yc", "mm", r.pose.centre.y()},
          {"phi", "rad", r.pose.angle},
          {"fx", "N/mm", r.force.x()},
          {"fy", "N/mm", r.force.y()},
          {"vx", "mm/s", r.velocity.x()},
          {"vy", "mm/s", r.velocity.y()},
          {"anchor_y", "mm", r.anchor_y},
          {"deflection", "mm", r.deflection},
          {"deflection_velocity", "mm/s", r.deflection_velocity},
          {"deflection_acceleration", "mm/s^2", r.deflection_acceleration},
          {"fx_prescribed", "N/mm", optional_cell(r.prescribed.fx)},
          {"fy_prescribed", "N/mm", optional_cell(r.prescribed.fy)},
          {"load_offset_x", "mm", r.load_offset.x()},
          {"load_offset_y", "mm", r.load_offset.y()},
          {"flattening", "mm", r.flattening},
          {"effective_radius", "mm", optional_cell(r.effective_radius)}};
}

Row pass_row(int step, const PassRecord& r) {
  return {{"step", "-", Index{step}},
          {"pass", "-", Index{r.pass}},
          {"max_plastic_increment", "1", r.max_plastic_increment},
          {"mean_plastic_increment", "1", r.mean_plastic_increment},
          {"band_plastic_increment", "1", r.band_plastic_increment},
          {"surface_ux", "mm", r.surface_ux},
          {"surface_uy", "mm", r.surface_uy},
          {"surface_dux", "mm", r.surface_dux},
          {"surface_duy", "mm", r.surface_duy},
          {"shear_depth", "mm", r.shear_depth},
          {"residual_shear_strain", "1", r.residual_shear_strain},
          {"residual_shear_increment", "1", r.residual_shear_increment},
          {"surface_shear_increment", "1", r.surface_shear_increment},
          {"peak_pressure", "MPa", r.peak_pressure},
          {"contact_half_width", "mm", r.contact_half_width},
          {"track_start", "mm", r.track_start},
          {"track_end", "mm", r.track_end},
          {"creep", "1", r.creep}};
}

Row depth_row(int step, int pass, Real x, const DepthSample& d) {
  return {{"step", "-", Index{step}},
          {"pass", "-", Index{pass}},
          {"x", "mm", x},
          {"depth", "mm", d.depth},
          {"sxx", "MPa", d.stress(0)},
          {"syy", "MPa", d.stress(1)},
          {"szz", "MPa", d.stress(2)},
          {"sxy", "MPa", d.stress(3)},
          {"eq_plastic_strain", "1", d.plastic_strain},
          {"back_xx", "MPa", d.back_stress(0)},
          {"back_yy", "MPa", d.back_stress(1)},
          {"back_zz", "MPa", d.back_stress(2)},
          {"back_xy", "MPa", d.back_stress(3)}};
}

Row fatigue_row(int step, int pass, Real x, const FatigueAtDepth& d) {
  return {{"step", "-", Index{step}},
          {"pass", "-", Index{pass}},
          {"x", "mm", x},
          {"depth", "mm", d.depth},
          {"dang_van", "MPa", d.dang_van.value},
          {"dang_van_index", "1", d.dang_van_index},
          {"dang_van_shear", "MPa", d.dang_van.shear},
          {"dang_van_hydrostatic", "MPa", d.dang_van.hydrostatic},
          {"path_radius", "MPa", d.dang_van.radius},
          {"shear_amplitude", "MPa", d.subsurface.shear_amplitude},
          {"max_hydrostatic", "MPa", d.subsurface.max_hydrostatic},
          {"fi_sub", "MPa", d.subsurface.value},
          {"fi_sub_index", "1", d.subsurface_index}};
}

std::vector<OutputTable> tables_of(const Scene& scene) {
  std::vector<OutputTable> tables{OutputTable::Solver};
  if (scene.roller) tables.insert(tables.end(), {OutputTable::Contact, OutputTable::Roller});
  if (scene.passes.count > 1) tables.insert(tables.end(), {OutputTable::Passes, OutputTable::ResidualDepth});
  if (scene.fatigue) tables.push_back(OutputTable::Fatigue);
  return tables;
}

Row empty_row(OutputTable table) {
  switch (table) {
    case OutputTable::Solver: return solver_row(Simulation::StepRecord{}, MonitorReport{}, 0.0);
    case OutputTable::Contact: return contact_row(0, 1, NodeContactRecord{});
    case OutputTable::Roller: return roller_row(0, 1, 0.0, Simulation::RollerRecord{});
    case OutputTable::Passes: return pass_row(0, PassRecord{});
    case OutputTable::ResidualDepth: return depth_row(0, 1, 0.0, DepthSample{});
    case OutputTable::Fatigue: return fatigue_row(0, 1, 0.0, FatigueAtDepth{});
  }
  return {};
}

std::string file_name(OutputTable table) { return std::string(enum_name(table)) + ".csv"; }

std::vector<TableColumns> output_tables() {
  std::vector<TableColumns> out;
  for (const auto& [table, name] : EnumNames<OutputTable>::names) out.push_back({file_name(table), empty_row(table)});
  return out;
}

std::string output_tables_markdown() {
  std::string out = "| file | columns [unit] |\n|---|---|\n";
  for (const TableColumns& t : output_tables()) {
    out += "| `" + t.file + "` |";
    for (std::size_t i = 0; i < t.columns.size(); ++i)
      out += std::string(i == 0 ? " " : ", ") + "`" + t.columns[i].name + "` [" + t.columns[i].unit + "]";
    out += " |\n";
  }
  return out;
}

}  // namespace roller
