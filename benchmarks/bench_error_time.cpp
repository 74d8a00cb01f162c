// Error against run time, penalty vs interior point (issue 7, docs/benchmarks.md): for each scene
// a sweep of mesh refinement (both backends at their default settings), of the penalty factor
// and of the Ipopt tolerance, each run timed (median of 3 repeats when a run takes < 10 s) and
// compared with a reference: for Hertz the analytic pressure, for every scene the run of the
// finest mesh with the tightest Ipopt tolerance (roller force, pressure profile, and the nodal
// fields sqrt(I2) and tau_xx at the last step, interpolated at the same material points).
// Writes one CSV row per run; benchmarks/plot_error_vs_time.py draws the plots.
//   usage: bench_error_time [--quick] [--out FILE.csv] [--scenes hertz,cattaneo,...]
// --quick: Hertz and Cattaneo on coarse meshes, one run each (the CTest sanity check).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "roller/analysis/hertz.hpp"
#include "roller/driver/simulation.hpp"
#include "roller/io/csv_table.hpp"
#include "roller/io/field_output.hpp"
#include "roller/io/scene_loader.hpp"

using namespace roller;

namespace {

constexpr Real kNaN = std::numeric_limits<Real>::quiet_NaN();

struct Plan {
  std::string scene;
  int steps = 0;                 // 0: the scene's own count
  std::vector<int> levels;       // mesh refinements (both backends, default settings)
  int sweep_level = 1;           // refinement of the penalty-factor and tolerance sweeps
  int reference_level = 1;       // finest mesh, run with the tightest Ipopt tolerance
};

struct Run {
  std::string backend, parameter;
  Real value = 0.0;
  int refine = 1;
};

// A nodal field on the structured strip grid, interpolated bilinearly at initial positions.
struct GridField {
  std::vector<Real> xs, ys;  // column x (ascending), row y (top to bottom, descending)
  std::vector<Real> values;  // node (i, j) at i * ys.size() + j
  Real at(const Vec2& p) const {
    auto locate = [](const std::vector<Real>& lines, Real v, bool ascending) {
      std::size_t k = 0;
      while (k + 2 < lines.size() && (ascending ? v > lines[k + 1] : v < lines[k + 1])) ++k;
      const Real t = (v - lines[k]) / (lines[k + 1] - lines[k]);
      return std::pair<std::size_t, Real>(k, std::clamp(t, 0.0, 1.0));
    };
    const auto [i, s] = locate(xs, p.x(), true);
    const auto [j, t] = locate(ys, p.y(), false);
    const std::size_t n = ys.size();
    auto v = [&](std::size_t a, std::size_t b) { return values[a * n + b]; };
    return (1 - s) * (1 - t) * v(i, j) + s * (1 - t) * v(i + 1, j) + (1 - s) * t * v(i, j + 1) + s * t * v(i + 1, j + 1);
  }
};

struct Result {
  bool converged = false;
  std::string message;
  Real wall = 0.0;
  int repeats = 0;
  int iterations = 0, factorizations = 0;
  Real residual = 0.0, penetration = 0.0, force = 0.0;
  Index dofs = 0;
  std::vector<PressureSample> profile;
  Real hertz_l2 = kNaN;
  GridField sqrt_i2, tau_xx;
  std::vector<Vec2> nodes;  // initial positions
};

GridField grid_field(const Mesh& mesh, const std::vector<Real>& values, int stride, int component) {
  GridField g;
  Index rows = 0;
  while (rows < mesh.n_nodes() && std::abs(mesh.nodes[rows].x() - mesh.nodes[0].x()) < 1e-12) ++rows;
  for (Index j = 0; j < rows; ++j) g.ys.push_back(mesh.nodes[j].y());
  for (Index i = 0; i * rows < mesh.n_nodes(); ++i) g.xs.push_back(mesh.nodes[i * rows].x());
  for (Index a = 0; a < mesh.n_nodes(); ++a) g.values.push_back(values[stride * a + component]);
  return g;
}

Result run_once(const Plan& plan, const Run& run) {
  std::vector<SceneOverride> o{{"mesh.refine", std::to_string(run.refine)},
                               {"contact.backend", "\"" + run.backend + "\""}};
  if (plan.steps > 0) o.push_back({"steps.count", std::to_string(plan.steps)});
  if (run.parameter == "penalty_factor") o.push_back({"contact.penalty.factor", fmt::format("{:.3e}", run.value)});
  if (run.parameter == "ipopt_tol") o.push_back({"contact.ipopt.tol", fmt::format("{:.3e}", run.value)});
  Scene scene = load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/" + plan.scene + ".toml", o);
  Result r;
  const auto t0 = std::chrono::steady_clock::now();
  Simulation sim(std::move(scene));
  r.converged = true;
  for (int step = 1; step <= sim.scene().steps.n_steps && r.converged; ++step) {
    const auto s = sim.advance_step(step);
    r.converged = s.converged;
    r.message = s.message;
    r.iterations += s.iterations;
    r.factorizations += s.factorizations;
    r.residual = s.last.residual;
    r.penetration = std::max(r.penetration, s.max_penetration);
  }
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.dofs = sim.model().n_dofs();
  if (!r.converged) return r;
  r.force = sim.roller_force().norm();
  r.profile = sim.pressure_profile();
  std::sort(r.profile.begin(), r.profile.end(), [](auto& a, auto& b) { return a.x < b.x; });
  if (plan.scene == "hertz") {
    const MaterialParams& m = sim.scene().material;
    r.hertz_l2 = compare_with_hertz(r.profile, sim.roller_force().y(), sim.scene().roller->radius,
                                    m.youngs_modulus / (1 - m.poisson_ratio * m.poisson_ratio))
                     .l2_error;
  }
  const StripFields f = strip_fields(sim.model());
  for (const VtuField& field : f.point_data) {
    if (field.name == "sqrt_I2_nodal") r.sqrt_i2 = grid_field(sim.model().mesh(), field.values, 1, 0);
    if (field.name == "stress_nodal") r.tau_xx = grid_field(sim.model().mesh(), field.values, 4, 0);
  }
  r.nodes = sim.model().mesh().nodes;
  return r;
}

Result run_timed(const Plan& plan, const Run& run, int repeats) {
  Result first = run_once(plan, run);
  std::vector<Real> walls{first.wall};
  // Median of `repeats` for short runs (machines are noisy); long runs once.
  while (first.converged && first.wall < 10.0 && static_cast<int>(walls.size()) < repeats)
    walls.push_back(run_once(plan, run).wall);
  std::sort(walls.begin(), walls.end());
  first.wall = walls[walls.size() / 2];
  first.repeats = static_cast<int>(walls.size());
  return first;
}

Real profile_l2(const std::vector<PressureSample>& p, const std::vector<PressureSample>& ref) {
  auto interp = [&](Real x) {
    if (ref.empty() || x <= ref.front().x || x >= ref.back().x) return 0.0;
    const auto hi = std::lower_bound(ref.begin(), ref.end(), x, [](auto& s, Real v) { return s.x < v; });
    const auto lo = hi - 1;
    return lo->p + (hi->p - lo->p) * (x - lo->x) / (hi->x - lo->x);
  };
  Real num = 0.0, den = 0.0;
  for (const auto& s : p) {
    const Real q = interp(s.x);
    num += (s.p - q) * (s.p - q);
    den += q * q;
  }
  return den > 0.0 ? std::sqrt(num / den) : kNaN;
}

Real field_l2(const Result& r, const GridField& mine, const GridField& ref) {
  Real num = 0.0, den = 0.0;
  for (std::size_t a = 0; a < r.nodes.size(); ++a) {
    const Real q = ref.at(r.nodes[a]);
    num += (mine.values[a] - q) * (mine.values[a] - q);
    den += q * q;
  }
  return den > 0.0 ? std::sqrt(num / den) : kNaN;
}

std::vector<Plan> plans(bool quick) {
  if (quick) return {{"hertz", 0, {1, 2}, 1, 3}, {"cattaneo", 0, {1}, 1, 2}};
  // The reference is one level finer than the finest swept mesh, so that every swept run has a
  // discretisation error to show (a reference equal to a swept level would give that level ~0).
  return {{"hertz", 0, {1, 2, 3, 4}, 2, 5},
          {"cattaneo", 0, {1, 2, 3, 4}, 2, 5},
          {"z1_outf05", 0, {1, 2, 3, 4}, 2, 5},
          {"z3_data01", 24, {1, 2, 3, 4}, 2, 5},
          {"z4_v25", 0, {1, 2, 3, 4}, 2, 5}};
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string out = "out/error_vs_time/error_vs_time.csv";
  std::vector<std::string> only;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") quick = true;
    else if (a == "--out" && i + 1 < argc) out = argv[++i];
    else if (a == "--scenes" && i + 1 < argc) {
      std::stringstream s(argv[++i]);
      for (std::string n; std::getline(s, n, ',');) only.push_back(n);
    } else {
      std::fprintf(stderr, "usage: bench_error_time [--quick] [--out FILE.csv] [--scenes a,b]\n");
      return 2;
    }
  }
  std::filesystem::create_directories(std::filesystem::path(out).parent_path());
  CsvTable csv(out, {"scene", "backend", "parameter", "value", "refine", "dofs", "converged", "wall_s", "repeats",
                     "iterations", "factorizations", "residual", "max_penetration", "force_error",
                     "pressure_l2_error", "sqrt_i2_error", "tau_xx_error", "reference"});
  const std::vector<Real> factors = quick ? std::vector<Real>{1e1, 1e3, 1e5}
                                          : std::vector<Real>{1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8};
  const std::vector<Real> tols = quick ? std::vector<Real>{1e-4, 1e-8} : std::vector<Real>{1e-4, 1e-6, 1e-8, 1e-10};
  for (const Plan& plan : plans(quick)) {
    if (!only.empty() && std::find(only.begin(), only.end(), plan.scene) == only.end()) continue;
    const Real tightest = *std::min_element(tols.begin(), tols.end());
    std::fprintf(stderr, "%s: reference (ipopt, refine %d, tol %.0e)\n", plan.scene.c_str(), plan.reference_level,
                 tightest);
    const Result ref = run_once(plan, {"ipopt", "ipopt_tol", tightest, plan.reference_level});
    if (!ref.converged) {
      std::fprintf(stderr, "%s: the reference run failed (%s); scene skipped\n", plan.scene.c_str(),
                   ref.message.c_str());
      continue;
    }
    std::vector<Run> runs;
    for (int level : plan.levels)
      for (const char* b : {"penalty", "ipopt"}) runs.push_back({b, "refine", static_cast<Real>(level), level});
    for (Real f : factors) runs.push_back({"penalty", "penalty_factor", f, plan.sweep_level});
    for (Real t : tols) runs.push_back({"ipopt", "ipopt_tol", t, plan.sweep_level});
    for (const Run& run : runs) {
      const Result r = run_timed(plan, run, quick ? 1 : 3);
      std::fprintf(stderr, "%s %s %s=%g refine %d: %s, %.3f s\n", plan.scene.c_str(), run.backend.c_str(),
                   run.parameter.c_str(), run.value, run.refine, r.converged ? "converged" : "FAILED", r.wall);
      const bool ok = r.converged;
      const Real pressure = plan.scene == "hertz" ? r.hertz_l2 : (ok ? profile_l2(r.profile, ref.profile) : kNaN);
      csv.add_row({plan.scene, run.backend, run.parameter, run.value, static_cast<Index>(run.refine), r.dofs,
                   static_cast<Index>(ok ? 1 : 0), r.wall, static_cast<Index>(r.repeats),
                   static_cast<Index>(r.iterations), static_cast<Index>(r.factorizations), ok ? r.residual : kNaN,
                   ok ? r.penetration : kNaN, ok ? std::abs(r.force - ref.force) / ref.force : kNaN,
                   ok ? pressure : kNaN, ok ? field_l2(r, r.sqrt_i2, ref.sqrt_i2) : kNaN,
                   ok ? field_l2(r, r.tau_xx, ref.tau_xx) : kNaN,
                   std::string(plan.scene == "hertz" ? "pressure: analytic; others: ipopt refine " +
                                                           std::to_string(plan.reference_level)
                                                     : "ipopt refine " + std::to_string(plan.reference_level))});
    }
  }
  return 0;
}
