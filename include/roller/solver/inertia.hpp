#pragma once
// Sylvester's inertia of a symmetric matrix, as a factorisation LDL^T counts it.
#include "roller/core/types.hpp"

namespace roller {

// How many eigenvalues are negative and how many are null (a pivot below 1e-12 ||A||, as the
// run-time monitor counts them: analysis/monotonicity.hpp).
struct Inertia {
  Index negative = 0;
  Index zero = 0;
};

}  // namespace roller
