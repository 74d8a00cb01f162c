#include "roller/solver/solver_abort.hpp"

#include <cstdlib>
#include <iostream>
#include <utility>

#include <fmt/format.h>

namespace roller {

namespace {

SolverAbortHandler& current_handler() {
  static SolverAbortHandler handler;
  return handler;
}

}  // namespace

SolverAbortGuard::SolverAbortGuard(SolverAbortHandler handler) : previous_(std::move(current_handler())) {
  current_handler() = std::move(handler);
}

SolverAbortGuard::~SolverAbortGuard() { current_handler() = std::move(previous_); }

}  // namespace roller

// MPI_ABORT(comm, errorcode, ierr) as MUMPS's Fortran calls it (by reference).
extern "C" [[noreturn]] void mpi_abort_(int* /*comm*/, int* errorcode, int* /*ierr*/) {
  const std::string message = fmt::format(
      "the sparse solver (MUMPS) stopped inside a factorisation (MPI_ABORT, code {}): an allocation failed, most "
      "likely the process's memory limit (ulimit -v) or the machine's memory is too small for this mesh; use a "
      "coarser mesh (--refine, mesh.nx, mesh.ny) or [linear_solver] out_of_core = true",
      errorcode ? *errorcode : 0);
  if (const roller::SolverAbortHandler& handler = roller::current_handler()) handler(message);
  std::cerr << "roller: system error: " << message << "\n" << std::flush;
  std::_Exit(3);
}
