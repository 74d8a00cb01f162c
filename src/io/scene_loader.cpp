#include "roller/io/scene_loader.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "roller/core/error.hpp"
#include "roller/io/toml_section.hpp"

namespace roller {

namespace {

// ---- overrides -------------------------------------------------------------------------------

void apply_override(toml::table& root, const SceneOverride& o) {
  std::vector<std::string> parts;
  std::stringstream ss(o.key);
  for (std::string p; std::getline(ss, p, '.');) parts.push_back(p);
  toml::table* t = &root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    toml::node* n = t->get(parts[i]);
    if (!n) {
      t->insert(parts[i], toml::table{});
      n = t->get(parts[i]);
    }
    t = n->as_table();
    if (!t)
      throw InputError(fmt::format("--set {}={}: '{}' is not a table in the scene", o.key, o.value,
                                   parts[i]));
  }
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + o.value);
  } catch (const toml::parse_error&) {
    parsed = toml::table{{"v", o.value}};  // bare word: take it as a string
  }
  t->insert_or_assign(parts.back(), *parsed.get("v"));
}

// ---- sections --------------------------------------------------------------------------------

Grading read_grading(TomlSection& s, const std::string& key) {
  Grading g;
  auto t = s.table(key);
  if (!t) return g;
  g.kind = Grading::Kind::Geometric;
  g.ratio = t->real_or("ratio", 1.0);
  g.focus = t->real_or("focus", 0.0);
  if (!(g.ratio >= 1.0)) t->fail("ratio", "expected ratio >= 1 (largest over smallest interval)");
  t->finish();
  return g;
}

void read_mesh(TomlSection& root, Scene& scene) {
  auto s = root.table("mesh");
  if (!s) root.fail("mesh", "a [mesh] table is required (element, length, height, nx, ny)");
  StripMeshSpec& m = scene.mesh;
  m.element = s->choice_or("element", {"Q4", "T3"}, "Q4") == "T3" ? ElementType::T3 : ElementType::Q4;
  m.length = s->real_or("length", m.length);
  m.height = s->real_or("height", m.height);
  m.nx = static_cast<int>(s->integer_or("nx", m.nx));
  m.ny = static_cast<int>(s->integer_or("ny", m.ny));
  m.refine = static_cast<int>(s->integer_or("refine", m.refine));
  m.grading_x = read_grading(*s, "grading_x");
  m.grading_y = read_grading(*s, "grading_y");
  if (auto v = s->real_array("x_lines")) m.x_lines = *v;
  if (auto v = s->real_array("y_lines")) m.y_lines = *v;
  const std::string diag = s->choice_or("diagonal", {"rising", "falling", "alternating"}, "rising");
  m.diagonal = diag == "falling" ? Diagonal::Falling
               : diag == "alternating" ? Diagonal::Alternating : Diagonal::Rising;
  if (auto f = s->string("q4_formulation")) {
    if (*f != "bbar" && *f != "standard") s->fail("q4_formulation", "expected \"bbar\" or \"standard\"");
    scene.element.q4 = *f == "bbar" ? Q4Formulation::BBar : Q4Formulation::Standard;
  } else {
    // Full-integration Q4 locks under isochoric plastic flow: B-bar is the plastic default.
    scene.element.q4 = scene.material.plastic ? Q4Formulation::BBar : Q4Formulation::Standard;
  }
  std::string why;
  if (!m.is_valid(&why)) s->fail_invalid(why, {{"element", "element"}});
  s->finish();
}

