#pragma once
// What repeated passes leave in the strip, and whether it shakes down (docs/validation.md,
// Shakedown; the criterion is documented in docs/scenes.md, passes.csv).
//
// Per pass, over the "track window" (the middle half, in x, of the stretch the roller rolled in
// contact during the pass, down to 4 contact half-widths a): the increment of equivalent plastic
// strain, and in the band at the depth of maximum shear (0.78 a under a Hertz line contact) the
// increment of the residual (total) shear strain 2 eps_xy. Closed plastic cycles accumulate
// equivalent plastic strain but no net strain; ratchetting adds net strain every pass.
#include <string>
#include <vector>

#include "roller/core/enum_names.hpp"
#include "roller/core/types.hpp"

namespace roller {

struct PassRecord {
  int pass = 0;
  Real max_plastic_increment = 0.0;   // max over the window of the increment of eps_p
  Real mean_plastic_increment = 0.0;  // area-weighted mean over the window
  Real band_plastic_increment = 0.0;  // area-weighted mean over the band at the depth of max shear
  Real surface_ux = 0.0;              // total displacement of the mid-track top node after the pass
  Real surface_uy = 0.0;
  Real surface_dux = 0.0;  // its change over the pass (permanent: the roller has left)
  Real surface_duy = 0.0;
  Real shear_depth = 0.0;                   // 0.78 a below the surface [mm]
  Real residual_shear_strain = 0.0;         // band mean of 2 eps_xy after the pass
  Real residual_shear_increment = 0.0;      // its change over the pass
  Real surface_shear_increment = 0.0;       // the window's top row of elements: change of 2 eps_xy over the pass
  Real peak_pressure = 0.0;                 // largest nodal contact pressure of the pass [MPa]
  Real contact_half_width = 0.0;            // largest a of the pass [mm]
  Real track_start = 0.0, track_end = 0.0;  // x of the window [mm]
  Real creep = 0.0;                         // the roller's creep 1 - omega R / V over the pass's travel
};

enum class ShakedownVerdict { Undetermined, ElasticShakedown, PlasticShakedown, Ratchetting };
template <>
struct EnumNames<ShakedownVerdict> {
  static constexpr std::array<std::pair<ShakedownVerdict, const char*>, 4> names{
      {{ShakedownVerdict::Undetermined, "undetermined"},
       {ShakedownVerdict::ElasticShakedown, "elastic_shakedown"},
       {ShakedownVerdict::PlasticShakedown, "plastic_shakedown"},
       {ShakedownVerdict::Ratchetting, "ratchetting"}}};
};

struct ShakedownClassification {
  ShakedownVerdict verdict = ShakedownVerdict::Undetermined;
  std::string criterion;  // the rule that decided, with the numbers
};

// Thresholds of the classification (docs/scenes.md, passes.csv).
struct ShakedownCriteria {
  int min_passes = 3;
  // Elastic shakedown: the last pass's mean plastic increment below this fraction of the first's
  // (or no plastic strain in the first pass at all).
  Real elastic_fraction = 0.01;
  // Settled: the last pass's mean plastic increment at least this fraction of the pass before.
  // Below it the increments still fall and no verdict is given (run more passes). Measured on the
  // stationary shakedown map (docs/validation.md, "The verdict of passes whose increments still
  // fall"): below Melan's limit the increments of pass 8 are 0.57-0.90 of pass 7's, and stay at
  // 0.90-0.93 a pass to pass 16 (they die out slowly); above it, 0.96-1.00 by pass 8.
  Real settled_ratio = 0.95;
  // Ratchetting: the last pass's net shear strain increment in the band above this fraction of
  // its accumulated plastic shear sqrt(3) d(eps_p) there; below it the cycle is closed. (The
  // shakedown scenes at p0/k = 4.5 and 5.5 add a steady net shear of 15-23 % every pass; a closed
  // cycle's net strain dies out.)
  Real ratchet_fraction = 0.05;
};

ShakedownClassification classify_passes(const std::vector<PassRecord>& passes, const ShakedownCriteria& c = {});

}  // namespace roller
