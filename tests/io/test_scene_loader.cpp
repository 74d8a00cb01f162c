// Scene files: a good scene loads with its defaults; every kind of bad input is rejected with a
// message that names the file, the key, the value and what was expected.
#include <catch2/catch.hpp>

#include <filesystem>

#include <sys/stat.h>
#include <unistd.h>

#include "../support/scene_errors.hpp"
#include "roller/core/error.hpp"
#include "roller/driver/simulation.hpp"
#include "roller/io/scene_loader.hpp"
#include "roller/io/scene_warnings.hpp"
#include "roller/mesh/strip_mesher.hpp"

using namespace roller;

namespace {

const std::string kGood = R"(
title = "block"
[mesh]
element = "Q4"
length = 10.0
height = 5.0
nx = 4
ny = 2
[material]
E = 2.1e5
nu = 0.3
yield_stress = 50.0
kappa = 0.07
[steps]
count = 4
[[displacement]]
nodes = "bottom"
y = 0.0
[[displacement]]
nodes = [1, 2]
x = { value = 0.5, ramp = [2, 3] }
)";

using test::error_of;

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  REQUIRE(pos != std::string::npos);
  return text.replace(pos, from.size(), to);
}

}  // namespace

TEST_CASE("a valid scene loads with its values and defaults", "[io][scene]") {
  const Scene s = parse_scene(kGood, "good.toml");
  CHECK(s.name == "good");
  CHECK(s.mesh.nx == 4);
  CHECK(s.material.plastic);
  CHECK(s.material.tangent_modulus == Approx(0.07 * 2.1e5));
  CHECK(s.element.kinematics == Kinematics::Finite);
  CHECK(s.element.q4 == Q4Formulation::BBar);  // plastic default
  CHECK(s.steps.n_steps == 4);
  REQUIRE(s.displacements.size() == 2);
  CHECK(s.displacements[1].nodes.numbers == std::vector<Index>{1, 2});
  CHECK(s.displacements[1].x->at_step(1) == 0.0);
  CHECK(s.displacements[1].x->at_step(2) == Approx(0.25));
  CHECK(s.displacements[1].x->at_step(4) == Approx(0.5));
  CHECK_FALSE(s.displacements[1].y.has_value());
}

TEST_CASE("the resolved scene written back loads to the same scene", "[io][scene]") {
  const Scene a = parse_scene(kGood, "good.toml");
  const Scene b = parse_scene(scene_to_toml(a), "resolved.toml");
  CHECK(b.name == a.name);
  CHECK(b.material.tangent_modulus == a.material.tangent_modulus);
  CHECK(b.mesh.ny == a.mesh.ny);
  CHECK(b.displacements.size() == a.displacements.size());
  CHECK(b.displacements[1].x->ramp_first == 2);
  CHECK(scene_to_toml(b) == scene_to_toml(a));
}

TEST_CASE("command-line overrides replace scene values and are validated", "[io][scene]") {
  const Scene s = parse_scene(kGood, "good.toml", {{"material.E", "1e5"}, {"mesh.element", "T3"}});
  CHECK(s.material.youngs_modulus == 1e5);
  CHECK(s.mesh.element == ElementType::T3);
  CHECK_THAT(error_of(kGood, {{"material.nu", "0.7"}}), Catch::Contains("material.nu = 0.7"));
  CHECK_THROWS_AS(parse_override("material.E"), InputError);
}