void read_material(TomlSection& root, Scene& scene) {
  auto s = root.table("material");
  if (!s) root.fail("material", "a [material] table is required (at least E and nu)");
  MaterialParams& p = scene.material;
  const auto e = s->real("E");
  if (!e) s->fail("E", "Young's modulus E [MPa] is required");
  p.youngs_modulus = *e;
  p.poisson_ratio = s->real_or("nu", p.poisson_ratio);
  p.density = s->real_or("density", 0.0);
  const auto yield = s->real("yield_stress");
  const auto et = s->real("tangent_modulus");
  const auto kappa = s->real("kappa");
  p.plastic = yield.has_value();
  if (!p.plastic && (et || kappa))
    s->fail(et ? "tangent_modulus" : "kappa", "hardening needs yield_stress (set it, or remove this key)");
  if (et && kappa) s->fail("kappa", "give either tangent_modulus or kappa = E_T/E, not both");
  if (p.plastic) {
    p.yield_stress = *yield;
    p.tangent_modulus = et ? *et : kappa.value_or(0.0) * p.youngs_modulus;
  }
  const std::string integ = s->choice_or("stress_integration", {"return_mapping", "substep"}, "return_mapping");
  p.integration = integ == "substep" ? StressIntegration::Substep : StressIntegration::ReturnMapping;
  p.n_substeps = static_cast<int>(s->integer_or("substeps", p.n_substeps));
  std::string why;
  if (!p.is_valid(&why))
    s->fail_invalid(why, {{"youngs_modulus", "E"},
                          {"poisson_ratio", "nu"},
                          {"tangent_modulus", kappa ? "kappa" : "tangent_modulus"},
                          {"n_substeps", "substeps"}});
  s->finish();
}

Ramp read_ramp(TomlSection& s, const std::string& key, int n_steps) {
  const toml::node* n = s.node(key);
  Ramp r;
  r.ramp_first = 1;
  r.ramp_last = 1;
  if (n->is_number()) {  // a constant: reached at once and held
    r.value = n->value<double>().value();
    return r;
  }
  auto t = s.table(key);
  if (!t) s.fail(key, "expected a number or { value = .., ramp = [first_step, last_step] }");
  const auto v = t->real("value");
  if (!v) t->fail("value", "the value reached at the end of the ramp is required");
  r.value = *v;
  if (auto steps = t->real_array("ramp")) {
    if (steps->size() != 2 || (*steps)[0] < 1 || (*steps)[1] < (*steps)[0] ||
        (*steps)[0] != static_cast<int>((*steps)[0]) || (*steps)[1] != static_cast<int>((*steps)[1]))
      t->fail("ramp", "expected [first_step, last_step] with 1 <= first_step <= last_step");
    r.ramp_first = static_cast<int>((*steps)[0]);
    r.ramp_last = static_cast<int>((*steps)[1]);
  } else {
    r.ramp_last = n_steps;  // default: linear over the whole run
  }
  t->finish();
  return r;
}

NodeSelector read_selector(TomlSection& s) {
  NodeSelector sel;
  const toml::node* n = s.node("nodes");
  if (!n) s.fail("nodes", "required: a node set name (\"top\", \"left\", ...) or thesis node numbers [5, 101]");
  if (auto name = n->value_exact<std::string>()) {
    sel.set_name = *name;
  } else if (n->is_table()) {
    auto t = s.table("nodes");
    const auto p = t->real_array("near");
    if (!p || p->size() != 2) t->fail("near", "expected { near = [x, y] }: the node nearest to that point");
    sel.near = Vec2((*p)[0], (*p)[1]);
    t->finish();
  } else if (const toml::array* arr = n->as_array()) {
    for (const auto& item : *arr) {
      auto i = item.value_exact<int64_t>();
      if (!i) s.fail("nodes", "expected an array of integer node numbers (1-based, thesis numbering)");
      sel.numbers.push_back(*i);
    }
    if (sel.numbers.empty()) s.fail("nodes", "the node list is empty");
  } else {
    s.fail("nodes", "expected a node set name, an array of node numbers, or { near = [x, y] }");
  }
  return sel;
}

