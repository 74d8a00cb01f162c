// Error against run time, penalty vs interior point (docs/benchmarks.md): for each scene
// a sweep of mesh refinement (both backends at their default settings), of the penalty factor
// and of the Ipopt tolerance, each run timed (median of 3 repeats when a run takes < 10 s) and
// compared with a reference run (ipopt, one mesh level finer than the finest swept mesh, the
// tightest swept tolerance; for Hertz the pressure profile is compared with the analytic
// solution instead). Compared: the roller force and the pressure profile at the scene's load
// step (the last step, except Z3: step 47, mid-pass), and the nodal fields sqrt(I2) and tau_xx
// at the final step, interpolated at the same material points. The final step is under load in
// every scene except Z3 (whose own lift-off leaves the strip free at step 73: residual fields);
// the final_state column says which.
// Writes one CSV row per run (the reference included), flushed at once; every run is guarded:
// an exception, a failed step or the per-run wall-clock budget ends that run only (status
// error / failed / timeout) and the study goes on. `rollerpy bench-error-vs-time` drives this
// program and draws the plots.
//   usage: bench_error_time [--quick] [--out FILE.csv] [--scenes hertz,cattaneo,...]
//                           [--refine-max N] [--max-run-seconds S] [--max-reference-seconds S]
// --quick: Hertz and Cattaneo on coarse meshes, one run each (the CTest sanity check).
// --refine-max N: no mesh above refine N (sweeps and reference; a capped reference is noted).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
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
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

struct Plan {
  std::string scene;
  int steps = 0;            // 0: the scene's own count
  int load_step = 0;        // step of the force and pressure comparison; 0: the last step
  std::vector<int> levels;  // mesh refinements (both backends, default settings)
  int sweep_level = 1;      // refinement of the penalty-factor and tolerance sweeps
  int reference_level = 1;  // finest mesh, run with the tightest Ipopt tolerance
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
    return (1 - s) * (1 - t) * v(i, j) + s * (1 - t) * v(i + 1, j) + (1 - s) * t * v(i, j + 1) +
           s * t * v(i + 1, j + 1);
  }
  bool empty() const { return values.empty(); }
};