TEST_CASE("bad scene files give precise errors", "[io][scene][errors]") {
  using Catch::Contains;
  // Unknown key with a suggestion, and with its line number.
  const auto typo = error_of(replace(kGood, "nu = 0.3", "nuu = 0.3"));
  CHECK_THAT(typo, Contains("bad.toml:11") && Contains("material.nuu") && Contains("did you mean 'material.nu'"));
  // Wrong type.
  CHECK_THAT(error_of(replace(kGood, "E = 2.1e5", "E = \"steel\"")),
             Contains("material.E = 'steel'") && Contains("expected a number"));
  // Out-of-range values name the field, the value and the rule.
  CHECK_THAT(error_of(replace(kGood, "nu = 0.3", "nu = 0.5")),
             Contains("bad.toml:11: material.nu = 0.5: must satisfy 0 <= nu < 0.5"));
  CHECK_THAT(error_of(replace(kGood, "kappa = 0.07", "kappa = 1.2")), Contains("material.kappa = 1.2"));
  CHECK_THAT(error_of(replace(kGood, "nx = 4", "nx = 0")), Contains("nx") && Contains("0"));
  CHECK_THAT(error_of(replace(kGood, "count = 4", "count = 0")), Contains("steps.count = 0"));
  // Bad choices list the alternatives.
  CHECK_THAT(error_of(replace(kGood, "element = \"Q4\"", "element = \"Q8\"")),
             Contains("mesh.element = 'Q8'") && Contains("\"Q4\", \"T3\""));
  // Missing required parts.
  CHECK_THAT(error_of(replace(kGood, "E = 2.1e5", "")), Contains("material.E") && Contains("required"));
  CHECK_THAT(error_of(replace(kGood, "[mesh]", "[meshes]")),
             Contains("meshes: unknown key") && Contains("did you mean 'mesh'"));
  // Ramps and selectors.
  CHECK_THAT(error_of(replace(kGood, "ramp = [2, 3]", "ramp = [3, 2]")), Contains("displacement[1].x.ramp"));
  CHECK_THAT(error_of(replace(kGood, "nodes = [1, 2]", "nodes = 7")), Contains("displacement[1].nodes"));
  CHECK_THAT(error_of(replace(kGood, "kappa = 0.07", "kappa = 0.07\ntangent_modulus = 100.0")),
             Contains("either tangent_modulus or kappa"));
  // Non-finite numbers are rejected wherever a number is read (TOML allows nan and inf): plain
  // keys, ramps, arrays, selectors.
  CHECK_THAT(error_of(replace(kGood, "E = 2.1e5", "E = inf")),
             Contains("bad.toml:10: material.E = inf") && Contains("finite"));
  CHECK_THAT(error_of(replace(kGood, "y = 0.0", "y = nan")), Contains("displacement[0].y = nan") && Contains("finite"));
  CHECK_THAT(error_of(replace(kGood, "value = 0.5", "value = -inf")),
             Contains("displacement[1].x.value") && Contains("finite"));
  CHECK_THAT(error_of(replace(kGood, "nodes = [1, 2]", "nodes = { near = [nan, 0.0] }")),
             Contains("displacement[1].nodes.near") && Contains("finite"));
  CHECK_THAT(error_of(kGood + "[[load]]\nnodes = \"top\"\nfy = inf\n"),
             Contains("load[0].fy = inf") && Contains("finite"));
  // Plausibility bounds: values found by fuzzing to overflow the solvers into NaN.
  CHECK_THAT(error_of(replace(kGood, "E = 2.1e5", "E = 1e300")),
             Contains("material.E = 1e+300") && Contains("<= 1000000000"));
  CHECK_THAT(error_of(replace(kGood, "length = 10.0", "length = 1e300")), Contains("mesh.length = 1e+300"));
  CHECK_THAT(error_of(replace(kGood, "height = 5.0", "height = 1e-308")), Contains("mesh.height"));
  CHECK_THAT(error_of(replace(kGood, "y = 0.0", "y = -1e308")),
             Contains("displacement[0].y") && Contains("plausibility"));
  // An integer beyond 2^53 is read like any other number and checked (it used to end in "bad
  // optional access", with no key and no line).
  CHECK_THAT(error_of(replace(kGood, "y = 0.0", "y = 9007199254740993")),
             Contains("bad.toml:18: displacement[0].y = 9007199254740993") && Contains("plausibility"));
  // The name is one folder under out/.
  CHECK_THAT(error_of("name = \"../../x\"\n" + kGood), Contains("bad.toml:1: name") && Contains("without '/'"));
  CHECK_THAT(error_of("name = \"\"\n" + kGood), Contains("name") && Contains("non-empty"));
  // Deep nesting is refused before the TOML parser, whose recursion 50,000 levels overflow.
  std::string deep;
  for (int k = 0; k < 50000; ++k) deep += "a.";
  CHECK_THAT(error_of(deep + "b = 1\n" + kGood), Contains("bad.toml:1: keys or brackets nested deeper than 100"));
  CHECK_THAT(error_of(std::string(200, '[') + "\n" + kGood), Contains("nested deeper"));
  // Syntax errors give line and column.
  CHECK_THAT(error_of(replace(kGood, "nx = 4", "nx = = 4")), Contains("bad.toml:7") && Contains("syntax"));
  // Missing file.
  CHECK_THROWS_WITH(load_scene("/nonexistent/scene.toml"), Contains("cannot open"));
  // A device or a folder is not read (/dev/zero would be read forever).
  CHECK_THROWS_WITH(load_scene("/dev/zero"), Contains("/dev/zero: not a regular file"));
  CHECK_THROWS_WITH(load_scene("/tmp"), Contains("not a regular file"));
  // A FIFO would block the read until someone writes into it.
  const std::filesystem::path fifo =
      std::filesystem::temp_directory_path() / ("roller_fifo_" + std::to_string(::getpid()) + ".toml");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  CHECK_THROWS_WITH(load_scene(fifo), Contains("not a regular file"));
  std::filesystem::remove(fifo);
}

