// Time of one sparse factorisation of the strip's tangent K (free dofs) by MUMPS (LDL^T,
// analysis + factorisation), the unit of the scaling study (`rollerpy bench-scaling`). Median of
// `repeats`. Prints one line: dofs free_dofs nnz_lower seconds mumps_memory_mb.
//   usage: bench_factorize SCENE.toml [repeats=3] [key=value ...]   (scene overrides)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "roller/driver/simulation.hpp"
#include "roller/io/scene_loader.hpp"
#include "roller/solver/mumps_factorization.hpp"

using namespace roller;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_factorize SCENE.toml [repeats=3] [key=value ...]\n");
    return 2;
  }
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 3;
  std::vector<SceneOverride> overrides;
  for (int i = 3; i < argc; ++i) overrides.push_back(parse_override(argv[i]));
  Simulation sim(load_scene(argv[1], overrides));
  SparseMatrix k;
  sim.model().evaluate(VecX::Zero(sim.model().n_dofs()), nullptr, &k);
  std::vector<double> times;
  Index memory_mb = 0;
  for (int r = 0; r < repeats; ++r) {
    MumpsSolver ldlt(MumpsSolver::Symmetry::Symmetric, sim.scene().newton.linear);  // [linear_solver]
    const auto t0 = std::chrono::steady_clock::now();
    if (!ldlt.factorize(k)) {
      std::fprintf(stderr, "%s\n", ldlt.message().c_str());
      return 1;
    }
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    memory_mb = ldlt.memory_mb();
  }
  std::sort(times.begin(), times.end());
  std::printf("%ld %ld %ld %.6f %ld\n", static_cast<long>(sim.model().n_dofs()), static_cast<long>(k.rows()),
              static_cast<long>((k.nonZeros() + k.rows()) / 2), times[times.size() / 2], static_cast<long>(memory_mb));
  return 0;
}
