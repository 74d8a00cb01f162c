#include "roller/driver/memory_estimate.hpp"

#include <fstream>
#include <string>

#include <fmt/format.h>

#include "roller/core/error.hpp"

namespace roller {

namespace {

constexpr Real kBytesPerDofInCore = 2.6e3;
constexpr Real kBytesPerDofInCoreHeld = 3.65e3;
constexpr Real kBytesPerDofOutOfCore = 1.2e3;
constexpr Real kProgramBytes = 20e6;  // a 400-dof run peaks at 15 MiB
constexpr Real kGiB = 1024.0 * 1024.0 * 1024.0;

Real bytes_per_dof(const LinearSolverOptions& linear, HeldFactors held) {
  if (linear.out_of_core) return kBytesPerDofOutOfCore;
  return held == HeldFactors::WholeRun ? kBytesPerDofInCoreHeld : kBytesPerDofInCore;
}

}  // namespace

MemoryEstimate estimate_run_memory(const StripMeshSpec& mesh, const LinearSolverOptions& linear, HeldFactors held) {
  MemoryEstimate e;
  e.dofs = 2.0 * strip_node_count(mesh);
  e.bytes = kProgramBytes + e.dofs * bytes_per_dof(linear, held);
  return e;
}

std::optional<Real> available_memory_bytes() {
  std::ifstream in("/proc/meminfo");
  for (std::string name; in >> name;) {
    Real kib = 0.0;
    in >> kib;
    if (name == "MemAvailable:") return kib * 1024.0;
    in.ignore(256, '\n');
  }
  return std::nullopt;
}

void check_run_memory(const StripMeshSpec& mesh, const LinearSolverOptions& linear, Real available, HeldFactors held) {
  const MemoryEstimate need = estimate_run_memory(mesh, linear, held);
  if (need.bytes <= available) return;
  LinearSolverOptions on_disk = linear;
  on_disk.out_of_core = true;
  const std::string advice =
      linear.out_of_core
          ? "use a smaller mesh.refine (--refine), nx or ny"
          : fmt::format(
                "use a smaller mesh.refine (--refine), nx or ny, or set [linear_solver] out_of_core = true "
                "(factors on disk: about {:.1f} GiB for this mesh)",
                estimate_run_memory(mesh, on_disk, held).bytes / kGiB);
  throw SystemError(fmt::format(
      "mesh.refine = {}: the mesh has {:.3g} dofs and the run needs about {:.1f} GiB of memory ({:.1f} kB per dof "
      "{}, measured: docs/benchmarks.md), but this machine has {:.1f} GiB available: {}",
      mesh.refine, need.dofs, need.bytes / kGiB, bytes_per_dof(linear, held) / 1e3,
      linear.out_of_core ? "out of core" : "in core", available / kGiB, advice));
}

}  // namespace roller