TEST_CASE("node selectors are checked against the mesh", "[io][scene][errors]") {
  StripMeshSpec spec;
  spec.nx = 2;
  spec.ny = 1;
  const Mesh mesh = make_strip_mesh(spec);
  NodeSelector by_number;
  by_number.numbers = {1, 6, 7};
  CHECK_THROWS_WITH(resolve_nodes(by_number, mesh, "displacement[0].nodes"),
                    Catch::Contains("displacement[0].nodes") && Catch::Contains("node 7") && Catch::Contains("1..6"));
  NodeSelector by_name;
  by_name.set_name = "topp";
  CHECK_THROWS_WITH(resolve_nodes(by_name, mesh, "load[0].nodes"), Catch::Contains("topp"));
  by_name.set_name = "top";
  CHECK(resolve_nodes(by_name, mesh, "x").size() == 3);
}

TEST_CASE("a node can be selected as the one nearest to a point", "[io][scene]") {
  const Scene s = parse_scene(replace(kGood, "nodes = [1, 2]", "nodes = { near = [5.2, 0.1] }"), "near.toml");
  REQUIRE(s.displacements[1].nodes.near.has_value());
  const Mesh mesh = make_strip_mesh(s.mesh);
  const auto nodes = resolve_nodes(s.displacements[1].nodes, mesh, "displacement[1].nodes");
  REQUIRE(nodes.size() == 1);
  CHECK(mesh.nodes[nodes[0]].x() == Approx(5.0));
  CHECK(mesh.nodes[nodes[0]].y() == Approx(0.0));
  CHECK_THAT(error_of(replace(kGood, "nodes = [1, 2]", "nodes = { near = [5.2] }")),
             Catch::Contains("displacement[1].nodes.near"));
}

