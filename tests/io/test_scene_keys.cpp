// The scene-key declarations (io/scene_keys.hpp): each key declared once in a declared table,
// documented in docs/scenes.md, and written by scene_to_toml so that it reads back the same.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "../support/scene_errors.hpp"
#include "../support/temp_files.hpp"
#include "roller/core/error.hpp"
#include "roller/io/scene_keys.hpp"
#include "roller/io/scene_loader.hpp"

using namespace roller;

namespace {

std::string read_file(const std::filesystem::path& p) {
  REQUIRE(std::filesystem::is_regular_file(p));
  return test::read_text(p);
}

using test::error_of;

// Every key set away from its default (kappa aside: it is written as tangent_modulus).
std::string all_keys_scene() {
  return R"(
name = "all"
title = "every key"
kinematics = "small"
[material]
E = 2.0e5
nu = 0.25
density = 7.8e-9
yield_stress = 250.0
tangent_modulus = 1000.0
stress_integration = "substep"
substeps = 5
yield_profile = [[0.0, 400.0], [2.0, 250.0]]
[[layer]]
thickness = 1.0
E = 2.2e5
nu = 0.28
density = 7.9e-9
yield_stress = 500.0
tangent_modulus = 1500.0
stress_integration = "return_mapping"
substeps = 4
[mesh]
element = "T3"
follow_layers = true
length = 50.0
height = 10.0
nx = 6
ny = 3
refine = 2
grading_x = { ratio = 4.0, focus = 25.0 }
grading_y = { ratio = 2.0, focus = 10.0 }
x_lines = [0.0, 20.0, 50.0]
y_lines = [0.0, 4.0, 7.0, 10.0]
diagonal = "alternating"
q4_formulation = "standard"
[passes]
count = 2
direction = "alternate"
[fatigue]
dang_van_a = 0.3
dang_van_limit = 300.0
shear_fatigue_limit = 250.0
critical_shear_strain = 11.0
[steps]
count = 5
dt = 1e-4
max_cuts = 3
[newton]
max_iterations = 12
residual_tolerance = 1e-9
line_search = false
[linear_solver]
out_of_core = true
ordering = "amd"
directory = ")" +
         std::filesystem::temp_directory_path().string() + R"("
[output]
every = 2
vtu = false
monitor = false
checkpoint_every = 0
save_states = [2, 4]
[dynamics]
strip_inertia = true
mass = "lumped"
[restart]
from = "/nonexistent/state_final.cbor"
[[displacement]]
nodes = "bottom"
y = 0.0
[[displacement]]
nodes = { near = [0.0, 10.0] }
x = { value = 0.1, ramp = [2, 3] }
y = -0.05
[[load]]
nodes = [1, 2]
fx = 1.0
fy = { value = -2.0, ramp = [1, 5] }
[roller]
radius = 150.0
centre = [25.0, 160.0]
angle = 0.1
E = 7.0e4
nu = 0.33
inner_radius = 50.0
[roller.suspension]
mass = 1e-3
damping = 2e-3
stiffness = 1e5
[[roller.path]]
steps = [1, 2]
dy = -0.5
[[roller.path]]
steps = [3, 5]
dx = 10.0
dy = 0.1
slip = [0.01, 0.02]
harmonic = { amplitude = 0.01, wavelength = 5.0 }
friction = 0.1
[contact]
backend = "penalty"
friction = 0.2
candidates = "top+right"
predictor = "arc"
[contact.penalty]
factor = 500.0
tangential_factor = 0.5
[contact.ipopt]
formulation = "full"
tol = 1e-8
max_iter = 100
mu_strategy = "monotone"
print_level = 1
warm_start = false
friction = "regularized"
regularization = 1e-7
fixed_point = "single"
fixed_point_tol = 1e-5
fixed_point_max = 10
[contact.ipopt.options]
mumps_pivot_order = 0
bound_push = 0.01
print_timing_statistics = true
)";
}

// docs/scenes.md in blocks: a header line (a heading, or a paragraph opening with `[table]`)
// and the text up to the next header.
struct DocBlock {
  std::string header;
  std::string text;  // header and body
};

std::vector<DocBlock> doc_blocks(const std::string& doc) {
  std::vector<DocBlock> blocks;
  std::istringstream in(doc);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("#", 0) == 0 || line.rfind("`[", 0) == 0) blocks.push_back({line, ""});
    if (!blocks.empty()) blocks.back().text += line + "\n";
  }
  return blocks;
}