struct Result {
  // converged: all steps done; failed: a step did not converge; timeout: stopped between steps
  // after the wall-clock budget; error: an exception (bad input, numerical, ...); skipped: not
  // run (a cheaper run of the same sweep timed out).
  std::string status = "error";
  std::string message;
  Real wall = 0.0;  // median over the repeats (converged) or of the one run
  Real cost = 0.0;  // all time spent on this row: repeats, scene loading, post-processing
  int repeats = 0;
  int steps = 0, steps_done = 0, load_step = 0;
  int iterations = 0, factorizations = 0;
  Real residual_max = kNaN, residual_last = kNaN, penetration = 0.0;
  Index dofs = 0;
  // At the load step:
  Real force = kNaN;
  std::vector<PressureSample> profile;
  Real hertz_l2 = kNaN;
  // At the final step:
  GridField sqrt_i2, tau_xx;
  Real final_force = kNaN;
  Index final_contact_nodes = -1;
  std::vector<Vec2> nodes;  // initial positions
  bool converged() const { return status == "converged"; }
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

std::vector<SceneOverride> overrides(const Plan& plan, const Run& run) {
  std::vector<SceneOverride> o{{"mesh.refine", std::to_string(run.refine)},
                               {"contact.backend", "\"" + run.backend + "\""}};
  if (plan.steps > 0) {
    // Scenes may keep states at steps beyond a shortened count (Z3: save_states = [23, 47, 71]),
    // which the loader rejects; this program writes no state files anyway.
    o.push_back({"steps.count", std::to_string(plan.steps)});
    o.push_back({"output.save_states", "[]"});
  }
  if (run.parameter == "penalty_factor") o.push_back({"contact.penalty.factor", fmt::format("{:.3e}", run.value)});
  if (run.parameter == "ipopt_tol" || run.parameter == "reference")
    o.push_back({"contact.ipopt.tol", fmt::format("{:.3e}", run.value)});
  return o;
}

// One run, stepped here so that the budget can stop it between steps. Never throws.
Result run_once(const Plan& plan, const Run& run, double budget_s) {
  Result r;
  const auto t_start = Clock::now();
  bool timing = false;
  auto t0 = t_start;
  try {
    Scene scene =
        load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/" + plan.scene + ".toml", overrides(plan, run));
    t0 = Clock::now();
    timing = true;
    Simulation sim(std::move(scene));
    r.dofs = sim.model().n_dofs();
    r.steps = sim.scene().steps.n_steps;
    r.load_step = plan.load_step > 0 ? std::min(plan.load_step, r.steps) : r.steps;
    r.status = "converged";
    for (int step = 1; step <= r.steps; ++step) {
      const auto s = sim.advance_step(step);
      r.iterations += s.counters.iterations;
      r.factorizations += s.counters.factorizations;
      r.penetration = std::max(r.penetration, s.max_penetration);
      if (!s.converged()) {
        r.status = "failed";
        r.message = s.message;
        break;
      }
      r.steps_done = step;
      // Residual of the step's (last) increment; the maximum over all steps of the run.
      r.residual_last = s.last.residual;
      if (!(r.residual_max >= s.last.residual)) r.residual_max = s.last.residual;
      if (step == r.load_step) {
        r.force = force_on_roller(sim.state().contact).norm();
        r.profile = pressure_profile(sim.state().contact, sim.state().pose);
        std::sort(r.profile.begin(), r.profile.end(), [](auto& a, auto& b) { return a.x < b.x; });
        if (plan.scene == "hertz") {
          const MaterialParams& m = sim.scene().material;
          r.hertz_l2 =
              compare_with_hertz(r.profile, force_on_roller(sim.state().contact).y(), sim.scene().roller->radius,
                                 m.youngs_modulus / (1 - m.poisson_ratio * m.poisson_ratio))
                  .l2_error;
        }
      }
      const double elapsed = seconds_since(t0);
      if (step < r.steps && elapsed > budget_s) {
        r.status = "timeout";
        r.message =
            fmt::format("stopped after step {} of {}: {:.3g} s > budget {:g} s", step, r.steps, elapsed, budget_s);
        break;
      }
    }
    r.wall = seconds_since(t0);
    timing = false;
    if (r.converged()) {
      r.final_force = force_on_roller(sim.state().contact).norm();
      r.final_contact_nodes = 0;
      for (const NodeContactRecord& c : sim.state().contact)
        if (c.contact.status != ContactStatus::Open) ++r.final_contact_nodes;
      const StripFields f = strip_fields(sim.model(), VecX::Zero(sim.model().n_dofs()));
      for (const VtuField& field : f.point_data) {
        if (field.name == "sqrt_I2_nodal") r.sqrt_i2 = grid_field(sim.model().mesh(), field.values, 1, 0);
        if (field.name == "stress_nodal") r.tau_xx = grid_field(sim.model().mesh(), field.values, 4, 0);
      }
      r.nodes = sim.model().mesh().nodes;
    }
  } catch (const std::exception& e) {
    if (timing) r.wall = seconds_since(t0);
    r.status = "error";
    r.message = e.what();
  } catch (...) {
    if (timing) r.wall = seconds_since(t0);
    r.status = "error";
    r.message = "unknown exception (not a std::exception)";
  }
  r.cost = seconds_since(t_start);
  return r;
}

Result run_timed(const Plan& plan, const Run& run, int repeats, double budget_s) {
  Result first = run_once(plan, run, budget_s);
  std::vector<Real> walls{first.wall};
  Real cost = first.cost;
  // Median of `repeats` for short runs (machines are noisy); long runs once. A repeat that
  // does not converge (it should not: runs are deterministic) is not counted.
  while (first.converged() && first.wall < 10.0 && static_cast<int>(walls.size()) < repeats) {
    const Result again = run_once(plan, run, budget_s);
    cost += again.cost;
    if (!again.converged()) break;
    walls.push_back(again.wall);
  }
  std::sort(walls.begin(), walls.end());
  first.wall = walls[walls.size() / 2];
  first.repeats = static_cast<int>(walls.size());
  first.cost = cost;
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
  if (mine.empty() || ref.empty() || mine.values.size() != r.nodes.size()) return kNaN;
  Real num = 0.0, den = 0.0;
  for (std::size_t a = 0; a < r.nodes.size(); ++a) {
    const Real q = ref.at(r.nodes[a]);
    num += (mine.values[a] - q) * (mine.values[a] - q);
    den += q * q;
  }
  return den > 0.0 ? std::sqrt(num / den) : kNaN;
}

std::vector<Plan> plans(bool quick) {
  if (quick) return {{"hertz", 0, 0, {1, 2}, 1, 3}, {"cattaneo", 0, 0, {1}, 1, 2}};
  // The reference is one level finer than the finest swept mesh, so that every swept run has a
  // discretisation error to show (a reference equal to a swept level would give that level ~0).
  // Z3 runs its whole pass (73 steps): its own lift-off (steps 65-73) leaves the strip free at
  // the end, so its final fields are residual; force and pressure are compared at step 47 (the
  // roller mid-strip, under load).
  return {{"hertz", 0, 0, {1, 2, 3, 4}, 2, 5},
          {"cattaneo", 0, 0, {1, 2, 3, 4}, 2, 5},
          {"z1_outf05", 0, 0, {1, 2, 3, 4}, 2, 5},
          {"z3_data01", 0, 47, {1, 2, 3, 4}, 2, 5},
          {"z4_v25", 0, 0, {1, 2, 3, 4}, 2, 5}};
}

// Columns of the CSV (`rollerpy bench-error-vs-time` reads them by name).
const std::vector<std::string> kColumns = {"scene",
                                           "backend",
                                           "parameter",
                                           "value",
                                           "refine",
                                           "dofs",
                                           "status",
                                           "converged",
                                           "message",
                                           "wall_s",
                                           "repeats",
                                           "cost_s",
                                           "steps",
                                           "steps_done",
                                           "iterations",
                                           "factorizations",
                                           "residual_max",
                                           "residual_last",
                                           "max_penetration",
                                           "load_step",
                                           "force_error",
                                           "pressure_l2_error",
                                           "pressure_reference",
                                           "final_roller_force",
                                           "final_contact_nodes",
                                           "final_state",
                                           "final_sqrt_i2_error",
                                           "final_tau_xx_error",
                                           "reference_backend",
                                           "reference_refine",
                                           "reference_tol",
                                           "errors_against"};

const char* usage =
    "usage: bench_error_time [--quick] [--out FILE.csv] [--scenes a,b] [--refine-max N]\n"
    "                        [--max-run-seconds S] [--max-reference-seconds S]\n";

struct Options {
  bool quick = false;
  std::string out = "out/error_vs_time/error_vs_time.csv";
  std::vector<std::string> only;
  int refine_max = 0;
  double max_run_s = 120.0, max_reference_s = 600.0;
};

// The command line, or nullopt (after the usage) when it is not understood.
std::optional<Options> parse_options(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--quick")
      o.quick = true;
    else if (a == "--out" && has_value)
      o.out = argv[++i];
    else if (a == "--scenes" && has_value) {
      std::stringstream s(argv[++i]);
      for (std::string n; std::getline(s, n, ',');)
        if (!n.empty()) o.only.push_back(n);
    } else if (a == "--refine-max" && has_value)
      o.refine_max = std::atoi(argv[++i]);
    else if (a == "--max-run-seconds" && has_value)
      o.max_run_s = std::atof(argv[++i]);
    else if (a == "--max-reference-seconds" && has_value)
      o.max_reference_s = std::atof(argv[++i]);
    else {
      std::fputs(usage, stderr);
      return std::nullopt;
    }
  }
  if (o.refine_max < 0 || !(o.max_run_s > 0) || !(o.max_reference_s > 0)) {
    std::fputs(usage, stderr);
    return std::nullopt;
  }
  return o;
}