TEST_CASE("contact.ipopt.options pass Ipopt options through and reject unknown ones before computing", "[io][ipopt]") {
  const std::string base = std::string(ROLLER_SOURCE_DIR) + "/problems/hertz.toml";
  const Scene ok = load_scene(base, {{"contact.backend", "\"ipopt\""},
                                     {"contact.ipopt.options.mumps_pivot_order", "0"},
                                     {"contact.ipopt.options.print_timing_statistics", "true"},
                                     {"contact.ipopt.options.bound_push", "0.01"}});
  REQUIRE(ok.contact.ipopt.raw.size() == 3);
  auto find = [&](const std::string& name) {
    for (const auto& r : ok.contact.ipopt.raw)
      if (r.name == name) return r;
    FAIL("option " << name << " missing");
    return RawIpoptOption{};
  };
  CHECK(find("mumps_pivot_order").kind == RawIpoptOption::Kind::Integer);
  CHECK(find("print_timing_statistics").text == "yes");
  CHECK(find("bound_push").kind == RawIpoptOption::Kind::Number);
  CHECK_NOTHROW(Simulation(ok));
  const Scene bad =
      load_scene(base, {{"contact.backend", "\"ipopt\""}, {"contact.ipopt.options.mumps_pivot_ordr", "0"}});
  CHECK_THROWS_WITH(Simulation(bad), Catch::Contains("contact.ipopt.options.mumps_pivot_ordr = 0: Ipopt rejects it"));
  // roller picks Ipopt's linear solver per NLP: the pass-through would be overridden, so it is refused.
  CHECK_THROWS_WITH(
      load_scene(base, {{"contact.backend", "\"ipopt\""}, {"contact.ipopt.options.linear_solver", "\"ma57\""}}),
      Catch::Contains("contact.ipopt.options.linear_solver") && Catch::Contains("contact.ipopt.kkt_solver"));
}

TEST_CASE("[linear_solver] selects MUMPS's ordering and out-of-core mode, checked before computing", "[io][scene]") {
  using Catch::Contains;
  const Scene plain = parse_scene(kGood, "good.toml");
  CHECK_FALSE(plain.newton.linear.out_of_core);
  CHECK(plain.newton.linear.ordering == "auto");
  const std::string dir = std::filesystem::temp_directory_path().string();
  const Scene s = parse_scene(
      kGood + "[linear_solver]\nout_of_core = true\nordering = \"amd\"\ndirectory = \"" + dir + "\"\n", "good.toml");
  CHECK(s.newton.linear.out_of_core);
  CHECK(s.newton.linear.ordering == "amd");
  CHECK(s.newton.linear.directory == dir);
  // The resolved scene keeps them.
  const Scene back = parse_scene(scene_to_toml(s), "resolved.toml");
  CHECK(back.newton.linear.out_of_core);
  CHECK(back.newton.linear.ordering == "amd");
  CHECK(back.newton.linear.directory == dir);
  // Errors name the key, the value and what was expected.
  CHECK_THAT(error_of(kGood, {{"linear_solver.ordering", "nested"}}),
             Contains("linear_solver.ordering = 'nested'") && Contains("\"amd\""));
  CHECK_THAT(error_of(kGood, {{"linear_solver.directory", "/nonexistent/ooc"}}),
             Contains("linear_solver.directory") && Contains("/nonexistent/ooc") && Contains("existing directory"));
  CHECK_THAT(error_of(kGood, {{"linear_solver.out_of_core", "3"}}), Contains("linear_solver.out_of_core"));
  CHECK_THAT(error_of(kGood, {{"linear_solver.out_of_cor", "true"}}),
             Contains("did you mean 'linear_solver.out_of_core'"));
}

TEST_CASE("a state file must be a regular file", "[io][state][errors]") {
  Scene s = parse_scene(kGood, "good.toml");
  s.initial_state = "/tmp";  // a folder gave a raw stream error
  CHECK_THROWS_WITH(Simulation(s), Catch::Contains("/tmp: not a regular file"));
  s.initial_state = "/dev/zero";  // was read forever
  CHECK_THROWS_WITH(Simulation(s), Catch::Contains("/dev/zero: not a regular file"));
}

TEST_CASE("a roller that starts inside the strip is reported as such, before computing", "[io][scene][errors]") {
  // kGood's strip is 10 x 5 mm; a roller of radius 2 centred 1 mm above its top is 1 mm deep.
  Scene s = parse_scene(kGood + "[roller]\nradius = 2.0\ncentre = [5.0, 6.0]\n", "inside.toml");
  CHECK_THROWS_WITH(Simulation(s),
                    Catch::Contains("inside.toml: roller.centre = [5, 6]: the roller starts inside the strip") &&
                        Catch::Contains("1 mm inside"));
  // Touching the surface is a valid start.
  Scene touching = parse_scene(kGood + "[roller]\nradius = 2.0\ncentre = [5.0, 7.0]\n", "touching.toml");
  CHECK_NOTHROW(Simulation(touching));
}