void read_steps(TomlSection& root, Scene& scene) {
  auto s = root.table("steps");
  if (!s) return;
  StepControl& st = scene.steps;
  st.n_steps = static_cast<int>(s->integer_or("count", st.n_steps));
  st.dt = s->real_or("dt", st.dt);
  st.max_cuts = static_cast<int>(s->integer_or("max_cuts", st.max_cuts));
  if (st.n_steps < 1) s->fail("count", "expected at least 1 step");
  if (!(st.dt > 0.0)) s->fail("dt", "expected a time step > 0 [s]");
  if (st.max_cuts < 0 || st.max_cuts > 20) s->fail("max_cuts", "expected 0 <= max_cuts <= 20");
  s->finish();
}

void read_newton(TomlSection& root, Scene& scene) {
  auto s = root.table("newton");
  if (!s) return;
  NewtonOptions& n = scene.newton;
  n.max_iterations = static_cast<int>(s->integer_or("max_iterations", n.max_iterations));
  n.residual_tolerance = s->real_or("residual_tolerance", n.residual_tolerance);
  n.line_search = s->boolean("line_search").value_or(n.line_search);
  std::string why;
  if (!n.is_valid(&why)) s->fail_invalid(why, {});
  s->finish();
}

void read_linear_solver(TomlSection& root, Scene& scene) {
  auto s = root.table("linear_solver");
  if (!s) return;
  LinearSolverOptions& l = scene.newton.linear;
  l.out_of_core = s->boolean("out_of_core").value_or(l.out_of_core);
  l.ordering = s->choice_or("ordering", LinearSolverOptions::orderings(), l.ordering);
  l.directory = s->string("directory").value_or(l.directory);
  std::string why;
  if (!l.is_valid(&why)) s->fail_invalid(why, {});
  s->finish();
}

void read_output(TomlSection& root, Scene& scene) {
  auto s = root.table("output");
  if (!s) return;
  scene.output.every = static_cast<int>(s->integer_or("every", scene.output.every));
  scene.output.vtu = s->boolean("vtu").value_or(scene.output.vtu);
  scene.output.monitor = s->boolean("monitor").value_or(scene.output.monitor);
  scene.output.checkpoint_every =
      static_cast<int>(s->integer_or("checkpoint_every", scene.output.checkpoint_every));
  if (scene.output.every < 1) s->fail("every", "expected an integer >= 1");
  if (scene.output.checkpoint_every < 0)
    s->fail("checkpoint_every", "expected an integer >= 0 (0: no checkpoint)");
  if (auto steps = s->real_array("save_states")) {
    for (Real v : *steps) {
      if (v != std::floor(v) || v < 1 || v > scene.steps.n_steps)
        s->fail("save_states", fmt::format("expected step numbers in 1..{} (steps.count)", scene.steps.n_steps));
      scene.output.save_states.push_back(static_cast<int>(v));
    }
  }
  s->finish();
}

void read_dynamics(TomlSection& root, Scene& scene) {
  auto s = root.table("dynamics");
  if (!s) return;
  DynamicsOptions& d = scene.dynamics;
  d.strip_inertia = s->boolean("strip_inertia").value_or(d.strip_inertia);
  d.lumped_mass = s->choice_or("mass", {"consistent", "lumped"}, d.lumped_mass ? "lumped" : "consistent") == "lumped";
  if (d.strip_inertia && !(scene.material.density > 0.0))
    s->fail("strip_inertia", fmt::format("strip inertia needs material.density > 0 [t/mm^3] (it is {}); "
                                         "steel: 7.8e-9",
                                         scene.material.density));
  s->finish();
}

void read_restart(TomlSection& root, Scene& scene) {
  auto s = root.table("restart");
  if (!s) return;
  const auto from = s->string("from");
  if (!from || from->empty()) s->fail("from", "expected the path of a state file (state_final.cbor of a run)");
  std::filesystem::path p(*from);
  // Relative to the scene file, so that a scene and its predecessor's output travel together.
  if (p.is_relative() && !scene.file.empty()) p = scene.file.parent_path() / p;
  scene.initial_state = p;
  s->finish();
}

