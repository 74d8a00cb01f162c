#pragma once
#include <string>

#include "roller/solver/linear_solver_options.hpp"

namespace roller {

struct NewtonOptions {
  int max_iterations = 30;
  double residual_tolerance = 1e-8;  // converged when ||r|| <= tol * force scale
  bool line_search = true;
  LinearSolverOptions linear;  // [linear_solver]: every sparse factorisation of the run
  bool is_valid(std::string* why) const;
};

}  // namespace roller