TEST_CASE("the roller's size and the motions are checked against the strip's size", "[io][scene][errors]") {
  using Catch::Contains;
  // kGood's strip is 10 x 5 mm: S = 10 mm.
  const std::string roller = kGood + "[roller]\nradius = 2.0\ncentre = [5.0, 7.0]\n";
  CHECK(error_of(roller).empty());
  // A 1e9 mm roller on a 10 mm strip passed the absolute bounds; the gap lost every digit.
  CHECK_THAT(error_of(replace(roller, "radius = 2.0", "radius = 1e9")),
             Contains("bad.toml:23: roller.radius = 1000000000") && Contains("<= radius <= 1e+07 mm"));
  CHECK_THAT(error_of(replace(roller, "radius = 2.0", "radius = 1e-6")), Contains("roller.radius = 1e-06"));
  // Within the bounds at either end: 1e-5 and 1e7 mm.
  CHECK(error_of(replace(replace(roller, "radius = 2.0", "radius = 1e7"), "7.0]", "10000005.0]")).empty());
  CHECK(error_of(replace(replace(roller, "radius = 2.0", "radius = 1e-5"), "7.0]", "5.00001]")).empty());
  // A roller starting far away never reaches the strip.
  CHECK_THAT(error_of(replace(roller, "centre = [5.0, 7.0]", "centre = [5.0, 1e5]")),
             Contains("bad.toml:24: roller.centre") && Contains("starts 99993 mm away from the strip"));
  // Travels, harmonic and displacements: at most 1000 S.
  CHECK_THAT(error_of(roller + "[[roller.path]]\nsteps = [1, 4]\ndx = -2e4\n"),
             Contains("roller.path[0].dx = -20000") && Contains("|value| <= 10000 mm"));
  CHECK_THAT(error_of(roller + "[[roller.path]]\nsteps = [1, 4]\ndx = -1.0\nharmonic = { amplitude = 1e5, "
                               "wavelength = 1.0 }\n"),
             Contains("roller.path[0].harmonic") && Contains("strip's size"));
  CHECK(error_of(roller + "[[roller.path]]\nsteps = [1, 4]\ndx = -1e4\n").empty());
  // A prescribed displacement stays below the strip's own extent (stricter than the reach).
  CHECK_THAT(error_of(replace(kGood, "y = 0.0", "y = 2e4")),
             Contains("bad.toml:18: displacement[0].y = 20000") && Contains("strip's height mesh.height = 5"));
}

TEST_CASE("prescribed roller forces are checked before computing", "[io][scene][errors]") {
  using Catch::Contains;
  const std::string roller = kGood + "[roller]\nradius = 2.0\ncentre = [5.0, 7.0]\n";
  CHECK(error_of(roller + "[[roller.path]]\nsteps = [1, 4]\nfy = 10.0\nfx = -2.5\n").empty());
  CHECK_THAT(error_of(roller + "[[roller.path]]\nsteps = [1, 4]\nfy = -10.0\n"),
             Contains("bad.toml") && Contains("fy = -10") && Contains("only pushes"));
  CHECK_THAT(error_of(roller + "[[roller.path]]\nsteps = [1, 4]\nfx = 1e16\n"),
             Contains("bad.toml") && Contains("fx = 1e+16") && Contains("|fx| <= 1e+15"));
  CHECK_THAT(error_of(roller + "[[roller.path]]\nsteps = [1, 4]\nfx = \"left\"\n"),
             Contains("roller.path") && Contains("fx"));
  CHECK_THAT(error_of(roller + "[roller.suspension]\nstiffness = 1e3\n[[roller.path]]\nsteps = [1, 4]\nfx = 1.0\n"),
             Contains("bad.toml:22: roller.path[0].fx") && Contains("without roller.suspension"));
}

