#pragma once
// Options of the sparse direct solver MUMPS (scene table [linear_solver]; docs/scenes.md), used
// by every factorisation of the strip's tangent: Newton without contact, the penalty backend,
// the condensed ipopt backend. (The "full" ipopt formulation factorises through Ipopt's own
// MUMPS interface, which these options do not reach.)
#include <string>
#include <vector>

namespace roller {

struct LinearSolverOptions {
  // Factors written to disk (MUMPS out-of-core, ICNTL(22) = 1): resident memory drops to the
  // active fronts, at the cost of reading them back in each solve (docs/benchmarks.md,
  // "Out-of-core factors").
  bool out_of_core = false;
  std::string directory;          // where the out-of-core files go ("" = MUMPS's default, /tmp)
  std::string ordering = "auto";  // fill-reducing ordering: "auto" (MUMPS chooses) | "amd" | "metis"
  // ICNTL(14) of the first factorisation: percent of workspace added to MUMPS's estimate for
  // delayed pivots; doubled on each overrun (not a scene key: the retry makes it self-tuning).
  int workspace_percent = 50;
  bool is_valid(std::string* why) const;
  bool operator==(const LinearSolverOptions& o) const {
    return out_of_core == o.out_of_core && directory == o.directory && ordering == o.ordering &&
           workspace_percent == o.workspace_percent;
  }
  static const std::vector<std::string>& orderings();  // the accepted values of `ordering`
};

}  // namespace roller
