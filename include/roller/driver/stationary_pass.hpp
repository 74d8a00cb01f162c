#pragma once
// One steady pass of the roller solved in its own frame (docs/model.md, "Stationary pass"):
// the displacement u (from the upstream configuration) for which the states swept along the
// streamlines carry the load. Each iteration is an initial-stress correction with the elastic
// stiffness, factorised once for every pass:
//   r(u) = f_ext + f(sigma_upstream) - f(sigma(u)),   g = K_e^-1 r
// and the fixed point u = u + g accelerated by Anderson's mixing of the last 20 corrections. The
// upstream term makes an unloaded strip keep its upstream state (r = 0 at u = 0).
#include <iosfwd>
#include <string>
#include <vector>

#include "roller/assembly/dof_map.hpp"
#include "roller/assembly/stationary_strip.hpp"
#include "roller/solver/sparse_solver.hpp"
#include "roller/solver/termination.hpp"

namespace roller {

struct StationarySettings {
  Real tolerance = 1e-8;             // on |r|_inf / F_ref, F_ref = |f_ext|_inf
  int max_iterations = 3000;         // then limit_reached
  std::ostream* progress = nullptr;  // a line every `report_every` iterations
  int report_every = 50;
};

struct StationaryPassResult {
  Termination status = Termination::Failed;
  int iterations = 0;
  Real residual = 0.0;                // |r|_inf / F_ref at the end
  VecX displacement;                  // all dofs
  std::vector<Vec4> strains;          // at every point
  std::vector<MaterialState> states;  // at every point
  Index n_yielded = 0;                // points that yield on their way
  std::string message;
  bool converged() const { return status == Termination::Converged; }
};

// `elastic`: K_e over the free dofs, factorised. `external`: the load (all dofs). `upstream`: one
// state per streamline. Constrained dofs stay at zero.
StationaryPassResult solve_stationary_pass(const StationaryStrip& strip, const DofMap& dofs, SparseSolver& elastic,
                                           const VecX& external, const std::vector<MaterialState>& upstream,
                                           const StationarySettings& settings);

}  // namespace roller
