#include "roller/assembly/recovery_iteration.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace roller {

namespace {

// A multiplier off by dd moves a back-stress by at most C dd (|alpha| <= C/gamma): settled when
// sum C_i max |d - d*| <= stress_tolerance x sigma_y0.
Real multiplier_tolerance(const MaterialParams& m, Real stress_tolerance) {
  Real moduli = 0.0;
  for (int i = 0; i < m.n_back_stresses(); ++i) moduli += m.back_stress_law(i).modulus;
  return moduli > 0.0 ? stress_tolerance * m.yield_stress / moduli : 0.0;
}

}  // namespace

RecoveryIteration::RecoveryIteration(StripModel& strip, Real stress_tolerance)
    : strip_(strip), active_(strip.has_recovery()) {
  if (!active_) return;
  // The strictest of the strip's materials (layers may differ).
  tolerance_ = std::numeric_limits<Real>::infinity();
  for (const MaterialParams& m : strip.materials().table)
    if (m.n_back_stresses() > 0) tolerance_ = std::min(tolerance_, multiplier_tolerance(m, stress_tolerance));
  const std::size_t n = strip.states().size();
  frozen_.assign(n, 0.0);
  strip_.freeze_recovery(frozen_);
}

RecoveryIteration::~RecoveryIteration() {
  if (active_) strip_.freeze_recovery({});
}

bool RecoveryIteration::settled(const VecX& u) {
  ++passes_;
  if (!active_) return true;
  std::vector<Real> d = strip_.plastic_multipliers(u);
  change_ = 0.0;
  for (std::size_t k = 0; k < d.size(); ++k) change_ = std::max(change_, std::abs(d[k] - frozen_[k]));
  const bool done = change_ <= tolerance_;
  // The plain update d* <- d contracts slowly where the recovery is strong (gamma d ~ 1: a factor
  // ~0.6 a pass measured on Z1). Each point's secant through its last two passes, the fixed point
  // of the map's local linearisation, is taken instead where the slope is safely below 1.
  std::vector<Real> next = d;
  if (!previous_frozen_.empty()) {
    for (std::size_t k = 0; k < d.size(); ++k) {
      const Real dx = frozen_[k] - previous_frozen_[k];
      if (!(std::abs(dx) > 0.0)) continue;
      const Real slope = (d[k] - previous_result_[k]) / dx;
      if (slope < 0.9 && slope > -10.0) next[k] = std::max(0.0, (d[k] - slope * frozen_[k]) / (1.0 - slope));
    }
  }
  previous_frozen_ = frozen_;
  previous_result_ = std::move(d);
  frozen_ = std::move(next);
  strip_.freeze_recovery(frozen_);
  return done;
}

std::string RecoveryIteration::failure() const {
  return fmt::format(
      "the Armstrong-Frederick recovery did not settle in {} solves (the plastic multipliers still moved by {:.3g}); "
      "use smaller steps (a larger steps.count) or the penalty backend (contact.backend = \"penalty\")",
      passes_, change_);
}

}  // namespace roller
