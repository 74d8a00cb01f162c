#pragma once
// When MUMPS gives up inside a call (an allocation that fails deep in the factorisation, under a
// memory limit), its sequential MPI stub ends the process with Fortran's STOP: exit code 0, and
// nothing of ours printed. So roller defines the stub's MPI_ABORT itself; CMakeLists.txt exports
// the symbol from the executable, where the dynamic linker finds it first. It calls the handler
// the driver installed, which records what the run has done (summary.json), then prints the
// message and ends the process with exit code 3 (an exception cannot unwind the Fortran frames).
#include <functional>
#include <string>

namespace roller {

using SolverAbortHandler = std::function<void(const std::string& message)>;

// Installs `handler` for the lifetime of the guard (the previous one comes back after it).
class SolverAbortGuard {
 public:
  explicit SolverAbortGuard(SolverAbortHandler handler);
  ~SolverAbortGuard();
  SolverAbortGuard(const SolverAbortGuard&) = delete;
  SolverAbortGuard& operator=(const SolverAbortGuard&) = delete;

 private:
  SolverAbortHandler previous_;
};

}  // namespace roller
