// Hertz line contact at several mesh levels and contact backends: half-width, peak-pressure and
// pressure-profile L2 errors (nodal samples, and against the work-equivalent average: analysis/hertz.hpp)
// against the analytic solution, with wall time (median of repeats).
// Printed as a Markdown table.
//   usage: bench_hertz [max_refine=3] [repeats=3] [backends=penalty[,ipopt]] [min_refine=1]
//                      [scene=problems/hertz.toml] [key=value ...]   (scene overrides)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "roller/analysis/hertz.hpp"
#include "roller/driver/simulation.hpp"
#include "roller/io/scene_loader.hpp"

using namespace roller;

int main(int argc, char** argv) {
  const int max_refine = argc > 1 ? std::atoi(argv[1]) : 3;
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 3;
  std::vector<std::string> backends;
  std::stringstream list(argc > 3 ? argv[3] : "penalty");
  for (std::string b; std::getline(list, b, ',');) backends.push_back(b);
  const int min_refine = argc > 4 ? std::max(1, std::atoi(argv[4])) : 1;
  const std::string scene_path = argc > 5 ? argv[5] : std::string(ROLLER_SOURCE_DIR) + "/problems/hertz.toml";
  std::vector<SceneOverride> extra;
  for (int i = 6; i < argc; ++i) extra.push_back(parse_override(argv[i]));

  std::printf(
      "| backend | refine | dofs | contact nodes | P [N/mm] | a error | p0 error | L2 error | "
      "L2 error (averaged) | max penetration [mm] | iterations | wall [s] |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& backend : backends) {
    for (int refine = min_refine; refine <= max_refine; ++refine) {
      std::vector<double> walls;
      HertzComparison c;
      Index dofs = 0, n_contact = 0;
      int iterations = 0;
      Real load = 0.0, penetration = 0.0;
      bool ok = true;
      for (int r = 0; r < repeats && ok; ++r) {
        std::vector<SceneOverride> overrides{{"mesh.refine", std::to_string(refine)},
                                             {"contact.backend", "\"" + backend + "\""}};
        overrides.insert(overrides.end(), extra.begin(), extra.end());
        Scene scene = load_scene(scene_path, overrides);
        const auto t0 = std::chrono::steady_clock::now();
        Simulation sim(std::move(scene));
        iterations = 0;
        penetration = 0.0;
        for (int step = 1; step <= sim.scene().steps.n_steps && ok; ++step) {
          const auto res = sim.advance_step(step);
          ok = res.converged();
          iterations += res.counters.iterations;
          penetration = std::max(penetration, res.max_penetration);
        }
        walls.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        n_contact = 0;
        for (const auto& rec : sim.state().contact) n_contact += rec.contact.status != ContactStatus::Open ? 1 : 0;
        const MaterialParams& m = sim.scene().material;
        load = force_on_roller(sim.state().contact).y();
        c = compare_with_hertz(pressure_profile(sim.state().contact, sim.state().pose), load,
                               sim.scene().roller->radius, m.youngs_modulus / (1 - m.poisson_ratio * m.poisson_ratio));
        dofs = sim.model().n_dofs();
      }
      if (!ok) {
        std::printf("| %s | %d | %ld | — | — | — | — | — | — | — | — | failed |\n", backend.c_str(), refine,
                    static_cast<long>(dofs));
        continue;
      }
      std::sort(walls.begin(), walls.end());
      std::printf("| %s | %d | %ld | %ld | %.1f | %+.2e | %+.2e | %.2e | %.2e | %.2e | %d | %.3f |\n", backend.c_str(),
                  refine, static_cast<long>(dofs), static_cast<long>(n_contact), load, c.half_width_error, c.peak_error,
                  c.l2_error, c.l2_error_averaged, penetration, iterations, walls[walls.size() / 2]);
      std::fflush(stdout);
    }
  }
  return 0;
}