// The plans of the chosen scenes, their meshes capped by --refine-max.
std::vector<Plan> select_plans(const Options& o) {
  std::vector<Plan> selected;
  for (const Plan& plan : plans(o.quick))
    if (o.only.empty() || std::find(o.only.begin(), o.only.end(), plan.scene) != o.only.end()) selected.push_back(plan);
  for (const std::string& name : o.only)
    if (std::none_of(selected.begin(), selected.end(), [&](const Plan& p) { return p.scene == name; }))
      std::fprintf(stderr, "warning: scene '%s' is not in the %s plan; ignored\n", name.c_str(),
                   o.quick ? "quick" : "default");
  auto cap = [&](int level) { return o.refine_max > 0 ? std::min(level, o.refine_max) : level; };
  for (Plan& plan : selected) {
    std::vector<int> levels;
    for (int l : plan.levels)
      if (o.refine_max <= 0 || l <= o.refine_max) levels.push_back(l);
    plan.levels = levels;
    plan.sweep_level = cap(plan.sweep_level);
    plan.reference_level = cap(plan.reference_level);
  }
  return selected;
}

// One scene's sweeps against its reference run, written to `csv` as the runs end.
class SceneSweep {
 public:
  SceneSweep(const Plan& plan, const Options& o, const std::vector<Real>& factors, const std::vector<Real>& tols,
             CsvTable& csv)
      : plan_(plan), options_(o), factors_(factors), tols_(tols), csv_(csv) {
    tightest_ = *std::min_element(tols.begin(), tols.end());
  }

