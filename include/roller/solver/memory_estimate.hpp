#pragma once
// Memory a run will need, estimated from the mesh before it is built, so that a mesh too large
// for the machine stops with advice instead of std::bad_alloc half-way through the set-up.
// The rates are the peak resident memory per dof measured on the Hertz and Z1 increments from
// 3e5 to 1.3e6 dofs (docs/benchmarks.md, Scaling and Out-of-core factors).
#include <optional>
#include <string>
#include <utility>

#include "roller/core/types.hpp"
#include "roller/mesh/strip_mesher.hpp"
#include "roller/solver/linear_solver_options.hpp"

namespace roller {

struct MemoryEstimate {
  Real dofs = 0.0;   // 2 per node
  Real bytes = 0.0;  // peak resident memory of the run
};

// Whether the contact solve keeps the strip tangent's factors for the whole run (the ipopt
// backend's condensed formulation on a constant tangent: contact/ipopt/ipopt_condensed.cpp): they are
// then resident beside the output and state files being written.
// SteadyJacobian: a stationary pass's steady Jacobian (steady/stationary_pass.hpp), general and
// unsymmetric over the dofs and the yielding steps' states, factorised once or twice a pass.
enum class HeldFactors { PerIncrement, WholeRun, SteadyJacobian };

// In core: 2.6 kB per dof (the penalty backend's 3175 MiB at 1.3e6 dofs; ipopt 2.0 kB), 3.65 kB
// with factors held for the run (Hertz with ipopt: 4507 MiB at 1.3e6 dofs); out of core: 1.2 kB
// per dof (1421 MiB). The steady Jacobian: 9.5 kB per dof in core, 7.2 kB out of core (shakedown_p45
// at p0/k = 4.5 from 1.8e4 to 6.8e4 dofs: its plastic zone sets the yielding steps' states). Plus
// the program itself.
MemoryEstimate estimate_run_memory(const StripMeshSpec& mesh, const LinearSolverOptions& linear,
                                   HeldFactors held = HeldFactors::PerIncrement);

// The memory a run may still take, and what sets it (as the refusal names it).
struct AvailableMemory {
  AvailableMemory(Real b, std::string by = "this machine has", bool limit = false)
      : bytes(b), limited_by(std::move(by)), address_space_limit(limit) {}
  Real bytes = 0.0;
  std::string limited_by;
  bool address_space_limit = false;  // the process runs under ulimit -v (solver/blas_buffers.hpp)
};

// MemAvailable of /proc/meminfo or, under an address-space limit (ulimit -v), the limit less what
// the process has mapped and what OpenBLAS's threads will map for their buffers (128 MiB each),
// over the address space a run maps per resident byte (1.25), whichever is smaller; none where
// neither can be read.
std::optional<AvailableMemory> available_memory();

// Throws SystemError when the estimate exceeds `available`, naming the size and the remedies
// (a smaller refine, out-of-core factors).
void check_run_memory(const StripMeshSpec& mesh, const LinearSolverOptions& linear, const AvailableMemory& available,
                      HeldFactors held = HeldFactors::PerIncrement);

}  // namespace roller
