#pragma once
// A dense symmetric indefinite solver for Ipopt's KKT systems of the condensed NLP, handed to
// Ipopt through its linear-solver loader as "ma27".
//
// Why. The condensed NLP (ipopt_condensed.cpp) has a dense Hessian of a few to a few hundred
// unknowns and is solved hundreds of times a run, each interior-point iteration factorising and
// solving its KKT system. Debian's Ipopt 3.11 solves those with MUMPS, whose 5.5 driver walks its
// whole structure (dmumps_compute_memory_save) on every call: about 0.1 ms a call whatever the
// size, most of a small scene's run (docs/benchmarks-log.md, "Ipopt's settings for many small NLPs").
// A dense Bunch-Kaufman LDL^T (LAPACK dsytrf/dsytrs) has no such fixed cost, and on a dense
// Hessian it does the work MUMPS does.
//
// How. Ipopt 3.11 cannot take a linear solver object without its algorithm builder's header,
// which Debian does not install; but its linear-solver loader (HSLLoader.h, installed) takes the
// four entry points of HSL's MA27 from the application (LSL_setMA27), and Ipopt's MA27 interface
// then calls them. The functions below keep MA27's calling convention and its workspace protocol:
//   ma27ad (analysis): asks for a real workspace LA >= NZ + N^2 (INFO(5)) and an integer one
//     LIW >= N + 1 (INFO(6)); NSTEPS = 1;
//   ma27bd (factorisation): sums the NZ triplets (1-based, either triangle, duplicates added)
//     into the dense lower triangle at A[NZ..], factorises it there, keeps the pivots in IW;
//     INFO(15) = the number of negative eigenvalues (from the 1x1 and 2x2 blocks of D), and an
//     eigenvalue of a pivot block at or below 1e-5 eps |A|_max (MUMPS's null pivot in Ipopt) is
//     a zero one: IFLAG = 3, INFO(2) = the rank, as MA27 reports a rank deficiency; a
//     workspace too small gives IFLAG = -3/-4 with the size needed in INFO(2), and Ipopt grows
//     it and calls again;
//   ma27cd (solve): one right-hand side in place.
// The pivot tolerance (CNTL(1)) is ignored: Bunch-Kaufman's pivot choice is fixed.
#include <HSLLoader.h>

namespace roller::dense_kkt {

// Makes the dense solver Ipopt's "ma27" for this process (idempotent, thread-safe).
void register_dense_kkt_solver();

// The MA27 entry points (for the tests; Ipopt reaches them through the loader).
namespace dense_ma27 {
void init(ipfint* icntl, double* cntl);
void analyse(ipfint* n, ipfint* nz, const ipfint* irn, const ipfint* icn, ipfint* iw, ipfint* liw, ipfint* ikeep,
             ipfint* iw1, ipfint* nsteps, ipfint* iflag, ipfint* icntl, double* cntl, ipfint* info, double* ops);
void factorise(ipfint* n, ipfint* nz, const ipfint* irn, const ipfint* icn, double* a, ipfint* la, ipfint* iw,
               ipfint* liw, ipfint* ikeep, ipfint* nsteps, ipfint* maxfrt, ipfint* iw1, ipfint* icntl, double* cntl,
               ipfint* info);
void solve(ipfint* n, double* a, ipfint* la, ipfint* iw, ipfint* liw, double* w, ipfint* maxfrt, double* rhs,
           ipfint* iw1, ipfint* nsteps, ipfint* icntl, double* cntl);
}  // namespace dense_ma27

}  // namespace roller::dense_kkt
