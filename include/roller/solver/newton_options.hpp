#pragma once
#include <string>

namespace roller {

struct NewtonOptions {
  int max_iterations = 30;
  double residual_tolerance = 1e-8;   // converged when ||r|| <= tol * force scale
  bool line_search = true;
  bool is_valid(std::string* why) const;
};

}  // namespace roller
