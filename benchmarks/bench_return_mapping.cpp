// Cost of one material update (return mapping, stress, consistent tangent, energy) per
// integration point for each hardening law, against the isotropic J2 law. Each law updates a
// set of committed plastic states (reached by a non-proportional path) by a plastic strain
// increment, the way the element kernel calls it; median of `repeats` sweeps. Prints one line
// per law: name, nanoseconds per update, ratio to isotropic (docs/benchmarks.md).
//   usage: bench_return_mapping [repeats=7] [points=200000] [law]
// With a law's name only that law runs, its ratio against isotropic then omitted (for a profiler).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "roller/material/j2_plasticity.hpp"

using namespace roller;

namespace {

MaterialParams steel() {
  MaterialParams p;
  p.youngs_modulus = 2.1e5;
  p.poisson_ratio = 0.3;
  p.plastic = true;
  p.yield_stress = 300.0;
  return p;
}

std::vector<std::pair<std::string, MaterialParams>> laws() {
  MaterialParams iso = steel();
  iso.tangent_modulus = 4200.0;
  MaterialParams kin = iso;
  kin.hardening = Hardening::Kinematic;
  MaterialParams af = steel();
  af.hardening = Hardening::Chaboche;
  af.n_chaboche = 1;
  af.chaboche[0] = {3.0e4, 150.0};
  MaterialParams ch4 = steel();
  ch4.hardening = Hardening::Chaboche;
  ch4.n_chaboche = 4;
  ch4.chaboche = {BackStressLaw{1.5e5, 2000.0}, BackStressLaw{4.0e4, 400.0}, BackStressLaw{1.0e4, 60.0},
                  BackStressLaw{2.0e3, 0.0}};
  MaterialParams ch4v = ch4;
  ch4v.voce_saturation = 80.0;
  ch4v.voce_rate = 15.0;
  return {{"isotropic", iso},
          {"kinematic", kin},
          {"armstrong_frederick", af},
          {"chaboche4", ch4},
          {"chaboche4_voce", ch4v}};
}

// Median seconds of one sweep of update_material over the states.
double sweep_seconds(const MaterialParams& p, const std::vector<MaterialState>& states, const Vec4& de, int repeats,
                     double& checksum) {
  std::vector<double> times;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    for (const MaterialState& s : states) checksum += update_material(p, de, s).stress(0);
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::atoi(argv[1]) : 7;
  const int points = argc > 2 ? std::atoi(argv[2]) : 200000;
  const std::string only = argc > 3 ? argv[3] : "";
  double checksum = 0.0;
  double iso_ns = 0.0;
  std::printf("law ns_per_update ratio_to_isotropic\n");
  for (const auto& [name, p] : laws()) {
    if (!only.empty() && name != only) continue;
    const Real ey = p.yield_stress / p.youngs_modulus;
    // Committed states on a non-proportional plastic path; the increment loads them further.
    std::vector<MaterialState> states(static_cast<std::size_t>(points));
    MaterialState s = initial_state(p);
    s = update_material(p, ey * Vec4(2.0, -0.5, 0.0, 0.0), s).trial;
    s = update_material(p, ey * Vec4(0.3, 0.2, 0.0, 2.5), s).trial;
    std::fill(states.begin(), states.end(), s);
    const Vec4 de = ey * Vec4(0.4, -0.1, 0.0, 0.6);
    if (!update_material(p, de, s).yielded) {
      std::fprintf(stderr, "%s: the increment is elastic; the benchmark needs a plastic one\n", name.c_str());
      return 1;
    }
    const double ns = 1e9 * sweep_seconds(p, states, de, repeats, checksum) / points;
    if (name == "isotropic") iso_ns = ns;
    std::printf("%s %.1f %.2f\n", name.c_str(), ns, iso_ns > 0.0 ? ns / iso_ns : 0.0);
  }
  std::fprintf(stderr, "checksum %g\n", checksum);
  return 0;
}