TEST_CASE("the smaller input checks: overrides do not hide the file, and the edge values are refused",
          "[io][scene][errors]") {
  using Catch::Contains;
  // The file as written is checked before an override replaces a bad value in it.
  CHECK_THAT(error_of(replace(kGood, "count = 4", "count = nan"), {{"steps.count", "2"}}), Contains("steps.count"));
  CHECK_THAT(error_of(replace(kGood, "element = \"Q4\"", "element = \"Q5\""), {{"mesh.element", "\"T3\""}}),
             Contains("mesh.element"));
  // Bounds found by the hostile-input probe.
  CHECK_THAT(
      error_of(replace(kGood, "kappa = 0.07", "kappa = 0.07\nsubsteps = 1000000\nstress_integration = \"substep\"")),
      Contains("material.substeps") && Contains("1000"));
  CHECK_THAT(error_of(replace(kGood, "ny = 2", "ny = 2\nx_lines = []")),
             Contains("mesh.x_lines") && Contains("at least two grid lines"));
  for (const char* name : {"a b", "a\\tb", "a\\u0000b"})
    CHECK_THAT(error_of("name = \"" + std::string(name) + "\"\n" + kGood), Contains("name"));
  CHECK_THAT(error_of(kGood, {{"steps.dt", "1e-308"}}), Contains("steps.dt") && Contains("1e-12"));
  CHECK_THAT(error_of(replace(kGood, "x = { value = 0.5", "x = { value = 10.0")),
             Contains("displacement[1].x") && Contains("mesh.length = 10"));
  CHECK(error_of(kGood, {{"steps.dt", "1e-6"}}).empty());
  // A roller entirely below the strip (kGood's strip spans y = 0..5).
  Scene below = parse_scene(kGood + "[roller]\nradius = 2.0\ncentre = [5.0, -3.0]\n", "below.toml");
  CHECK_THROWS_WITH(Simulation(below), Contains("below.toml: roller.centre = [5, -3]: the roller lies entirely below"));
}

TEST_CASE("a modulus or a yield stress in the wrong unit is named with the likely unit before computing",
          "[io][scene][errors]") {
  using Catch::Contains;
  // E in Pa: beyond the modulus's bound, and the message says why it likely is.
  CHECK_THAT(error_of(kGood, {{"material.E", "2.1e11"}}),
             Contains("material.E = 210000000000") && Contains("E in Pa? roller works in MPa"));
  // A yield stress in Pa beside E in MPa, or E in GPa beside a yield stress in MPa: legal values (a
  // contrast of layers may mean them), named in a warning.
  auto warnings = [](const std::vector<SceneOverride>& overrides, const std::string& extra = "") {
    const Scene s = parse_scene(kGood + extra, "units.toml", overrides);
    std::string all;
    for (const std::string& w : scene_warnings(s, make_strip_mesh(s.strip_mesh_spec()))) all += w + "\n";
    return all;
  };
  CHECK(warnings({}).empty());
  CHECK_THAT(warnings({{"material.yield_stress", "5e8"}}), Contains("units.toml: material.yield_stress = 5e+08 MPa") &&
                                                               Contains("yield stress in Pa") &&
                                                               Contains("roller works in MPa"));
  CHECK_THAT(warnings({{"material.E", "210"}}), Contains("material.yield_stress") && Contains("E in GPa"));
  CHECK_THAT(warnings({}, "[[layer]]\nthickness = 1.0\nyield_stress = 5e8\n"),
             Contains("layer[0].yield_stress") && Contains("yield stress in Pa"));
  // A polymer's ratio is none (nylon: E = 2500, yield 75: 3 %).
  CHECK(warnings({{"material.E", "2500"}, {"material.yield_stress", "75"}}).empty());
}