  void run() {
    const int finest_swept = std::max(plan_.sweep_level, plan_.levels.empty() ? 0 : plan_.levels.back());
    const std::string ref_name = fmt::format(
        "reference run (ipopt refine {} tol {:.0e}{})", plan_.reference_level, tightest_,
        plan_.reference_level <= finest_swept ? "; capped by --refine-max: no finer than the swept meshes" : "");
    against_ = plan_.scene == "hertz"
                   ? "pressure_l2_error: analytic Hertz solution at the measured load (load step); force_error and "
                     "final_* fields: " +
                         ref_name
                   : "all errors: " + ref_name;
    std::fprintf(stderr, "%s: reference (ipopt, refine %d, tol %.0e)\n", plan_.scene.c_str(), plan_.reference_level,
                 tightest_);
    const Run ref_run{"ipopt", "reference", tightest_, plan_.reference_level};
    ref_ = run_once(plan_, ref_run, options_.max_reference_s);
    Result shown = ref_;
    shown.repeats = 1;
    row(ref_run, shown, true);
    std::fprintf(stderr, "%s: reference %s, %.2f s%s%s\n", plan_.scene.c_str(), ref_.status.c_str(), ref_.wall,
                 ref_.message.empty() ? "" : ": ", ref_.message.c_str());
    if (!ref_.converged()) {
      std::fprintf(stderr, "%s: no reference, scene skipped\n", plan_.scene.c_str());
      return;
    }
    std::fprintf(stderr, "%s: final step %s (reference: %lld closed contact nodes, roller force %.4g N/mm)\n",
                 plan_.scene.c_str(), contact_state(ref_).c_str(), static_cast<long long>(ref_.final_contact_nodes),
                 ref_.final_force);
    sweeps();
  }

 private:
  static std::string contact_state(const Result& r) {
    return r.final_contact_nodes < 0 ? "" : (r.final_contact_nodes > 0 ? "loaded" : "unloaded");
  }

  void sweeps() {
    const int repeats = options_.quick ? 1 : 3;
    std::vector<Run> runs;
    for (int level : plan_.levels)
      for (const char* b : {"penalty", "ipopt"}) runs.push_back({b, "refine", static_cast<Real>(level), level});
    for (Real f : factors_) runs.push_back({"penalty", "penalty_factor", f, plan_.sweep_level});
    for (Real t : tols_) runs.push_back({"ipopt", "ipopt_tol", t, plan_.sweep_level});
    std::map<std::string, std::string> stopped;  // sweep (backend/parameter) -> why it stopped
    for (const Run& run : runs) {
      const std::string sweep = run.backend + "/" + run.parameter;
      Result r;
      if (stopped.count(sweep)) {
        r.status = "skipped";
        r.message = stopped[sweep];
      } else {
        r = run_timed(plan_, run, repeats, options_.max_run_s);
        // Only where cost surely grows along the sweep: finer meshes, stiffer penalties (a looser
        // Ipopt tolerance is not always cheaper: Z3 ran longer at 1e-4 than at 1e-8).
        if (r.status == "timeout" && run.parameter != "ipopt_tol")
          stopped[sweep] =
              fmt::format("not run: the cheaper {}={:g} (refine {}) timed out", run.parameter, run.value, run.refine);
      }
      std::fprintf(stderr, "%s %s %s=%g refine %d: %s, %.3f s%s%s\n", plan_.scene.c_str(), run.backend.c_str(),
                   run.parameter.c_str(), run.value, run.refine, r.status.c_str(), r.wall,
                   r.message.empty() ? "" : ": ", r.message.c_str());
      row(run, r, false);
    }
  }

