#pragma once
// Newton's method for a smooth system r(x) = 0 over the free dofs, with a line search on a merit
// function and a clear report: the one Newton of the program. The strip without a roller
// minimises its incremental potential (r = grad Pi, merit Pi); the penalty contact backend solves
// its equilibrium equations, unsymmetric once friction slips (merit ||r||).
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

// What one evaluation computes besides the residual and its Jacobian.
struct ObjectiveValue {
  Real value = 0.0;        // Pi(x), for the energy merit
  Real force_scale = 0.0;  // at x, for the relative residual test (e.g. max of external load and reactions)
  // ||r|| that round-off alone leaves at x (0: none known): a residual below it counts as
  // converged, since no iteration can reduce it further.
  Real roundoff_floor = 0.0;
  bool symmetric = true;  // the Jacobian at x is symmetric (LDL^T) or not (LU)
};

// r(x) (for a potential: its gradient), the Jacobian (full storage), or why the system cannot be
// evaluated at x (an inverted element, ...): Newton then backtracks or gives up.
class NewtonObjective {
 public:
  virtual ~NewtonObjective() = default;
  virtual Expected<ObjectiveValue> evaluate(const VecX& x, VecX* gradient, SparseMatrix* hessian) = 0;
};

// What the line search decreases, and with it how a direction is found.
enum class NewtonMerit {
  // Pi (Armijo), for a potential. The Hessian is shifted (Levenberg) until the direction descends.
  Energy,
  // ||r||, for equations without a potential (friction). The direction is Newton's (LDL^T when
  // the Jacobian is symmetric, LU otherwise or when LDL^T fails). Where ||r|| does not decrease
  // along it (a contact, stick or slip status changes along the step) the full step is taken, at
  // most kMaxFullStepsInARow times in a row: a semismooth Newton step.
  Residual,
};

struct NewtonReport {
  Termination status = Termination::Failed;
  SolveCounters counters;              // iterations and factorisations
  Real residual = 0.0;                 // final ||r|| / force scale
  bool at_roundoff_floor = false;      // converged by ||r|| <= the round-off floor, above the tolerance
  std::vector<Real> residual_history;  // ||r|| at each iterate (absolute)
  int line_search_cuts = 0;
  std::string message;
  bool converged() const { return status == Termination::Converged; }
};

// Newton's method with its linear solvers: one object per sequence of similar problems (a run's
// increments), so that MUMPS's symbolic analysis is redone only when the pattern changes.
class NewtonMinimiser {
 public:
  static constexpr int kMaxFullStepsInARow = 5;
  NewtonMinimiser() : symmetric_(std::make_unique<SparseSolver>(MumpsSolver::Symmetry::Symmetric)) {}
  // Starts from x (updated in place: the last iterate, also when not converged). Converged when
  // ||r|| <= residual_tolerance * scale, or ||r|| <= the round-off floor.
  NewtonReport minimise(NewtonObjective& objective, VecX& x, const NewtonOptions& options,
                        NewtonMerit merit = NewtonMerit::Energy);

 private:
  // Solves J d = -r as the merit asks; false when no direction is found.
  bool direction(NewtonMerit merit, const SparseMatrix& j, const VecX& r, bool symmetric,
                 const LinearSolverOptions& linear, VecX& d, int& factorizations);
  bool descent_direction(const SparseMatrix& h, const VecX& g, VecX& d, int& factorizations);
  bool newton_direction(const SparseMatrix& j, const VecX& r, bool symmetric, VecX& d, int& factorizations);
  // Held by pointer: Eigen's solvers cannot move. The LU one is made when first needed.
  std::unique_ptr<SparseSolver> symmetric_;
  std::unique_ptr<SparseSolver> general_;
};

// One minimisation with a solver of its own (tests, one-off problems).
NewtonReport minimise_newton(NewtonObjective& objective, VecX& x, const NewtonOptions& options);

}  // namespace roller
