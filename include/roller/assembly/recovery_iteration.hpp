#pragma once
// The fixed point that lets a minimiser (the interior-point backend, the strip's Newton) solve an
// increment of a law with Armstrong-Frederick recovery, which has no incremental potential
// (docs/model.md, Hardening laws): each integration point's recovery is frozen at a plastic
// multiplier d* (a linear kinematic update with a potential), the increment is solved, d* is set
// to the solution's multipliers d, and the increment is solved again until max |d - d*| is small.
// At the fixed point the solution is the exact backward-Euler update's.
#include <optional>
#include <string>
#include <vector>

#include "roller/assembly/strip_model.hpp"
#include "roller/solver/termination.hpp"

namespace roller {

class RecoveryIteration {
 public:
  // Freezes every point at d* = 0 when the strip's law has a recovery term; otherwise inactive.
  // Settled when no back-stress is off by more than stress_tolerance x sigma_y0: the caller's
  // equilibrium tolerance (a tighter one only chases the solver's own round-off in d).
  RecoveryIteration(StripModel& strip, Real stress_tolerance);
  ~RecoveryIteration();  // unfreezes: the strip's commit takes the exact update
  RecoveryIteration(const RecoveryIteration&) = delete;
  RecoveryIteration& operator=(const RecoveryIteration&) = delete;

  // Calls `solve()` (the increment of all dofs it ended at, or nullopt when it failed), refreezing
  // at each solution's multipliers, until they settle (Converged; one solve when inactive), a
  // solve fails (Failed), or max_passes() solves ran (LimitReached: failure() says why).
  template <class Solve>
  Termination iterate(Solve solve) {
    for (;;) {
      const std::optional<VecX> u = solve();
      if (!u) return Termination::Failed;
      if (settled(*u)) return Termination::Converged;
      if (passes_ >= max_passes()) return Termination::LimitReached;
    }
  }
  // Why the iteration stopped unsettled after max_passes() solves, for the step's message.
  std::string failure() const;
  static constexpr int max_passes() { return 30; }

 private:
  // After a solve that ended at the increment u (all dofs): refreezes at u's multipliers and
  // returns true when they moved so little that no back-stress moves by more than the tolerance.
  // Always true when inactive.
  bool settled(const VecX& u);

  StripModel& strip_;
  bool active_ = false;
  Real tolerance_ = 0.0;  // on max |d - d*|
  int passes_ = 0;
  Real change_ = 0.0;
  std::vector<Real> frozen_;
  std::vector<Real> previous_frozen_, previous_result_;  // the pass before: d* and d
};

}  // namespace roller
