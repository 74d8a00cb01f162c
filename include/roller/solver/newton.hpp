#pragma once
// Newton's method for the minimisation of a smooth objective Pi(x) over the free dofs, with a
// backtracking line search on Pi and a clear report. Used for increments without contact (the
// penalty contact backend runs a Newton loop of its own, contact/penalty/penalty_backend.cpp).
#include <memory>
#include <string>
#include <vector>

#include "roller/core/expected.hpp"
#include "roller/core/types.hpp"
#include "roller/solver/newton_options.hpp"
#include "roller/solver/solve_counters.hpp"
#include "roller/solver/sparse_solver.hpp"
#include "roller/solver/termination.hpp"

namespace roller {

// What one evaluation of the objective computes besides its gradient and Hessian.
struct ObjectiveValue {
  Real value = 0.0;        // Pi(x)
  Real force_scale = 0.0;  // at x, for the relative residual test (e.g. max of external load and reactions)
};

// Pi(x), its gradient and Hessian (full symmetric storage), or why it cannot be evaluated at x
// (an inverted element, ...): Newton then backtracks or gives up.
class NewtonObjective {
 public:
  virtual ~NewtonObjective() = default;
  virtual Expected<ObjectiveValue> evaluate(const VecX& x, VecX* gradient, SparseMatrix* hessian) = 0;
};

struct NewtonReport {
  Termination status = Termination::Failed;
  SolveCounters counters;              // iterations and factorisations
  Real residual = 0.0;                 // final ||gradient|| / force scale
  std::vector<Real> residual_history;  // ||gradient|| at each iterate (absolute)
  int line_search_cuts = 0;
  std::string message;
  bool converged() const { return status == Termination::Converged; }
};

// Newton's method with its linear solver: one object per sequence of similar problems (a run's
// increments), so that MUMPS's symbolic analysis is redone only when the pattern changes.
class NewtonMinimiser {
 public:
  NewtonMinimiser() : solver_(std::make_unique<SparseSolver>(MumpsSolver::Symmetry::Symmetric)) {}
  // Starts from x (updated in place). Converged when ||gradient|| <= residual_tolerance * scale.
  NewtonReport minimise(NewtonObjective& objective, VecX& x, const NewtonOptions& options);

 private:
  // Solves H d = -g; false when no shift of H gives a descent direction.
  bool direction(const SparseMatrix& h, const VecX& g, const LinearSolverOptions& linear, VecX& d, int& factorizations);
  std::unique_ptr<SparseSolver> solver_;  // held by pointer: Eigen's solvers cannot move
};

// One minimisation with a solver of its own (tests, one-off problems).
NewtonReport minimise_newton(NewtonObjective& objective, VecX& x, const NewtonOptions& options);

}  // namespace roller
