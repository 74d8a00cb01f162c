#include "roller/solver/memory_estimate.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <string>

#include <dlfcn.h>
#include <sys/resource.h>
#include <unistd.h>

#include <fmt/format.h>

#include "roller/core/error.hpp"

namespace roller {

namespace {

constexpr Real kBytesPerDofInCore = 2.6e3;
constexpr Real kBytesPerDofInCoreHeld = 3.65e3;
constexpr Real kBytesPerDofOutOfCore = 1.2e3;
constexpr Real kBytesPerDofSteadyInCore = 9.5e3;
constexpr Real kBytesPerDofSteadyOutOfCore = 7.2e3;
constexpr Real kProgramBytes = 20e6;  // a 400-dof run peaks at 15 MiB
constexpr Real kGiB = 1024.0 * 1024.0 * 1024.0;

Real bytes_per_dof(const LinearSolverOptions& linear, HeldFactors held) {
  if (held == HeldFactors::SteadyJacobian)
    return linear.out_of_core ? kBytesPerDofSteadyOutOfCore : kBytesPerDofSteadyInCore;
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

namespace {

// A field of /proc/self/status or /proc/meminfo in kB, as bytes.
std::optional<Real> proc_field_bytes(const char* file, const std::string& field) {
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);)
    if (line.compare(0, field.size(), field) == 0) return std::strtod(line.c_str() + field.size(), nullptr) * 1024.0;
  return std::nullopt;
}

// The threads OpenBLAS runs: its own count when it is the BLAS loaded, else its rule (the
// environment's OPENBLAS_NUM_THREADS or OMP_NUM_THREADS, else the processors).
int blas_threads() {
  using GetThreads = int (*)();
  if (void* f = dlsym(RTLD_DEFAULT, "openblas_get_num_threads")) return std::max(1, reinterpret_cast<GetThreads>(f)());
  for (const char* name : {"OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS"})
    if (const char* v = std::getenv(name); v && std::atoi(v) > 0) return std::atoi(v);
  return std::max(1L, sysconf(_SC_NPROCESSORS_ONLN));
}

// Under an address-space limit: OpenBLAS's 128 MiB buffer per thread (solver/blas_buffers.hpp)
// and the output writer's threads, and the address space a run maps per byte it keeps resident
// (MUMPS's workspace is allocated whole, SCOTCH's graphs beside it). Measured on
// block_compression at refine 24 (docs/stability.md, "Out of memory"): the address space grew
// by 2 x 128 MiB plus 1.07 times the resident estimate.
Real blas_and_thread_reserve() { return (128.0 * blas_threads() + 64.0) * 1024.0 * 1024.0; }
constexpr Real kAddressSpacePerResident = 1.25;

}  // namespace

std::optional<AvailableMemory> available_memory() {
  std::optional<AvailableMemory> out;
  if (const auto machine = proc_field_bytes("/proc/meminfo", "MemAvailable:")) out = AvailableMemory(*machine);
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    const Real mapped = proc_field_bytes("/proc/self/status", "VmSize:").value_or(0.0);
    const Real room = std::max(0.0, static_cast<Real>(limit.rlim_cur) - mapped - blas_and_thread_reserve()) /
                      kAddressSpacePerResident;
    if (!out || room < out->bytes)
      out = AvailableMemory(room,
                            fmt::format("the process's address-space limit (ulimit -v, {:.2f} GiB) leaves",
                                        static_cast<Real>(limit.rlim_cur) / kGiB),
                            true);
    else
      out->address_space_limit = true;
  }
  return out;
}

void check_run_memory(const StripMeshSpec& mesh, const LinearSolverOptions& linear, const AvailableMemory& available,
                      HeldFactors held) {
  const MemoryEstimate need = estimate_run_memory(mesh, linear, held);
  if (need.bytes <= available.bytes) return;
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
      "{}, measured: docs/benchmarks.md), but {} {:.1f} GiB available: {}",
      mesh.refine, need.dofs, need.bytes / kGiB, bytes_per_dof(linear, held) / 1e3,
      linear.out_of_core ? "out of core" : "in core", available.limited_by, available.bytes / kGiB, advice));
}

}  // namespace roller
