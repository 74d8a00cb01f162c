// roller shakedown-limit SCENE: Melan's bound of the scene's strip, roller and traction from one
// elastic solution (docs/model.md, "Melan's bound"; docs/tutorial.md shows a session).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli_checks.hpp"
#include "commands.hpp"
#include "roller/core/error.hpp"
#include "roller/io/atomic_file.hpp"
#include "roller/io/scene_loader.hpp"
#include "roller/steady/shakedown_limit.hpp"
#include "rollerpy_plot.hpp"

namespace roller::app {

namespace {

struct ShakedownLimitArgs {
  std::string scene;
  std::vector<std::string> sets;
  int refine = 0;
  std::optional<Real> traction;
  std::string csv, json;
  std::string map;      // the folder of the map over q/p
  int map_points = 11;  // q/p = 0 .. 0.5
  bool no_plot = false;
};

// The map's file names in its folder.
constexpr const char* kMapCsv = "shakedown_limit_map.csv";

const char* where(Real depth) { return depth == 0.0 ? "at the surface" : "below it"; }

// A limit as its load factor, the p0 it puts on the scene and p0/k with the k where it is reached.
std::string bound_line(const char* name, const ShakedownLimitResult& r, const MelanLimit& b) {
  if (b.critical_row < 0) return fmt::format("  {:<26} none: no depth limits the load\n", name);
  const MelanRowLimit& c = b.rows[b.critical_row];
  return fmt::format(
      "  {:<26} load factor {:.4g}: p0 = {:.5g} MPa, p0/k = {:.4g} (k = {:.4g} MPa there), at depth {:.3g} mm "
      "({:.3g} a, {}), x = {:.4g} mm\n",
      name, b.load_factor(), b.load_factor() * r.load.hertz_peak, r.p0_over_k(b),
      c.critical_yield_stress / std::sqrt(3.0), c.depth, c.depth / r.load.half_width, where(c.depth), c.critical_x);
}

void print_result(const Scene& scene, const ShakedownLimitResult& r) {
  const ShakedownLoad& l = r.load;
  std::cout << fmt::format(
      "roller: shakedown limit of '{}' (load factor 1: the scene's load P = {:.6g} N/mm, {}Hertz a = {:.4g} mm, "
      "p0 = {:.5g} MPa; computed peak pressure {:.5g} MPa; {})\n",
      scene.name, l.load, scene.roller->elastic() ? "two-body " : "", l.half_width, l.hertz_peak, l.computed_peak,
      l.shape == TractionShape::Carter
          ? fmt::format("Carter's traction Q = {:.3g} P, stick zone c = {:.4g} mm at the leading edge", l.traction,
                        l.stick_half_width)
          : fmt::format("traction q = {:.3g} p", l.traction));
  std::cout << fmt::format("  {:<26} load factor {:.4g}: p0 = {:.5g} MPa\n", "first yield", r.elastic.first_yield(),
                           r.elastic.first_yield() * l.hertz_peak);
  std::cout << bound_line("elastic shakedown limit", r, r.elastic);
  if (r.kinematic) std::cout << bound_line("kinematic hardening limit", r, *r.kinematic);
  // With p0 = sqrt(P E*/(pi R)) the load scales with the square of the factor (a grows with it).
  std::cout << fmt::format("  the load P at the elastic shakedown limit (Hertz: P ~ p0^2): {:.6g} N/mm\n",
                           l.load * r.elastic.load_factor() * r.elastic.load_factor());
  for (const std::string& w : r.warnings) std::cerr << "roller: warning: " << w << "\n";
}

// The bound's governing mode: the surface or below it.
std::string mode_of(const MelanLimit& b) {
  if (b.critical_row < 0) return "none";
  return b.rows[b.critical_row].depth == 0.0 ? "surface" : "subsurface";
}

// The map over q/p: a line per traction, in the folder `dir` as CSV, and its figure.
int write_map(const Scene& scene, const ShakedownLimitArgs& args) {
  namespace fs = std::filesystem;
  std::vector<Real> tractions;
  for (int i = 0; i < args.map_points; ++i) tractions.push_back(0.5 * i / (args.map_points - 1));
  ShakedownLimitSettings settings;
  settings.progress = &std::cout;
  std::vector<ShakedownLimitResult> map;
  try {
    map = compute_shakedown_map(scene, tractions, settings);
  } catch (const NumericalError& e) {
    std::cerr << "roller: shakedown-limit failed: " << e.what() << "\n";
    return 1;
  }
  std::string text =
      "q_over_p,elastic_p0_over_k,elastic_depth_over_a,elastic_mode,kinematic_p0_over_k,kinematic_depth_over_a,"
      "kinematic_mode,nu\n";
  auto cells = [](const ShakedownLimitResult& r, const std::optional<MelanLimit>& b) {
    if (!b || b->critical_row < 0) return std::string(",,");
    return fmt::format("{:.6g},{:.6g},{}", r.p0_over_k(*b), b->rows[b->critical_row].depth / r.load.half_width,
                       mode_of(*b));
  };
  for (const ShakedownLimitResult& r : map)
    text += fmt::format("{:.6g},{},{},{:.6g}\n", r.load.traction, cells(r, r.elastic), cells(r, r.kinematic),
                        scene.strip_material().surface().poisson_ratio);
  std::error_code ec;
  fs::create_directories(args.map, ec);
  if (ec) throw InputError(fmt::format("--map {}: cannot create the folder ({})", args.map, ec.message()));
  write_file_atomically(fs::path(args.map) / kMapCsv, text, "the shakedown map's CSV");
  std::cout << fmt::format("roller: shakedown map of '{}' over q/p = 0..0.5 in {}\n", scene.name,
                           (fs::path(args.map) / kMapCsv).string());
  std::vector<std::string> warned;
  for (const ShakedownLimitResult& r : map)
    for (const std::string& w : r.warnings)
      if (std::find(warned.begin(), warned.end(), w) == warned.end()) warned.push_back(w);
  for (const std::string& w : warned) std::cerr << "roller: warning: " << w << "\n";
  return render_with_rollerpy("plot-melan-map", args.map, args.no_plot, "roller shakedown-limit");
}

nlohmann::json bound_json(const ShakedownLimitResult& r, const MelanLimit& b) {
  nlohmann::json j{{"bound", enum_name(b.bound)},
                   {"load_factor", b.load_factor()},
                   {"p0_over_k", r.p0_over_k(b)},
                   {"mode", mode_of(b)}};
  if (b.critical_row >= 0) {
    const MelanRowLimit& c = b.rows[b.critical_row];
    j["depth"] = c.depth;
    j["depth_over_a"] = c.depth / r.load.half_width;
    j["x"] = c.critical_x;
    j["yield_stress"] = c.critical_yield_stress;
  }
  return j;
}

void write_json(const std::string& path, const ShakedownLimitResult& r) {
  const ShakedownLoad& l = r.load;
  nlohmann::json j{{"load",
                    {{"P", l.load},
                     {"a", l.half_width},
                     {"p0", l.hertz_peak},
                     {"computed_peak", l.computed_peak},
                     {"traction", l.traction},
                     {"traction_shape", l.shape == TractionShape::Carter ? "carter" : "uniform"},
                     {"stick_half_width", l.stick_half_width},
                     {"press_steps", l.press_steps}}},
                   {"scene_p0_over_k", r.scene_p0_over_k(r.elastic)},
                   {"first_yield_p0_over_k", r.elastic.first_yield() * r.scene_p0_over_k(r.elastic)},
                   {"elastic", bound_json(r, r.elastic)}};
  if (r.kinematic) j["kinematic"] = bound_json(r, *r.kinematic);
  j["warnings"] = r.warnings;
  write_file_atomically(path, j.dump(2) + "\n", "the shakedown limit's JSON");
}

// One line per depth: each row's limits as p0/k (with that row's own k) and its residual state.
void write_csv(const std::string& path, const ShakedownLimitResult& r) {
  std::string text =
      "depth_mm,depth_over_a,first_yield_p0_over_k,elastic_p0_over_k,kinematic_p0_over_k,rho_xx,rho_zz,alpha_xx,"
      "alpha_yy,alpha_zz,alpha_xy\n";
  const auto p0k = [&](const MelanRowLimit& row, Real factor) {
    switch (row.status) {
      case MelanRowStatus::Solved:
        return fmt::format("{:.6g}", factor * r.load.hertz_peak * std::sqrt(3.0) / row.critical_yield_stress);
      case MelanRowStatus::Unlimited: return std::string("inf");
      case MelanRowStatus::NotLimiting: return std::string();
    }
    return std::string();
  };
  for (std::size_t i = 0; i < r.elastic.rows.size(); ++i) {
    const MelanRowLimit& e = r.elastic.rows[i];
    const MelanRowLimit* k = r.kinematic ? &r.kinematic->rows[i] : nullptr;
    const Real yield = e.critical_yield_stress;
    const std::string fy = yield > 0.0
                               ? fmt::format("{:.6g}", e.first_yield * r.load.hertz_peak * std::sqrt(3.0) / yield)
                               : std::string("inf");
    const Vec4 alpha = k ? k->back_stress : Vec4::Zero();
    text += fmt::format("{:.6g},{:.6g},{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}\n", e.depth,
                        e.depth / r.load.half_width, fy, p0k(e, e.load_factor), k ? p0k(*k, k->load_factor) : "",
                        e.residual_stress[0], e.residual_stress[2], alpha[0], alpha[1], alpha[2], alpha[3]);
  }
  write_file_atomically(path, text, "the shakedown limit's CSV");
}

}  // namespace

Command add_shakedown_limit_command(CLI::App& app) {
  auto args = std::make_shared<ShakedownLimitArgs>();
  CLI::App* cmd = app.add_subcommand(
      "shakedown-limit",
      "Melan's shakedown limit of a scene's strip, roller and traction from one elastic solution (docs/model.md)");
  cmd->add_option("scene", args->scene, "scene file (TOML)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--set", args->sets, "override a scene value, e.g. --set contact.friction=0.2")
      ->type_name("KEY=VALUE");
  cmd->add_option("--refine", args->refine, "mesh refinement factor (overrides mesh.refine)")->check(CLI::Range(1, 64));
  cmd->add_option("--traction", args->traction,
                  "a uniform traction q/p (default: Carter's traction of the rolling segment's fx or q_over_p when it "
                  "has one, the "
                  "friction coefficient when the roller slides, 0 when it rolls freely)")
      ->check(finite_range(0.0, 10.0));
  cmd->add_option("--csv", args->csv, "write the limit of every depth to this CSV file (a new or a regular file)");
  cmd->add_option("--json", args->json, "write the limits to this JSON file (a new or a regular file)");
  cmd->add_option(
      "--map", args->map,
      "sweep a uniform traction q/p from 0 to 0.5 and write the map to this folder (shakedown_limit_map.csv "
      "and .png, beside Johnson's line-contact limits)");
  cmd->add_option("--map-points", args->map_points, "tractions of the map, from 0 to 0.5")->check(CLI::Range(2, 101));
  cmd->add_flag("--no-plot", args->no_plot, "with --map: write the CSV only; print the plotting command");
  return [args, cmd] {
    // The files named are checked before anything is computed.
    if (cmd->count("--csv") > 0) check_output_file(args->csv, "--csv");
    if (cmd->count("--json") > 0) check_output_file(args->json, "--json");
    std::vector<SceneOverride> overrides;
    for (const auto& s : args->sets) overrides.push_back(parse_override(s));
    if (args->refine > 0) overrides.push_back({"mesh.refine", std::to_string(args->refine)});
    const Scene scene = load_scene(args->scene, overrides);
    if (cmd->count("--map") > 0) {
      if (args->traction || cmd->count("--csv") > 0 || cmd->count("--json") > 0)
        throw InputError(
            "--map sweeps the traction and writes its own files: give it without --traction, --csv "
            "and --json");
      std::error_code ec;
      if (args->map.empty() ||
          (std::filesystem::exists(args->map, ec) && !std::filesystem::is_directory(args->map, ec)))
        throw InputError(fmt::format("--map '{}': expected a folder (new or existing) for the map's files", args->map));
      return write_map(scene, *args);
    }
    ShakedownLimitSettings settings;
    settings.traction = args->traction;
    if (cmd->count("--csv") > 0) settings.search = MelanSearch::EveryRow;
    settings.progress = &std::cout;
    ShakedownLimitResult result;
    try {
      result = compute_shakedown_limit(scene, settings);
    } catch (const NumericalError& e) {
      std::cerr << "roller: shakedown-limit failed: " << e.what() << "\n";
      return 1;
    }
    print_result(scene, result);
    if (cmd->count("--csv") > 0) write_csv(args->csv, result);
    if (cmd->count("--json") > 0) write_json(args->json, result);
    return 0;
  };
}

}  // namespace roller::app