void read_conditions(TomlSection& root, Scene& scene) {
  const int n = scene.steps.n_steps;
  for (auto& s : root.table_array("displacement")) {
    DisplacementBC bc;
    bc.nodes = read_selector(s);
    if (s.has("x")) bc.x = read_ramp(s, "x", n);
    if (s.has("y")) bc.y = read_ramp(s, "y", n);
    s.node("x");
    s.node("y");
    if (!bc.x && !bc.y) s.fail("x", "a [[displacement]] block needs x and/or y");
    s.finish();
    scene.displacements.push_back(bc);
  }
  for (auto& s : root.table_array("load")) {
    NodalLoad load;
    load.nodes = read_selector(s);
    if (s.has("fx")) load.fx = read_ramp(s, "fx", n);
    if (s.has("fy")) load.fy = read_ramp(s, "fy", n);
    s.node("fx");
    s.node("fy");
    if (!load.fx && !load.fy) s.fail("fx", "a [[load]] block needs fx and/or fy");
    s.finish();
    scene.loads.push_back(load);
  }
}

void read_roller(TomlSection& root, Scene& scene) {
  auto s = root.table("roller");
  if (!s) return;
  RollerSpec r;
  r.radius = s->real_or("radius", r.radius);
  if (auto c = s->real_array("centre")) {
    if (c->size() != 2) s->fail("centre", "expected [x, y] of the roller centre at the start [mm]");
    r.start_centre = Vec2((*c)[0], (*c)[1]);
  }
  r.start_angle = s->real_or("angle", 0.0);
  if (auto q = s->table("suspension")) {
    SuspensionSpec sp;
    sp.mass = q->real_or("mass", 0.0);
    sp.damping = q->real_or("damping", 0.0);
    sp.stiffness = q->real_or("stiffness", 0.0);
    q->finish();
    r.suspension = sp;
  }
  for (auto& seg : s->table_array("path")) {
    PathSegment p;
    const auto steps = seg.real_array("steps");
    if (!steps || steps->size() != 2 || (*steps)[0] != std::floor((*steps)[0]) ||
        (*steps)[1] != std::floor((*steps)[1]))
      seg.fail("steps", "expected [first_step, last_step] (integers, 1-based, inclusive)");
    p.first_step = static_cast<int>((*steps)[0]);
    p.last_step = static_cast<int>((*steps)[1]);
    p.dx = seg.real_or("dx", 0.0);
    p.dy = seg.real_or("dy", 0.0);
    if (const toml::node* slip = seg.node("slip")) {
      if (slip->is_number()) {
        p.slip_start = p.slip_end = slip->value<double>().value();
      } else if (auto pair = seg.real_array("slip"); pair && pair->size() == 2) {
        p.slip_start = (*pair)[0];
        p.slip_end = (*pair)[1];
      } else {
        seg.fail("slip", "expected a slip ratio s = (v - omega R)/v, or [s_start, s_end]");
      }
    }
    if (auto h = seg.table("harmonic")) {
      p.harmonic_amplitude = h->real_or("amplitude", 0.0);
      const auto wl = h->real("wavelength");
      if (!wl || !(*wl > 0.0)) h->fail("wavelength", "expected the wavelength L_p > 0 [mm]");
      p.harmonic_wavelength = *wl;
      h->finish();
    }
    seg.finish();
    r.path.push_back(p);
  }
  std::string why;
  if (!r.is_valid(&why)) s->fail_invalid(why, {});
  s->finish();
  scene.roller = r;
}