// How docs/scenes.md names a table: "## Top level", "`[mesh]`", "`[[roller.path]]`".
std::string doc_marker(const SceneTable& t) {
  if (t.path.empty()) return "## Top level";
  return t.array ? "`[[" + t.path + "]]`" : "`[" + t.path + "]`";
}

}  // namespace

TEST_CASE("scene keys: each declared once, in a declared table, its parents declared first", "[io][scene][keys]") {
  std::set<std::string> tables;
  for (const SceneTable& t : scene_tables()) {
    INFO("table '" << t.path << "'");
    CHECK(tables.insert(t.path).second);
    if (!t.path.empty()) CHECK(tables.count(t.parent()) == 1);
  }
  std::set<std::string> keys;
  for (const SceneKey& k : scene_keys()) {
    INFO(k.dotted());
    CHECK(keys.insert(k.dotted()).second);
    CHECK(tables.count(k.table) == 1);
    CHECK(tables.count(k.table.empty() ? k.name : k.table + "." + k.name) == 0);  // not also a table
    CHECK_FALSE(k.type.empty());
    CHECK_FALSE(k.default_text.empty());
    CHECK_FALSE(k.doc.empty());
    CHECK(k.read);
    CHECK(k.write);
  }
  CHECK(keys.count("contact.ipopt.tol") == 1);
  CHECK(keys.count("roller.path[].dx") == 1);
}

TEST_CASE("docs/scenes.md mentions every declared key under its table", "[io][scene][keys][docs]") {
  const std::string doc = read_file(std::filesystem::path(ROLLER_SOURCE_DIR) / "docs" / "scenes.md");
  CHECK_THAT(doc, Catch::Contains("roller scene-keys"));
  const std::vector<DocBlock> blocks = doc_blocks(doc);
  for (const SceneTable& t : scene_tables()) {
    INFO("table " << doc_marker(t));
    CHECK_THAT(doc, Catch::Contains(doc_marker(t)));
  }
  for (const SceneKey& k : scene_keys()) {
    const std::string marker = doc_marker(scene_table(k.table));
    bool found = false;
    for (const DocBlock& b : blocks)
      found =
          found || (b.header.find(marker) != std::string::npos && b.text.find("`" + k.name + "`") != std::string::npos);
    INFO(k.dotted() << ": `" << k.name << "` is not documented under " << marker);
    CHECK(found);
  }
}

TEST_CASE("every shipped scene round-trips through the resolved scene", "[io][scene][keys]") {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(ROLLER_SOURCE_DIR) / "problems"))
    if (entry.path().extension() == ".toml") files.push_back(entry.path());
  REQUIRE(files.size() >= 10);
  for (const auto& file : files) {
    INFO(file.string());
    const std::string first = scene_to_toml(load_scene(file));
    const std::string second = scene_to_toml(parse_scene(first, "resolved.toml"));
    CHECK(second == first);
  }
}

