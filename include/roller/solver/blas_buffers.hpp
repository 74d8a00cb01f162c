#pragma once
// OpenBLAS maps a 128 MiB buffer per thread at its first level-3 call and, when the mapping
// fails (under an address-space limit, ulimit -v), retries it for ever: the process hangs inside
// the factorisation (seen in gdb, docs/stability.md, "Out of memory"). Under such a limit a run
// takes the buffers at its start, before the factorisation's workspace, so that a later shortage
// is an allocation of MUMPS or of ours that fails, and ends the run with exit code 3.
namespace roller {

// One threaded product large enough to give every OpenBLAS thread its buffer (about 5 ms).
void map_blas_buffers();

}  // namespace roller
