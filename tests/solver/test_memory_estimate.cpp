// A mesh too large for the machine stops before it is built, with the remedies named.
#include <catch2/catch.hpp>

#include "roller/core/error.hpp"
#include "roller/solver/memory_estimate.hpp"

using namespace roller;
using Catch::Contains;

namespace {

LinearSolverOptions factors_on_disk() {
  LinearSolverOptions o;
  o.out_of_core = true;
  return o;
}

std::string refusal(const StripMeshSpec& mesh, const LinearSolverOptions& linear, Real available) {
  try {
    check_run_memory(mesh, linear, available);
  } catch (const SystemError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("the run's memory is estimated from the mesh before it is built", "[io][memory]") {
  StripMeshSpec mesh;  // 10 x 4 Q4
  mesh.nx = 570;       // the Hertz mesh of docs/benchmarks.md at 1.3e6 dofs: 571 x 1141 nodes
  mesh.ny = 1140;
  LinearSolverOptions in_core;
  const LinearSolverOptions out_of_core = factors_on_disk();
  const MemoryEstimate e = estimate_run_memory(mesh, in_core);
  CHECK(e.dofs == 2.0 * 571 * 1141);
  // Measured peaks (docs/benchmarks.md): ipopt 2559 MiB, penalty 3175 MiB in core; 1421 MiB out of
  // core. The estimate covers the larger, by no more than 10 %.
  const Real mib = 1024.0 * 1024.0;
  CHECK(e.bytes / mib >= 3175.0);
  CHECK(e.bytes / mib <= 1.1 * 3175.0);
  // A constant tangent's factors held for the run (ipopt, Hertz): 4507 MiB measured.
  const MemoryEstimate held = estimate_run_memory(mesh, in_core, HeldFactors::WholeRun);
  CHECK(held.bytes / mib >= 4507.0);
  CHECK(held.bytes / mib <= 1.1 * 4507.0);
  const MemoryEstimate ooc = estimate_run_memory(mesh, out_of_core);
  CHECK(ooc.bytes / mib >= 1421.0);
  CHECK(ooc.bytes / mib <= 1.1 * 1421.0);
  // A stationary pass's steady Jacobian: 636 MiB in core at 68,404 dofs (shakedown_p45, 0.08 mm
  // elements under the track), 336 MiB out of core at 47,974.
  StripMeshSpec track;
  track.nx = 97;
  track.ny = 348;
  const MemoryEstimate steady = estimate_run_memory(track, in_core, HeldFactors::SteadyJacobian);
  CHECK(steady.dofs == 68404.0);
  CHECK(steady.bytes / mib >= 636.0);
  CHECK(steady.bytes / mib <= 1.1 * 636.0);
  const Real ooc_per_dof = estimate_run_memory(track, out_of_core, HeldFactors::SteadyJacobian).bytes / steady.dofs;
  CHECK(47974.0 * ooc_per_dof / mib >= 336.0);
  CHECK(47974.0 * ooc_per_dof / mib <= 1.1 * 336.0);
  // The node count is computed in floating point: nx * refine beyond an int does not wrap.
  mesh.nx = 2'000'000'000;
  mesh.refine = 64;
  CHECK(estimate_run_memory(mesh, in_core).dofs > 1e11);
}

TEST_CASE("a mesh that does not fit stops with the remedies, one that fits goes on", "[io][memory]") {
  StripMeshSpec mesh;
  mesh.nx = 1000;
  mesh.ny = 1000;  // 2e6 dofs: ~5 GB in core, ~2.3 GB out of core
  const Real gib = 1024.0 * 1024.0 * 1024.0;
  CHECK_NOTHROW(check_run_memory(mesh, {}, 8.0 * gib));
  CHECK_THAT(refusal(mesh, {}, 4.0 * gib), Contains("2e+06 dofs") && Contains("4.0 GiB available") &&
                                               Contains("smaller mesh.refine") && Contains("out_of_core = true"));
  // Out of core it fits in 4 GiB; when even that is too large only a coarser mesh helps.
  CHECK(refusal(mesh, factors_on_disk(), 4.0 * gib).empty());
  CHECK_THAT(refusal(mesh, factors_on_disk(), 1.0 * gib),
             Contains("out of core") && Contains("smaller mesh.refine") && !Contains("out_of_core = true"));
  CHECK(available_memory().value_or(AvailableMemory(1.0)).bytes > 0.0);
}