  void row(const Run& run, const Result& r, bool is_reference) {
    const bool ok = r.converged() && ref_.converged();
    const bool hertz = plan_.scene == "hertz";
    const Real pressure = !r.converged()          ? kNaN
                          : hertz                 ? r.hertz_l2
                          : (ok && !is_reference) ? profile_l2(r.profile, ref_.profile)
                                                  : kNaN;
    const bool cmp = ok && !is_reference;
    const Real force_error = cmp && ref_.force > 0.0 ? std::abs(r.force - ref_.force) / ref_.force : kNaN;
    csv_.add_row({plan_.scene,
                  run.backend,
                  run.parameter,
                  run.value,
                  static_cast<Index>(run.refine),
                  r.dofs,
                  r.status,
                  static_cast<Index>(r.converged() ? 1 : 0),
                  r.message,
                  r.wall,
                  static_cast<Index>(r.repeats),
                  r.cost,
                  static_cast<Index>(r.steps),
                  static_cast<Index>(r.steps_done),
                  static_cast<Index>(r.iterations),
                  static_cast<Index>(r.factorizations),
                  r.residual_max,
                  r.residual_last,
                  r.converged() ? r.penetration : kNaN,
                  static_cast<Index>(r.load_step),
                  force_error,
                  pressure,
                  std::string(hertz ? "analytic Hertz" : "reference run"),
                  r.final_force,
                  r.final_contact_nodes,
                  contact_state(r),
                  cmp ? field_l2(r, r.sqrt_i2, ref_.sqrt_i2) : kNaN,
                  cmp ? field_l2(r, r.tau_xx, ref_.tau_xx) : kNaN,
                  std::string("ipopt"),
                  static_cast<Index>(plan_.reference_level),
                  tightest_,
                  against_});
  }

  const Plan& plan_;
  const Options& options_;
  const std::vector<Real>& factors_;
  const std::vector<Real>& tols_;
  CsvTable& csv_;
  Real tightest_ = 0.0;
  std::string against_;
  Result ref_;
};

}  // namespace

int main(int argc, char** argv) {
  const std::optional<Options> parsed = parse_options(argc, argv);
  if (!parsed) return 2;
  const Options& o = *parsed;
  const std::vector<Real> factors =
      o.quick ? std::vector<Real>{1e1, 1e3, 1e5} : std::vector<Real>{1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8};
  // Ordered from cheap to expensive within each sweep, so that once a mesh or penalty-factor run
  // times out, the rest of that sweep is skipped.
  const std::vector<Real> tols = o.quick ? std::vector<Real>{1e-4, 1e-8} : std::vector<Real>{1e-4, 1e-6, 1e-8, 1e-10};
  const std::vector<Plan> selected = select_plans(o);

  const std::filesystem::path out_path(o.out);
  if (out_path.has_parent_path()) std::filesystem::create_directories(out_path.parent_path());
  CsvTable csv(out_path, kColumns);
  std::fprintf(stderr, "plan: budget %g s per run (stopped between steps), %g s per reference run\n", o.max_run_s,
               o.max_reference_s);
  const Real tightest = *std::min_element(tols.begin(), tols.end());
  for (const Plan& plan : selected) {
    const std::size_t n = 2 * plan.levels.size() + factors.size() + tols.size();
    std::fprintf(stderr, "plan: %s: reference ipopt refine %d tol %.0e, %zu runs (worst case %.0f s)\n",
                 plan.scene.c_str(), plan.reference_level, tightest, n,
                 o.max_reference_s + n * std::max(o.max_run_s, 30.0));
  }
  for (const Plan& plan : selected) SceneSweep(plan, o, factors, tols, csv).run();
  return 0;
}
