// scene_to_toml: the resolved scene (every default filled in) in the scene-file format.
#include <sstream>

#include <toml++/toml.h>

#include "roller/io/scene_loader.hpp"

namespace roller {

namespace {

toml::array to_array(const std::vector<Real>& v) {
  toml::array a;
  for (Real x : v) a.push_back(x);
  return a;
}

toml::table ramp_table(const Ramp& r) {
  return toml::table{{"value", r.value},
                     {"ramp", toml::array{static_cast<int64_t>(r.ramp_first), static_cast<int64_t>(r.ramp_last)}}};
}

void put_selector(toml::table& t, const NodeSelector& s) {
  if (s.near) {
    t.insert("nodes", toml::table{{"near", toml::array{s.near->x(), s.near->y()}}});
  } else if (s.numbers.empty()) {
    t.insert("nodes", s.set_name);
  } else {
    toml::array a;
    for (Index n : s.numbers) a.push_back(static_cast<int64_t>(n));
    t.insert("nodes", a);
  }
}

toml::table grading_table(const Grading& g) { return toml::table{{"ratio", g.ratio}, {"focus", g.focus}}; }

const char* diagonal_name(Diagonal d) {
  return d == Diagonal::Falling ? "falling" : d == Diagonal::Alternating ? "alternating" : "rising";
}

}  // namespace

std::string scene_to_toml(const Scene& scene) {
  toml::table root;
  root.insert("name", scene.name);
  if (!scene.title.empty()) root.insert("title", scene.title);
  root.insert("kinematics", to_string(scene.element.kinematics));

  const StripMeshSpec& m = scene.mesh;
  toml::table mesh{{"element", m.element == ElementType::T3 ? "T3" : "Q4"},
                   {"length", m.length},
                   {"height", m.height},
                   {"nx", static_cast<int64_t>(m.nx)},
                   {"ny", static_cast<int64_t>(m.ny)},
                   {"refine", static_cast<int64_t>(m.refine)},
                   {"diagonal", diagonal_name(m.diagonal)},
                   {"q4_formulation", to_string(scene.element.q4)}};
  if (m.grading_x.kind == Grading::Kind::Geometric) mesh.insert("grading_x", grading_table(m.grading_x));
  if (m.grading_y.kind == Grading::Kind::Geometric) mesh.insert("grading_y", grading_table(m.grading_y));
  if (!m.x_lines.empty()) mesh.insert("x_lines", to_array(m.x_lines));
  if (!m.y_lines.empty()) mesh.insert("y_lines", to_array(m.y_lines));
  root.insert("mesh", mesh);

  const MaterialParams& p = scene.material;
  toml::table material{{"E", p.youngs_modulus}, {"nu", p.poisson_ratio}, {"density", p.density}};
  if (p.plastic) {
    material.insert("yield_stress", p.yield_stress);
    material.insert("tangent_modulus", p.tangent_modulus);
    material.insert("stress_integration",
                    p.integration == StressIntegration::Substep ? "substep" : "return_mapping");
    material.insert("substeps", static_cast<int64_t>(p.n_substeps));
  }
  root.insert("material", material);

  root.insert("steps", toml::table{{"count", static_cast<int64_t>(scene.steps.n_steps)},
                                   {"dt", scene.steps.dt},
                                   {"max_cuts", static_cast<int64_t>(scene.steps.max_cuts)}});
  root.insert("newton", toml::table{{"max_iterations", static_cast<int64_t>(scene.newton.max_iterations)},
                                    {"residual_tolerance", scene.newton.residual_tolerance},
                                    {"line_search", scene.newton.line_search}});
  root.insert("linear_solver", toml::table{{"out_of_core", scene.newton.linear.out_of_core},
                                           {"ordering", scene.newton.linear.ordering},
                                           {"directory", scene.newton.linear.directory}});
  toml::array save_states;
  for (int step : scene.output.save_states) save_states.push_back(static_cast<int64_t>(step));
  root.insert("output", toml::table{{"every", static_cast<int64_t>(scene.output.every)},
                                    {"vtu", scene.output.vtu},
                                    {"monitor", scene.output.monitor},
                                    {"checkpoint_every", static_cast<int64_t>(scene.output.checkpoint_every)},
                                    {"save_states", save_states}});
  root.insert("dynamics", toml::table{{"strip_inertia", scene.dynamics.strip_inertia},
                                      {"mass", scene.dynamics.lumped_mass ? "lumped" : "consistent"}});
  if (!scene.initial_state.empty()) root.insert("restart", toml::table{{"from", scene.initial_state.string()}});

  toml::array displacements;
  for (const auto& bc : scene.displacements) {
    toml::table t;
    put_selector(t, bc.nodes);
    if (bc.x) t.insert("x", ramp_table(*bc.x));
    if (bc.y) t.insert("y", ramp_table(*bc.y));
    displacements.push_back(t);
  }
  if (!displacements.empty()) root.insert("displacement", displacements);
  toml::array loads;
  for (const auto& l : scene.loads) {
    toml::table t;
    put_selector(t, l.nodes);
    if (l.fx) t.insert("fx", ramp_table(*l.fx));
    if (l.fy) t.insert("fy", ramp_table(*l.fy));
    loads.push_back(t);
  }
  if (!loads.empty()) root.insert("load", loads);

  if (scene.roller) {
    const RollerSpec& r = *scene.roller;
    toml::table roller{{"radius", r.radius}, {"angle", r.start_angle}};
    if (r.start_centre) roller.insert("centre", toml::array{r.start_centre->x(), r.start_centre->y()});
    toml::array path;
    if (r.suspension)
      roller.insert("suspension", toml::table{{"mass", r.suspension->mass},
                                              {"damping", r.suspension->damping},
                                              {"stiffness", r.suspension->stiffness}});
    for (const PathSegment& seg : r.path) {
      toml::table t{{"steps", toml::array{static_cast<int64_t>(seg.first_step), static_cast<int64_t>(seg.last_step)}},
                    {"dx", seg.dx},
                    {"dy", seg.dy},
                    {"slip", toml::array{seg.slip_start, seg.slip_end}}};
      if (seg.harmonic_wavelength > 0.0)
        t.insert("harmonic",
                 toml::table{{"amplitude", seg.harmonic_amplitude}, {"wavelength", seg.harmonic_wavelength}});
      path.push_back(t);
    }
    if (!path.empty()) roller.insert("path", path);
    root.insert("roller", roller);
    const ContactOptions& c = scene.contact;
    const IpoptOptions& o = c.ipopt;
    toml::table raw_options;
    for (const RawIpoptOption& option : o.raw) {
      if (option.kind == RawIpoptOption::Kind::Integer) raw_options.insert(option.name, std::stoll(option.text));
      else if (option.kind == RawIpoptOption::Kind::Number) raw_options.insert(option.name, std::stod(option.text));
      else raw_options.insert(option.name, option.text);
    }
    root.insert("contact",
                toml::table{{"backend", enum_name(c.backend)},
                            {"friction", c.friction},
                            {"candidates", c.candidates},
                            {"predictor", enum_name(c.predictor)},
                            {"penalty", toml::table{{"factor", c.penalty.factor},
                                                    {"tangential_factor", c.penalty.tangential_factor}}},
                            {"ipopt", toml::table{{"formulation", enum_name(o.formulation)},
                                                  {"tol", o.tol},
                                                  {"max_iter", static_cast<int64_t>(o.max_iter)},
                                                  {"mu_strategy", enum_name(o.mu_strategy)},
                                                  {"print_level", static_cast<int64_t>(o.print_level)},
                                                  {"warm_start", o.warm_start},
                                                  {"friction", enum_name(o.friction)},
                                                  {"regularization", o.regularization},
                                                  {"fixed_point", enum_name(o.fixed_point)},
                                                  {"fixed_point_tol", o.fixed_point_tol},
                                                  {"fixed_point_max", static_cast<int64_t>(o.fixed_point_max)},
                                                  {"options", raw_options}}}});
  }

  std::ostringstream out;
  out << "# Resolved scene: every value roller used, defaults included.\n" << root << "\n";
  return out.str();
}

}  // namespace roller