void read_contact(TomlSection& root, Scene& scene) {
  auto s = root.table("contact");
  if (!s) return;
  if (!scene.roller) s->fail("backend", "a [contact] table needs a [roller]");
  ContactOptions& c = scene.contact;
  c.backend = s->enum_or("backend", c.backend);
  c.friction = s->real_or("friction", c.friction);
  c.candidates = s->string("candidates").value_or(c.candidates);
  c.predictor = s->enum_or("predictor", c.predictor);
  if (auto p = s->table("penalty")) {
    c.penalty.factor = p->real_or("factor", c.penalty.factor);
    c.penalty.tangential_factor = p->real_or("tangential_factor", c.penalty.tangential_factor);
    p->finish();
  }
  if (auto p = s->table("ipopt")) {
    IpoptOptions& o = c.ipopt;
    o.formulation = p->enum_or("formulation", o.formulation);
    o.tol = p->real_or("tol", o.tol);
    o.max_iter = static_cast<int>(p->integer_or("max_iter", o.max_iter));
    o.mu_strategy = p->enum_or("mu_strategy", o.mu_strategy);
    o.print_level = static_cast<int>(p->integer_or("print_level", o.print_level));
    o.warm_start = p->boolean("warm_start").value_or(o.warm_start);
    o.friction = p->enum_or("friction", o.friction);
    o.regularization = p->real_or("regularization", o.regularization);
    o.fixed_point = p->enum_or("fixed_point", o.fixed_point);
    o.fixed_point_tol = p->real_or("fixed_point_tol", o.fixed_point_tol);
    o.fixed_point_max = static_cast<int>(p->integer_or("fixed_point_max", o.fixed_point_max));
    if (auto raw = p->table("options")) {
      // Any Ipopt option, passed through (checked by Ipopt when the backend is built).
      for (const std::string& key : raw->keys()) {
        const toml::node* v = raw->node(key);
        RawIpoptOption r{key, RawIpoptOption::Kind::String, ""};
        if (v->is_integer()) {
          r.kind = RawIpoptOption::Kind::Integer;
          r.text = std::to_string(v->value<int64_t>().value());
        } else if (v->is_floating_point()) {
          r.kind = RawIpoptOption::Kind::Number;
          r.text = fmt::format("{:.17g}", v->value<double>().value());
        } else if (v->is_boolean()) {
          r.text = v->value<bool>().value() ? "yes" : "no";
        } else if (v->is_string()) {
          r.text = v->value<std::string>().value();
        } else {
          raw->fail(key, "expected a string, integer, number or boolean (an Ipopt option value)");
        }
        o.raw.push_back(r);
      }
      raw->finish();
    }
    p->finish();
  }
  std::string why;
  if (!c.is_valid(&why)) s->fail_invalid(why, {});
  s->finish();
}

Scene scene_from_table(const toml::table& table, const std::filesystem::path& file) {
  Scene scene;
  scene.file = file;
  TomlSection root(table, "", file);
  root.allow({"name", "title", "kinematics", "mesh", "material", "steps", "newton", "linear_solver", "output",
              "displacement", "load", "roller", "contact", "dynamics", "restart"});
  root.finish();
  scene.name = root.string("name").value_or(file.stem().string());
  scene.title = root.string("title").value_or("");
  const std::string kin = root.choice_or("kinematics", {"small", "finite"}, "finite");
  scene.element.kinematics = kin == "small" ? Kinematics::Small : Kinematics::Finite;
  read_material(root, scene);  // before the mesh: the Q4 default depends on plasticity
  read_mesh(root, scene);
  read_steps(root, scene);
  read_newton(root, scene);
  read_linear_solver(root, scene);
  read_output(root, scene);
  read_dynamics(root, scene);
  read_restart(root, scene);
  read_conditions(root, scene);
  read_roller(root, scene);
  read_contact(root, scene);
  root.finish();
  return scene;
}

}  // namespace

SceneOverride parse_override(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw InputError(fmt::format("--set '{}': expected key=value, e.g. --set material.E=2e5", text));
  return {text.substr(0, eq), text.substr(eq + 1)};
}

