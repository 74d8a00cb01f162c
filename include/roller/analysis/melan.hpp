#pragma once
// Melan's static shakedown theorem for a load that moves along a long strip (docs/model.md,
// "Melan's bound"): the largest factor lambda on an elastic stress field for which a
// time-independent residual stress (and, for a kinematically hardening material, a back-stress)
// keeps every point inside its yield surface at every position of the load.
//
// The load moves along x over a strip long enough that the residual state is uniform along x:
// then equilibrium with a free top surface leaves only rho_xx(z) and the out-of-plane rho_zz(z),
// and every point at one depth sees the same stress history, the elastic field of one load
// position read along its row. So the theorem splits into one small convex problem per depth:
//   maximise lambda  over lambda >= 0 and the shift s
//   subject to  sigma_vm(lambda sigma_i + rho(s) - alpha(s)) <= sigma_y,i  for every point i of the row
//               sigma_vm(alpha) <= alpha_max  (a saturating back-stress; absent when unbounded)
// each solved with Ipopt. The limit of the strip is the smallest over the rows.
#include <limits>
#include <vector>

#include "roller/core/enum_names.hpp"
#include "roller/core/types.hpp"

namespace roller {

// Which shift of each point's stress cycle the theorem may use.
enum class ShakedownBound {
  // Residual stresses rho_xx, rho_zz only (a perfectly plastic, or isotropically hardening, strip:
  // Melan's elastic shakedown limit).
  Elastic,
  // Residual stresses and a back-stress alpha per depth (a deviator: alpha_xx, alpha_yy, alpha_xy;
  // alpha_zz = -alpha_xx - alpha_yy), bounded by alpha_max: the limit above which a kinematically
  // hardening strip keeps yielding every pass (Melan's theorem extended to kinematic hardening).
  Kinematic,
};
template <>
struct EnumNames<ShakedownBound> {
  static constexpr std::array<std::pair<ShakedownBound, const char*>, 2> names{
      {{ShakedownBound::Elastic, "elastic"}, {ShakedownBound::Kinematic, "kinematic"}}};
};

// The integration points at one depth: the stress history of a point at that depth.
struct MelanRow {
  Real depth = 0.0;          // below the strip's top [mm]
  std::vector<Real> x;       // position of each point along the row [mm]
  std::vector<Vec4> stress;  // elastic stress [xx, yy, zz, xy] at each point at load factor 1 [MPa]
  // Yield stress of each point [MPa]: the initial one, or a softening law's saturated one (the
  // bound must hold after any plastic flow; MaterialParams::lowest_yield_stress).
  std::vector<Real> yield_stress;
  // The largest von Mises measure the back-stress can reach (sum of C/gamma of a saturating law);
  // infinity for linear kinematic hardening. Only ShakedownBound::Kinematic reads it.
  Real back_stress_bound = std::numeric_limits<Real>::infinity();
};

// Stops the search when the rows' limits exceed this multiple of their first-yield factor: a row
// whose stress cycle a shift cancels (a uniform stress along it) has no finite limit.
constexpr Real kMelanCapOverFirstYield = 100.0;

// What became of a row.
enum class MelanRowStatus {
  Solved,       // load_factor is the row's limit
  Unlimited,    // no stress along it, or a shift cancels its cycle (the cap was reached)
  NotLimiting,  // not solved: its first yield lies above a limit found in another row, and its own
                // limit cannot lie below its first yield (MelanSearch::StrictestRow)
};
template <>
struct EnumNames<MelanRowStatus> {
  static constexpr std::array<std::pair<MelanRowStatus, const char*>, 3> names{
      {{MelanRowStatus::Solved, "solved"},
       {MelanRowStatus::Unlimited, "unlimited"},
       {MelanRowStatus::NotLimiting, "not_limiting"}}};
};

struct MelanRowLimit {
  Real depth = 0.0;
  MelanRowStatus status = MelanRowStatus::Solved;
  Real load_factor = 0.0;               // lambda at the limit (Solved)
  Real first_yield = 0.0;               // min sigma_y,i / sigma_vm(sigma_i): the row's first yield
  Vec4 residual_stress = Vec4::Zero();  // rho at the limit [xx, yy, zz, xy] (MPa; yy and xy are 0)
  Vec4 back_stress = Vec4::Zero();      // alpha at the limit (ShakedownBound::Kinematic)
  Real critical_x = 0.0;                // the point of the row whose constraint is most active
  Real critical_yield_stress = 0.0;     // its initial yield stress [MPa]
  int iterations = 0;                   // Ipopt's
};

struct MelanLimit {
  ShakedownBound bound = ShakedownBound::Elastic;
  std::vector<MelanRowLimit> rows;  // in the order given
  Index critical_row = -1;          // the row with the smallest limit
  Real load_factor() const { return critical_row < 0 ? 0.0 : rows[critical_row].load_factor; }
  Real first_yield() const;  // the smallest first-yield factor over the rows
};

// Which rows to solve: only as many as the strip's limit needs (rows in the order of their first
// yield, until the next one's first yield lies above the smallest limit so far), or every row
// (the limit by depth).
enum class MelanSearch { StrictestRow, EveryRow };

// One row. Throws NumericalError when Ipopt fails on it (the message names the depth).
MelanRowLimit melan_row_limit(const MelanRow& row, ShakedownBound bound);
MelanLimit melan_limit(const std::vector<MelanRow>& rows, ShakedownBound bound,
                       MelanSearch search = MelanSearch::StrictestRow);

}  // namespace roller
