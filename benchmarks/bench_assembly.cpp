// Assembly throughput (elements per second for energy + gradient + Hessian) and the time of one
// sparse LDL^T factorisation (Eigen SimplicialLDLT, AMD ordering) of the tangent, on Q4 B-bar
// plastic strips from ~1e3 to ~1e6 dofs. Medians of repeats, printed as a Markdown table.
//   usage: bench_assembly [max_dofs=1e6] [repeats=5]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <Eigen/SparseCholesky>

#include "roller/assembly/strip_model.hpp"
#include "roller/mesh/strip_mesher.hpp"

using namespace roller;
using Clock = std::chrono::steady_clock;

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

template <class F>
double time_of(F&& f) {
  const auto t0 = Clock::now();
  f();
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  const double max_dofs = argc > 1 ? std::atof(argv[1]) : 1e6;
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 5;
  MaterialParams mat;
  mat.plastic = true;
  mat.yield_stress = 50.0;
  mat.tangent_modulus = 0.07 * mat.youngs_modulus;

  std::printf("| dofs | elements | assembly [s] | elements/s | factorisation [s] | nnz(K) |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|\n");
  for (double target = 1e3; target <= max_dofs * 1.01; target *= 10.0) {
    // Strip 4:1 (nx = 4 ny): dofs = 2 (nx+1)(ny+1).
    const int ny = std::max(1, static_cast<int>(std::lround(std::sqrt(target / 8.0))) - 1);
    StripMeshSpec spec;
    spec.element = ElementType::Q4;
    spec.length = 400.0;
    spec.height = 100.0;
    spec.nx = 4 * (ny + 1) - 1;
    spec.ny = ny;
    StripModel model(make_strip_mesh(spec), mat, ElementOptions{Kinematics::Finite, Q4Formulation::BBar});
    std::vector<bool> fixed(model.n_dofs(), false);
    for (Index a : model.mesh().node_set("bottom")) fixed[2 * a + 1] = true;
    fixed[2 * model.mesh().node_set("bottom_left").front()] = true;
    model.set_dof_map(DofMap(fixed));
    // A compression that makes part of the strip yield.
    VecX u(model.n_dofs());
    for (Index a = 0; a < model.mesh().n_nodes(); ++a) {
      const Vec2& x = model.mesh().nodes[a];
      u(2 * a) = 1e-4 * x.x();
      u(2 * a + 1) = fixed[2 * a + 1] ? 0.0 : -2e-3 * x.y() * (1.0 + 0.001 * x.x());
    }
    VecX g;
    SparseMatrix k;
    std::vector<double> t_asm, t_fact;
    const int reps = model.n_dofs() > 2e5 ? std::max(1, repeats / 2) : repeats;
    for (int r = 0; r < reps; ++r) t_asm.push_back(time_of([&] { model.evaluate(u, &g, &k); }));
    for (int r = 0; r < reps; ++r) {
      t_fact.push_back(time_of([&] {
        Eigen::SimplicialLDLT<SparseMatrix> ldlt;
        ldlt.compute(k);
        if (ldlt.info() != Eigen::Success) std::printf("factorisation failed\n");
      }));
    }
    const double ta = median(t_asm), tf = median(t_fact);
    std::printf("| %ld | %ld | %.4f | %.3g | %.4f | %ld |\n", static_cast<long>(model.n_dofs()),
                static_cast<long>(model.mesh().n_elements()), ta, model.mesh().n_elements() / ta, tf,
                static_cast<long>(k.nonZeros()));
    std::fflush(stdout);
  }
  return 0;
}
