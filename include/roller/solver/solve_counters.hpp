#pragma once
// The work of a solve (Newton, a contact backend), summed over the solves of an increment or a step with +=.
namespace roller {

struct SolveCounters {
  int iterations = 0;  // Newton or interior-point iterations
  int factorizations = 0;
  SolveCounters& operator+=(const SolveCounters& other) {
    iterations += other.iterations;
    factorizations += other.factorizations;
    return *this;
  }
};

}  // namespace roller
