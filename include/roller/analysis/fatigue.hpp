#pragma once
// Fatigue of the stabilised pass (docs/model.md, Fatigue): the indices rolling-contact fatigue is
// judged by, from one material point's stress cycle (plane strain, [xx, yy, zz, xy] in MPa, tension
// positive) and from the pass's load. Pure maths: no mesh, no run.
//   Dang Van: the mesoscopic stress s(t) - s* (s* the centre of the smallest ball holding the
//     deviatoric path), its Tresca shear tau(t) and the hydrostatic stress sigma_h(t);
//     index max_t [tau(t) + a_DV sigma_h(t)] / tau_w (> 1: initiation).
//   Ekberg, Kabo & Andersson (2002), subsurface: FI_sub = tau_eq,a + a_DV sigma_h,max with
//     tau_eq,a half the longest chord of the path in sqrt(J2); against tau_e (> 1: initiation).
//   Ekberg et al., surface: FI_surf = f - k/p0 (line contact; > 0: surface initiation).
//   Kapoor's ratchetting life: passes to initiation = gamma_c / (shear strain per pass).
#include <string>
#include <vector>

#include "roller/core/types.hpp"

namespace roller {

// The criteria's parameters (the scene's [fatigue]).
struct FatigueParams {
  Real dang_van_a = 0.0;             // a_DV [-] >= 0, the hydrostatic stress's weight
  Real dang_van_limit = 0.0;         // tau_w [MPa] > 0: Dang Van's shear fatigue limit
  Real shear_fatigue_limit = 0.0;    // tau_e [MPa] > 0: Ekberg's subsurface limit
  Real critical_shear_strain = 0.0;  // gamma_c [-] > 0: the ductility Kapoor's ratchetting exhausts
  // True when every field is admissible; otherwise false and *why names the key, its value and the rule.
  bool is_valid(std::string* why) const;
};

struct DangVan {
  Vec4 centre = Vec4::Zero();  // s*: the centre of the deviatoric path (a deviator) [MPa]
  Real radius = 0.0;           // the path's ball's radius in sqrt(J2) [MPa]
  Real value = 0.0;            // max_t tau + a sigma_h [MPa]
  Real shear = 0.0;            // tau at that instant [MPa]
  Real hydrostatic = 0.0;      // sigma_h at that instant [MPa]
  int instant = 0;             // which sample of the cycle
};
DangVan dang_van(const std::vector<Vec4>& cycle, Real a);

struct EkbergSubsurface {
  Real shear_amplitude = 0.0;  // tau_eq,a [MPa]
  Real max_hydrostatic = 0.0;  // sigma_h,max [MPa]
  Real value = 0.0;            // FI_sub = tau_eq,a + a sigma_h,max [MPa]
};
EkbergSubsurface ekberg_subsurface(const std::vector<Vec4>& cycle, Real a);

// Ekberg et al.'s surface index of a line contact: the traction coefficient f = |Q|/P less k/p0.
Real ekberg_surface(Real traction_coefficient, Real p0, Real shear_yield);

// Kapoor's passes to initiation: gamma_c over the magnitude of the shear strain a pass adds
// (infinite when the pass adds none).
Real ratchetting_life(Real shear_strain_per_pass, Real critical_shear_strain);

// The Tresca shear (sigma_1 - sigma_3)/2 of a plane-strain tensor [xx, yy, zz, xy].
Real tresca_shear(const Vec4& t);

// One depth's stress over a pass: the material point's cycle (element means of a column).
struct DepthCycle {
  Real depth = 0.0;  // [mm]
  std::vector<Vec4> stress;
};

// What a pass's load and surface give the surface indices.
struct PassSurface {
  Real traction_coefficient = 0.0;   // |Q|/P of the pass's largest normal force
  Real peak_pressure = 0.0;          // Hertz's p0 of that force [MPa]
  Real shear_yield = 0.0;            // k: the surface material's lowest yield stress / sqrt3 [MPa]
  Real shear_strain_per_pass = 0.0;  // the top layer's change of 2 eps_xy over the pass
};

struct FatigueAtDepth {
  Real depth = 0.0;
  DangVan dang_van;
  Real dang_van_index = 0.0;  // value / tau_w
  EkbergSubsurface subsurface;
  Real subsurface_index = 0.0;  // FI_sub / tau_e
};

// The indices of one pass: by depth, and at the surface.
struct PassFatigue {
  int pass = 0;
  Real x = 0.0;  // of the column the cycles were taken at [mm]
  std::vector<FatigueAtDepth> depths;
  PassSurface surface;
  Real surface_index = 0.0;     // FI_surf
  Real ratchetting_life = 0.0;  // Kapoor's passes to initiation (infinite: no ratchet)
  int dang_van_row = -1;        // the depth of the largest Dang Van index (-1: no depth)
  int subsurface_row = -1;      // the depth of the largest FI_sub index
};
PassFatigue pass_fatigue(const FatigueParams& p, int pass, Real x, const std::vector<DepthCycle>& cycles,
                         const PassSurface& surface);

// A pass's answer: its governing indices (summary.json's fatigue block and the console's line).
struct FatigueAnswer {
  int pass = 0;
  Real dang_van_index = 0.0, dang_van_depth = 0.0;
  Real subsurface_index = 0.0, subsurface_depth = 0.0;
  Real surface_index = 0.0;
  Real traction_coefficient = 0.0, peak_pressure = 0.0, shear_yield = 0.0;
  Real shear_strain_per_pass = 0.0;
  Real ratchetting_life = 0.0;  // infinite: no ratchet
};
FatigueAnswer answer_of(const PassFatigue& f);
// One line: which mechanism governs and whether it initiates, with the numbers.
std::string describe(const FatigueAnswer& a);

}  // namespace roller
