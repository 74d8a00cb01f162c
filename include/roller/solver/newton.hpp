#pragma once
// Newton's method for the minimisation of a smooth objective Pi(x) over the free dofs, with a
// backtracking line search on Pi and a clear report. Used for increments without contact and,
// with penalty terms added to Pi, by the penalty contact backend (thesis §4.2.1).
#include <string>
#include <vector>

#include "roller/core/types.hpp"
#include "roller/solver/newton_options.hpp"

namespace roller {

// Pi(x), its gradient and Hessian (full symmetric storage). Throws NumericalError when it
// cannot be evaluated at x (inverted element, ...); Newton then backtracks or gives up.
class NewtonObjective {
 public:
  virtual ~NewtonObjective() = default;
  virtual Real evaluate(const VecX& x, VecX* gradient, SparseMatrix* hessian) = 0;
  // Force scale for the relative residual test (e.g. max of external load and reactions).
  virtual Real force_scale(const VecX& x) = 0;
};

enum class NewtonStatus { Converged, NotConverged, Failure };

struct NewtonReport {
  NewtonStatus status = NewtonStatus::Failure;
  int iterations = 0;
  Real residual = 0.0;        // final ||gradient|| / force scale
  std::vector<Real> residual_history;  // ||gradient|| at each iterate (absolute)
  int line_search_cuts = 0;
  int factorizations = 0;
  std::string message;
  bool converged() const { return status == NewtonStatus::Converged; }
};

// Starts from x (updated in place). Converged when ||gradient|| <= residual_tolerance * scale.
NewtonReport minimise_newton(NewtonObjective& objective, VecX& x, const NewtonOptions& options);

}  // namespace roller