TEST_CASE("a scene that sets every key round-trips, and the resolved scene holds every key", "[io][scene][keys]") {
  const Scene scene = parse_scene(all_keys_scene(), "all.toml");
  CHECK(scene.mesh.element == ElementType::T3);
  CHECK(scene.dynamics.lumped_mass);
  CHECK(scene.roller->path.at(1).harmonic_wavelength == 5.0);
  CHECK(scene.contact.ipopt.raw.size() == 3);
  const std::string first = scene_to_toml(scene);
  const std::string second = scene_to_toml(parse_scene(first, "resolved.toml"));
  CHECK(second == first);
  const toml::table written = toml::parse(first);
  for (const SceneKey& k : scene_keys()) {
    if (k.dotted() == "material.kappa" || k.dotted() == "layer[].kappa") continue;  // written as tangent_modulus
    // The hardening laws' own keys, in [material] and in [[layer]]: only with their law (substep
    // here): the hardening scenes below.
    const std::string field = k.dotted().substr(k.dotted().find('.') + 1);
    if ((k.table == "material" || k.table == "layer") &&
        (field == "kinematic_fraction" || field.rfind("chaboche_", 0) == 0 || field.rfind("voce_", 0) == 0))
      continue;
    if (k.dotted() == "roller.path[].p0" || k.dotted() == "roller.path[].p0_over_k")
      continue;  // written as the fy they give (tests/io/test_scene_user_terms.cpp)
    if (k.dotted() == "roller.path[].fy" || k.dotted() == "roller.path[].fx" || k.dotted() == "roller.path[].q_over_p")
      continue;  // not with a suspension: checked below
    // The key in the written table (in the last block of an array of tables).
    const toml::node* node = &written;
    std::stringstream path(k.table);
    for (std::string part; std::getline(path, part, '.');) {
      node = node->as_table()->get(part);
      REQUIRE(node);
      if (const toml::array* blocks = node->as_array()) node = blocks->get(blocks->size() - 1);
    }
    INFO(k.dotted() << " is not in the resolved scene:\n" << first);
    CHECK(node->as_table()->contains(k.name));
  }
  // A force-controlled segment (exclusive with the suspension above).
  const Scene loaded = parse_scene(
      "[mesh]\n[material]\nE = 2.1e5\n[steps]\ncount = 2\n[roller]\n[[roller.path]]\nsteps = [1, 2]\nfy = 250.0\nfx = "
      "-12.5\n",
      "fy.toml");
  const std::string resolved = scene_to_toml(loaded);
  CHECK_THAT(resolved, Catch::Contains("fy = 250") && Catch::Contains("fx = -12.5"));
  CHECK(scene_to_toml(parse_scene(resolved, "resolved.toml")) == resolved);
  // The traction ratio instead of fx, kept as the ratio.
  const Scene ratio = parse_scene(
      "[mesh]\n[material]\nE = 2.1e5\n[steps]\ncount = 2\n[roller]\n[[roller.path]]\nsteps = [1, 2]\nfy = 250.0\ndx = "
      "1.0\nq_over_p = 0.05\n",
      "q.toml");
  const std::string resolved_ratio = scene_to_toml(ratio);
  CHECK_THAT(resolved_ratio, Catch::Contains("q_over_p = 0.05") && !Catch::Contains("fx ="));
  CHECK(scene_to_toml(parse_scene(resolved_ratio, "resolved.toml")) == resolved_ratio);
  // One horizontal force a segment: fx and q_over_p in one block, or as two overrides, are refused;
  // an override of one replaces the other in the file's block.
  CHECK_THROWS_WITH(parse_scene("[mesh]\n[material]\nE = 2.1e5\n[steps]\ncount = 2\n[roller]\n[[roller.path]]\n"
                                "steps = [1, 2]\nfy = 250.0\ndx = 1.0\nfx = -5.0\nq_over_p = 0.05\n",
                                "both.toml"),
                    Catch::Contains("q_over_p") && Catch::Contains("not both"));
  CHECK_THROWS_WITH(
      parse_scene(resolved_ratio, "resolved.toml", {{"roller.path[0].fx", "-5.0"}, {"roller.path[0].q_over_p", "0.1"}}),
      Catch::Contains("fx and q_over_p another"));
  const Scene replaced = parse_scene(resolved_ratio, "resolved.toml", {{"roller.path[0].fx", "-5.0"}});
  CHECK(replaced.roller->path[0].fx == -5.0);
  CHECK_FALSE(replaced.roller->path[0].q_over_p);
}

TEST_CASE("scene keys check their range before narrowing, and suggest declared keys", "[io][scene][keys][errors]") {
  using Catch::Contains;
  const std::string base = "[mesh]\n[material]\nE = 2.1e5\n[roller]\n";
  CHECK_THAT(error_of(base, {{"mesh.nx", "4294967297"}}), Contains("mesh.nx = 4294967297") && Contains("2147483647"));
  CHECK_THAT(error_of(base, {{"steps.max_cuts", "-4294967295"}}),
             Contains("steps.max_cuts = -4294967295") && Contains("0 <= max_cuts <= 20"));
  CHECK_THAT(error_of(base, {{"contact.ipopt.print_level", "13"}}),
             Contains("contact.ipopt.print_level = 13") && Contains("0 <= print_level <= 12"));
  CHECK_THAT(error_of(base, {{"mesh.diagonal", "\"up\""}}),
             Contains("mesh.diagonal = 'up'") && Contains("\"rising\", \"falling\", \"alternating\""));
  CHECK_THAT(error_of(base, {{"dynamics.mass", "\"diagonal\""}}), Contains("\"consistent\", \"lumped\""));
  CHECK_THAT(error_of(base, {{"newton.residual_tolerance", "1.5"}}),
             Contains("newton.residual_tolerance = 1.5: must satisfy 0 < residual_tolerance < 1"));
  // A declared key that this file does not set is still suggested.
  CHECK_THAT(error_of(base + "[newton]\nline_serch = false\n"), Contains("did you mean 'newton.line_search'"));
}

