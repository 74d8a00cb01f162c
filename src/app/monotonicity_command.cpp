// roller monotonicity: the thesis's study of operator A (Fig. 3.1; docs/monotonicity.md, "The
// maps"). Sweeps the 4-D grid (sigma_pl, a, b, c), writes the PD flag and lambda_min over it, the
// twelve slices of Fig. 3.1 at one yield stress (coarse = the grid's own points, fine = for smooth
// boundaries) and a JSON summary, then renders the PNG maps with `rollerpy plot-monotonicity`
// (the launcher ./rollerpy of the source tree, /usr/bin/python3).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli_checks.hpp"
#include "commands.hpp"
#include "roller/analysis/monotonicity_map.hpp"
#include "roller/core/error.hpp"
#include "rollerpy_plot.hpp"

namespace roller::app {

namespace {

namespace fs = std::filesystem;

struct MonotonicityArgs {
  Real youngs_modulus = 2.1e5;
  Real poisson_ratio = 0.3;
  Real tangent_modulus = std::numeric_limits<Real>::quiet_NaN();  // NaN: E/3
  std::vector<Real> sigma_range{5.0, 105.0};
  std::vector<Real> ab_range{-150.0, 150.0};
  std::vector<Real> c_range{-50.0, 50.0};
  int grid = 21;
  Real slice_sigma = 40.0;
  int slice_grid = 201;
  std::string layout = "thesis";
  std::string tau33 = "zero";
  Real density = 0.0;
  Real dt = 0.0;
  Real h = 0.0;
  std::string out = "out/monotonicity";
  bool no_plot = false;
};

GridAxis axis(const std::vector<Real>& range, int n) { return {range.at(0), range.at(1), n}; }

MonotonicityMapOptions map_options(const MonotonicityArgs& args) {
  MonotonicityMapOptions o;
  o.youngs_modulus = args.youngs_modulus;
  o.poisson_ratio = args.poisson_ratio;
  o.tangent_modulus = std::isnan(args.tangent_modulus) ? args.youngs_modulus / 3.0 : args.tangent_modulus;
  o.sigma = axis(args.sigma_range, args.grid);
  o.a = axis(args.ab_range, args.grid);
  o.b = axis(args.ab_range, args.grid);
  o.c = axis(args.c_range, args.grid);
  o.layout = parse_gradient_layout(args.layout);
  if (args.tau33 == "zero") {
    o.out_of_plane = OutOfPlaneStress::Zero;
  } else if (args.tau33 == "elastic") {
    o.out_of_plane = OutOfPlaneStress::PlaneStrainElastic;
  } else {
    throw InputError(fmt::format("--tau33 {}: expected zero or elastic", args.tau33));
  }
  const int n_dynamic = (args.density > 0.0) + (args.dt > 0.0) + (args.h > 0.0);
  if (n_dynamic != 0 && n_dynamic != 3) {
    throw InputError(fmt::format("--density {} --dt {} --h {}: the dynamic term needs all three > 0 (or none)",
                                 args.density, args.dt, args.h));
  }
  o.mass_scale = n_dynamic == 3 ? mass_scale(args.density, args.h, args.dt) : 0.0;
  std::string why;
  if (!o.is_valid(&why)) throw InputError(why);
  if (!(args.slice_sigma > 0.0)) {
    throw InputError(fmt::format("--slice-sigma {}: must be > 0", args.slice_sigma));
  }
  if (args.slice_grid < 2) {
    throw InputError(fmt::format("--slice-grid {}: must be >= 2", args.slice_grid));
  }
  return o;
}

std::string flag(bool b) { return b ? "1" : "0"; }

void write_point(std::ostream& out, const MapPoint& m) {
  out << fmt::format("{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{},{},{}\n", m.sigma_pl, m.p.a, m.p.b, m.p.c,
                     m.d.lambda_min, flag(m.d.by_eigenvalue), flag(m.d.by_cholesky), flag(m.d.by_minors));
}

std::ofstream open_output(const fs::path& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(fmt::format("cannot write {}", path.string()));
  return out;
}

// "'launcher' plot-monotonicity 'dir'" with single quotes escaped for the shell.

// The 4-D grid into monotonicity_grid.csv: its points, how many are positive definite, and at
// how many the three tests disagree.
struct GridCounts {
  std::size_t points = 0;
  Index pd = 0, disagree = 0;
};
GridCounts write_grid(const MonotonicityMapOptions& options, const fs::path& dir) {
  const std::vector<MapPoint> grid = sweep_grid(options);
  GridCounts counts;
  counts.points = grid.size();
  std::ofstream out = open_output(dir / "monotonicity_grid.csv");
  out << "sigma_pl,a,b,c,lambda_min,pd_eigen,pd_cholesky,pd_minors\n";
  for (const MapPoint& m : grid) {
    write_point(out, m);
    counts.pd += m.d.positive_definite();
    counts.disagree += !m.d.consistent();
  }
  return counts;
}

// The twelve slices at the figures' yield stress (the grid's own points and a fine grid) into
// monotonicity_slices.csv; their summaries for monotonicity.json.
nlohmann::json write_slices(const MonotonicityMapOptions& options, const MonotonicityArgs& args, const fs::path& dir) {
  nlohmann::json panels = nlohmann::json::array();
  std::ofstream out = open_output(dir / "monotonicity_slices.csv");
  out << "panel,resolution,sigma_pl,a,b,c,lambda_min,pd_eigen,pd_cholesky,pd_minors\n";
  for (const MapSlice& slice : thesis_slices()) {
    const int n_first = slice.plane == SlicePlane::CB ? options.b.n : options.a.n;
    const int n_second = slice.plane == SlicePlane::AB ? options.b.n : options.c.n;
    const auto coarse = sweep_slice(options, slice, args.slice_sigma, n_first, n_second);
    const auto fine = sweep_slice(options, slice, args.slice_sigma, args.slice_grid, args.slice_grid);
    Index coarse_pd = 0;
    for (const MapPoint& m : coarse) {
      out << slice.id << ",coarse,";
      write_point(out, m);
      coarse_pd += m.d.positive_definite();
    }
    Real lambda_max_slice = -std::numeric_limits<Real>::infinity();
    for (const MapPoint& m : fine) {
      out << slice.id << ",fine,";
      write_point(out, m);
      lambda_max_slice = std::max(lambda_max_slice, m.d.lambda_min);
    }
    panels.push_back({{"id", slice.id},
                      {"plane", slice.plane == SlicePlane::AB   ? "ab"
                                : slice.plane == SlicePlane::CA ? "ca"
                                                                : "cb"},
                      {"fixed", slice.fixed},
                      {"title", slice.describe()},
                      {"coarse_points", coarse.size()},
                      {"coarse_pd", coarse_pd},
                      {"max_lambda_min_fine", lambda_max_slice}});
  }
  return panels;
}

// The PNG maps from the data in `dir` by the Python package (exit code of the command).
int render_maps(const MonotonicityArgs& args, const fs::path& dir) {
  return render_with_rollerpy("plot-monotonicity", dir, args.no_plot, "roller monotonicity");
}

int run_monotonicity(const MonotonicityArgs& args) {
  const MonotonicityMapOptions options = map_options(args);
  const fs::path dir(args.out);
  fs::create_directories(dir);
  const auto t0 = std::chrono::steady_clock::now();
  const GridCounts grid = write_grid(options, dir);
  const nlohmann::json panels = write_slices(options, args, dir);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  const MaterialParams material = options.material();
  nlohmann::json meta = {{"E", options.youngs_modulus},
                         {"nu", options.poisson_ratio},
                         {"E_T", options.tangent_modulus},
                         {"G", material.shear_modulus()},
                         {"H_prime", material.plastic_modulus()},
                         {"layout", to_string(options.layout)},
                         {"tau33", args.tau33},
                         {"mass_scale", options.mass_scale},
                         {"density", args.density},
                         {"dt", args.dt},
                         {"h", args.h},
                         {"sigma_range", {options.sigma.lo, options.sigma.hi}},
                         {"ab_range", {options.a.lo, options.a.hi}},
                         {"c_range", {options.c.lo, options.c.hi}},
                         {"grid", args.grid},
                         {"slice_sigma", args.slice_sigma},
                         {"slice_grid", args.slice_grid},
                         {"grid_points", grid.points},
                         {"grid_pd", grid.pd},
                         {"grid_tests_disagree", grid.disagree},
                         {"seconds", seconds},
                         {"panels", panels}};
  open_output(dir / "monotonicity.json") << meta.dump(2) << "\n";

  std::cout << fmt::format(
      "roller monotonicity: {} grid points ({}^4), A positive definite at {} ({:.1f} %), the three "
      "tests disagree at {}; slices at sigma_pl = {} MPa; layout {}, t33 {}, E_T = {:g} MPa; "
      "{:.2f} s -> {}\n",
      grid.points, args.grid, grid.pd, 100.0 * grid.pd / static_cast<double>(grid.points), grid.disagree,
      args.slice_sigma, to_string(options.layout), args.tau33, options.tangent_modulus, seconds, dir.string());
  return render_maps(args, dir);
}

}  // namespace

Command add_monotonicity_command(CLI::App& app) {
  auto args = std::make_shared<MonotonicityArgs>();
  CLI::App* cmd = app.add_subcommand(
      "monotonicity", "maps of the positive definiteness of operator A (docs/monotonicity.md, thesis Fig. 3.1)");
  cmd->add_option("--E", args->youngs_modulus, "Young's modulus [MPa]")->check(finite_number())->capture_default_str();
  cmd->add_option("--nu", args->poisson_ratio, "Poisson's ratio")->check(finite_number())->capture_default_str();
  cmd->add_option("--Et", args->tangent_modulus, "tangent modulus E_T [MPa] (default E/3)")->check(finite_number());
  cmd->add_option("--sigma-range", args->sigma_range, "yield stress range lo,hi [MPa]")
      ->delimiter(',')
      ->expected(2)
      ->check(finite_number())
      ->capture_default_str();
  cmd->add_option("--ab-range", args->ab_range, "range lo,hi of a and b [MPa]")
      ->delimiter(',')
      ->expected(2)
      ->check(finite_number())
      ->capture_default_str();
  cmd->add_option("--c-range", args->c_range, "range lo,hi of c [MPa]")
      ->delimiter(',')
      ->expected(2)
      ->check(finite_number())
      ->capture_default_str();
  cmd->add_option("--grid", args->grid, "points per axis of the 4-D grid")
      ->check(CLI::Range(2, 201))
      ->capture_default_str();
  cmd->add_option("--slice-sigma", args->slice_sigma,
                  "yield stress of the twelve Fig. 3.1 slices [MPa] (the thesis's s = 40)")
      ->check(finite_number())
      ->capture_default_str();
  cmd->add_option("--slice-grid", args->slice_grid, "points per axis of the fine slices")
      ->check(CLI::Range(2, 2001))
      ->capture_default_str();
  cmd->add_option("--layout", args->layout,
                  "4x4 layout of C: thesis (3.4), navier (null-Lagrangian shifted), gradient (K_L)")
      ->check(CLI::IsMember({"thesis", "navier", "gradient"}))
      ->capture_default_str();
  cmd->add_option("--tau33", args->tau33,
                  "out-of-plane stress: zero (a = 3 s11, the thesis) or elastic (nu (t11 + t22))")
      ->check(CLI::IsMember({"zero", "elastic"}))
      ->capture_default_str();
  cmd->add_option("--density", args->density, "rho [t/mm^3] of the dynamic term (with --dt, --h)")
      ->check(finite_number());
  cmd->add_option("--dt", args->dt, "time step [s] of the dynamic term rho h^2/dt^2")->check(finite_number());
  cmd->add_option("--h", args->h, "inverse-estimate length h [mm] of the dynamic term")->check(finite_number());
  cmd->add_option("--out,-o", args->out, "output folder")->capture_default_str();
  cmd->add_flag("--no-plot", args->no_plot, "write the data only; print the plotting command");
  return [args]() -> int { return run_monotonicity(*args); };
}

}  // namespace roller::app