Scene parse_scene(const std::string& text, const std::filesystem::path& file_name,
                  const std::vector<SceneOverride>& overrides) {
  toml::table table;
  try {
    table = toml::parse(text, file_name.string());
  } catch (const toml::parse_error& e) {
    throw InputError(fmt::format("{}:{}:{}: TOML syntax error: {}", file_name.string(),
                                 e.source().begin.line, e.source().begin.column, e.description()));
  }
  for (const auto& o : overrides) apply_override(table, o);
  return scene_from_table(table, file_name);
}

Scene load_scene(const std::filesystem::path& file, const std::vector<SceneOverride>& overrides) {
  std::ifstream in(file);
  if (!in) throw InputError(fmt::format("{}: cannot open the scene file (check the path)", file.string()));
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_scene(buffer.str(), file, overrides);
}

std::vector<Index> resolve_nodes(const NodeSelector& selector, const Mesh& mesh,
                                 const std::string& context) {
  if (selector.near) {
    Index best = 0;
    for (Index a = 1; a < mesh.n_nodes(); ++a)
      if ((mesh.nodes[a] - *selector.near).norm() < (mesh.nodes[best] - *selector.near).norm()) best = a;
    return {best};
  }
  if (selector.numbers.empty()) {
    // "top+right": the union of named sets, in order, each node once.
    std::vector<Index> out;
    std::stringstream names(selector.set_name);
    for (std::string name; std::getline(names, name, '+');) {
      try {
        for (Index a : mesh.node_set(name))
          if (std::find(out.begin(), out.end(), a) == out.end()) out.push_back(a);
      } catch (const InputError& e) {
        throw InputError(fmt::format("{}: {}", context, e.what()));
      }
    }
    return out;
  }
  std::vector<Index> out;
  for (Index number : selector.numbers) {
    if (number < 1 || number > mesh.n_nodes())
      throw InputError(fmt::format("{}: node {} does not exist: the mesh has nodes 1..{} "
                                   "(thesis numbering: column by column from the left, top to bottom)",
                                   context, number, mesh.n_nodes()));
    out.push_back(number - 1);
  }
  return out;
}

std::string NodeSelector::describe() const {
  if (near) return fmt::format("the node nearest to ({}, {})", near->x(), near->y());
  if (numbers.empty()) return fmt::format("set '{}'", set_name);
  return fmt::format("nodes [{}]", fmt::join(numbers, ", "));
}

Real Ramp::at_step(int step) const {
  if (step >= ramp_last) return value;
  if (step < ramp_first) return 0.0;
  return value * static_cast<Real>(step - ramp_first + 1) / static_cast<Real>(ramp_last - ramp_first + 1);
}

const std::vector<std::string>& LinearSolverOptions::orderings() {
  static const std::vector<std::string> names{"auto", "amd", "metis"};
  return names;
}

bool LinearSolverOptions::is_valid(std::string* why) const {
  auto bad = [why](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  const auto& known = orderings();
  if (std::find(known.begin(), known.end(), ordering) == known.end())
    return bad(fmt::format("linear_solver.ordering = \"{}\": expected one of \"{}\"", ordering,
                           fmt::join(known, "\", \"")));
  if (!directory.empty()) {
    std::error_code ec;
    if (!std::filesystem::is_directory(directory, ec))
      return bad(fmt::format("linear_solver.directory = \"{}\": expected an existing directory (for the "
                             "out-of-core factor files)", directory));
    if (directory.size() > 250)
      return bad(fmt::format("linear_solver.directory = \"{}\": MUMPS takes at most 250 characters", directory));
  }
  return true;
}

bool NewtonOptions::is_valid(std::string* why) const {
  auto bad = [why](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  if (max_iterations < 1) return bad(fmt::format("newton.max_iterations = {}: must be >= 1", max_iterations));
  if (!(residual_tolerance > 0.0 && residual_tolerance < 1.0))
    return bad(fmt::format("newton.residual_tolerance = {}: must be in (0, 1)", residual_tolerance));
  return true;
}

}  // namespace roller
