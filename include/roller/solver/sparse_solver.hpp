#pragma once
// The sparse direct solver of the Newton iterations (penalty backend, contact-free scenes):
// Eigen's simplicial LDL^T / SparseLU below `kMumpsFromUnknowns`, MUMPS (multifrontal, BLAS-3)
// from there on: on small systems MUMPS's per-call overhead dominates and Eigen is faster, on
// large ones MUMPS is much faster (docs/benchmarks.md, "Assembly throughput and one sparse
// factorisation" and "Scaling of one increment").
// The solver persists between calls: the symbolic analysis is reused while the pattern stays.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>

#include "roller/solver/mumps_factorization.hpp"

namespace roller {

constexpr Index kMumpsFromUnknowns = 20000;

class SparseSolver {
 public:
  explicit SparseSolver(MumpsSolver::Symmetry symmetry) : symmetry_(symmetry) {}
  // MUMPS's options for the next factorisations (a new MUMPS instance when they change).
  void configure(const LinearSolverOptions& options);
  // Factorises `a` (symmetric: only its lower triangle matters for MUMPS). False on failure.
  bool factorize(const SparseMatrix& a);
  VecX solve(const VecX& b);

 private:
  MumpsSolver::Symmetry symmetry_;
  LinearSolverOptions options_;
  bool use_mumps_ = false;
  std::unique_ptr<MumpsSolver> mumps_;
  Eigen::SimplicialLDLT<SparseMatrix> ldlt_;
  Eigen::SparseLU<SparseMatrix> lu_;
  std::vector<int> analysed_outer_, analysed_inner_;  // the pattern Eigen's analysis holds
};

}  // namespace roller