TEST_CASE("hardening laws' keys round-trip and appear in the resolved scene with their law", "[io][scene][keys]") {
  const std::string base = "[mesh]\n[steps]\ncount = 1\n[material]\nE = 2.1e5\nyield_stress = 250.0\n";
  SECTION("chaboche with Voce") {
    const Scene scene =
        parse_scene(base +
                        "hardening = \"chaboche\"\nchaboche_C = [1e5, 2e4]\nchaboche_gamma = [1000.0, 0.0]\n"
                        "voce_Q = 50.0\nvoce_b = 20.0\n",
                    "chaboche.toml");
    CHECK(scene.material.n_back_stresses() == 2);
    CHECK(scene.material.back_stress_law(0).recovery == 1000.0);
    const std::string first = scene_to_toml(scene);
    CHECK(scene_to_toml(parse_scene(first, "resolved.toml")) == first);
    const toml::table written = toml::parse(first);
    for (const char* key : {"hardening", "chaboche_C", "chaboche_gamma", "voce_Q", "voce_b"}) {
      INFO(key);
      CHECK(written["material"].as_table()->contains(key));
    }
  }
  SECTION("mixed") {
    const Scene scene = parse_scene(
        base + "tangent_modulus = 2000.0\nhardening = \"mixed\"\nkinematic_fraction = 0.25\n", "mixed.toml");
    CHECK(scene.material.isotropic_modulus() == Approx(0.75 * scene.material.plastic_modulus()));
    const std::string first = scene_to_toml(scene);
    CHECK(scene_to_toml(parse_scene(first, "resolved.toml")) == first);
    CHECK(toml::parse(first)["material"].as_table()->contains("kinematic_fraction"));
  }
  SECTION("errors name the key") {
    CHECK_THROWS_WITH(parse_scene(base + "chaboche_C = [1e5]\nchaboche_gamma = [10.0]\n", "e.toml"),
                      Catch::Contains("material.chaboche_C") && Catch::Contains("hardening = \"chaboche\""));
    CHECK_THROWS_WITH(
        parse_scene(base + "hardening = \"chaboche\"\nchaboche_C = [1e5, 1e4]\nchaboche_gamma = [10.0]\n", "e.toml"),
        Catch::Contains("material.chaboche_gamma") && Catch::Contains("one recovery per modulus"));
    CHECK_THROWS_WITH(parse_scene(base + "hardening = \"chaboche\"\n", "e.toml"),
                      Catch::Contains("1 to 10 back-stresses"));
    CHECK_THROWS_WITH(parse_scene(base + "hardening = \"chaboche\"\nchaboche_C = [1,2,3,4,5,6,7,8,9,10,11]\n"
                                         "chaboche_gamma = [0,0,0,0,0,0,0,0,0,0,0]\n",
                                  "e.toml"),
                      Catch::Contains("material.chaboche_C") && Catch::Contains("1 to 10 moduli"));
    // A softening Voce term: its saturated yield stress must stay positive, its rate below 3G's.
    CHECK_THROWS_WITH(parse_scene(base + "voce_Q = -250.0\nvoce_b = 1.0\n", "e.toml"),
                      Catch::Contains("material.voce_Q = -250") && Catch::Contains("yield_stress + voce_Q > 0"));
    CHECK_THROWS_WITH(parse_scene(base + "voce_Q = -100.0\nvoce_b = 1e4\n", "e.toml"),
                      Catch::Contains("material.voce_b = 10000") && Catch::Contains("voce_Q * voce_b > -3G"));
  }
  SECTION("ten back-stresses and a softening Voce term") {
    const Scene scene = parse_scene(base +
                                        "hardening = \"chaboche\"\nchaboche_C = [10,9,8,7,6,5,4,3,2,1]\n"
                                        "chaboche_gamma = [0,1,2,3,4,5,6,7,8,9]\nvoce_Q = -40.0\nvoce_b = 0.04\n",
                                    "ten.toml");
    CHECK(scene.material.n_back_stresses() == 10);
    CHECK(scene.material.back_stress_law(9).modulus == 1.0);
    CHECK(scene.material.back_stress_law(9).recovery == 9.0);
    CHECK(scene.material.lowest_yield_stress() == 210.0);
    const std::string first = scene_to_toml(scene);
    CHECK(scene_to_toml(parse_scene(first, "resolved.toml")) == first);
    CHECK(toml::parse(first)["material"]["voce_Q"].value<double>() == -40.0);
    CHECK_THROWS_WITH(parse_scene(base + "hardening = \"chaboche\"\ntangent_modulus = 100.0\nchaboche_C = [1e5]\n"
                                         "chaboche_gamma = [10.0]\n",
                                  "e.toml"),
                      Catch::Contains("material.tangent_modulus"));
  }
}

TEST_CASE("a load history is piecewise linear through (0, 0), held after its last point, and checked",
          "[io][scene][keys]") {
  const std::string base =
      "[mesh]\nheight = 1.0\n[steps]\ncount = 8\n[material]\nE = 2.1e5\n[[displacement]]\n"
      "nodes = \"bottom\"\nx = 0.0\ny = 0.0\n[[displacement]]\nnodes = \"top\"\n";
  const Scene scene = parse_scene(base + "y = { history = [[2, 0.1], [4, -0.1]] }\n", "history.toml");
  const Ramp& y = *scene.displacements[1].y;
  CHECK(y.at_step(1) == Approx(0.05));
  CHECK(y.at_step(3) == Approx(0.0).margin(1e-15));
  CHECK(y.at_step(4) == Approx(-0.1));
  CHECK(y.at_step(8) == Approx(-0.1));
  CHECK(y.peak() == Approx(0.1));
  const std::string first = scene_to_toml(scene);
  CHECK(scene_to_toml(parse_scene(first, "resolved.toml")) == first);
  CHECK_THROWS_WITH(parse_scene(base + "y = { history = [[2, 0.1], [2, 0.2]] }\n", "h.toml"),
                    Catch::Contains("history") && Catch::Contains("increasing"));
  CHECK_THROWS_WITH(parse_scene(base + "y = { value = 0.1, history = [[2, 0.1]] }\n", "h.toml"),
                    Catch::Contains("either history or value/ramp"));
  // A point on the way as large as the strip is refused, not only the last one.
  CHECK_THROWS_WITH(parse_scene(base + "y = { history = [[2, 1.5], [4, 0.1]] }\n", "h.toml"),
                    Catch::Contains("mesh.height"));
}

TEST_CASE("[fatigue]: every criterion constant is required and physical, and a single pass is refused",
          "[io][scene][keys][fatigue]") {
  const std::string scene = test::read_text(std::string(ROLLER_SOURCE_DIR) + "/problems/shakedown_p45.toml");
  const std::string fatigue =
      "\n[fatigue]\ndang_van_a = 0.3\ndang_van_limit = 300.0\nshear_fatigue_limit = 250.0\n"
      "critical_shear_strain = 11.0\n";
  REQUIRE(error_of(scene + fatigue).empty());
  const Scene loaded = parse_scene(scene + fatigue, "f.toml");
  REQUIRE(loaded.fatigue);
  CHECK(loaded.fatigue->shear_fatigue_limit == 250.0);
  // Each key missing: named, with what it is.
  for (const char* key : {"dang_van_a", "dang_van_limit", "shear_fatigue_limit", "critical_shear_strain"}) {
    std::string without = fatigue;
    const auto at = without.find(key);
    without.erase(at, without.find('\n', at) + 1 - at);
    INFO(key);
    CHECK_THAT(error_of(scene + without),
               Catch::Contains(std::string("fatigue.") + key) && Catch::Contains("is required in [fatigue]"));
  }
  // Non-physical values: the key, the value and the bound.
  CHECK_THAT(error_of(scene + fatigue, {{"fatigue.dang_van_a", "-0.1"}}),
             Catch::Contains("fatigue.dang_van_a") && Catch::Contains("-0.1"));
  CHECK_THAT(error_of(scene + fatigue, {{"fatigue.dang_van_limit", "0.0"}}), Catch::Contains("fatigue.dang_van_limit"));
  CHECK_THAT(error_of(scene + fatigue, {{"fatigue.shear_fatigue_limit", "-5.0"}}),
             Catch::Contains("fatigue.shear_fatigue_limit"));
  CHECK_THAT(error_of(scene + fatigue, {{"fatigue.critical_shear_strain", "0.0"}}),
             Catch::Contains("fatigue.critical_shear_strain"));
  // A limit in Pa: the likely unit.
  CHECK_THAT(error_of(scene + fatigue, {{"fatigue.dang_van_limit", "3e8"}}), Catch::Contains("MPa"));
  // One pass has no stabilised cycle to judge.
  CHECK_THAT(error_of(scene + fatigue, {{"passes.count", "1"}}),
             Catch::Contains("[fatigue] judges a repeated pass") && Catch::Contains("passes.count >= 2"));
}
