#pragma once
// The thesis's numerical study of operator A (thesis Fig. 3.1 a-l; docs/monotonicity.md, "The
// maps"): positive definiteness of A = C + T over the 4-D grid (sigma_pl, a, b, c) and on the
// twelve 2-D slices.
//
// At a grid point the stress is built from (a, b, c) (t33 by OutOfPlaneStress), C is the
// plastic branch C^E - 2G beta s s^T with beta = 3/(2 sigma_pl^2 (1 + H'/3G)) whatever the
// yield function says (the thesis's (3.4) depends on the deviator and sigma_pl separately, and
// its maps cover points off the yield surface), T is (3.5) in MPa, all in MPa (no rescaling
// of T against C). A slice of Fig. 3.1 is taken at one yield stress (the thesis's captions
// say s = 40 MPa for every panel).
#include <string>
#include <vector>

#include "roller/analysis/monotonicity.hpp"

namespace roller {

struct GridAxis {
  Real lo = 0.0;
  Real hi = 0.0;
  int n = 1;  // points, >= 1 (n = 1: lo only)
  Real value(int i) const { return n > 1 ? lo + (hi - lo) * i / (n - 1) : lo; }
};

struct MonotonicityMapOptions {
  Real youngs_modulus = 2.1e5;         // E [MPa]
  Real poisson_ratio = 0.3;            // nu
  Real tangent_modulus = 2.1e5 / 3.0;  // E_T [MPa], 0 <= E_T < E
  GridAxis sigma{5.0, 105.0, 21};      // sigma_pl [MPa], > 0
  GridAxis a{-150.0, 150.0, 21};       // a = 2 t11 - t22 [MPa]
  GridAxis b{-150.0, 150.0, 21};       // b = 2 t22 - t11 [MPa]
  GridAxis c{-50.0, 50.0, 21};         // c = t12 [MPa]
  GradientLayout layout = GradientLayout::Thesis;
  OutOfPlaneStress out_of_plane = OutOfPlaneStress::Zero;
  Real mass_scale = 0.0;  // rho h^2/dt^2 [MPa]; 0 = quasistatic

  // The material of the study (plastic, yield stress sigma.lo; the sweep sets sigma_pl itself).
  MaterialParams material() const;
  // False with *why naming the field, its value and the rule when an option is inadmissible.
  bool is_valid(std::string* why) const;
};

struct MapPoint {
  Real sigma_pl = 0.0;
  ThesisParameters p;
  Definiteness d;
};

// A at one point of the study.
Mat4 map_operator(const MonotonicityMapOptions& options, Real sigma_pl, const ThesisParameters& p);
MapPoint evaluate_map_point(const MonotonicityMapOptions& options, Real sigma_pl, const ThesisParameters& p);

// The whole grid; order: sigma slowest, then a, then b, c fastest. Throws InputError for
// invalid options.
std::vector<MapPoint> sweep_grid(const MonotonicityMapOptions& options);

// Planes of Fig. 3.1: (a, b) at fixed c; (c, a) at fixed b; (c, b) at fixed a.
enum class SlicePlane { AB, CA, CB };

struct MapSlice {
  std::string id;  // thesis panel letter, "a" ... "l"
  SlicePlane plane;
  Real fixed;                    // value of the third parameter [MPa]
  std::string describe() const;  // e.g. "(a,b) plane, c = -5 MPa"
};

// The twelve panels: (a,b) for c = 0, -5, -10, -15, -20, +10 (a-f); (c,a) for b = 0, -75,
// -105, +105 (g-j); (c,b) for a = 0, -75 (k, l).
std::vector<MapSlice> thesis_slices();

// n_first x n_second points over the slice's two axes (ranges from options), at yield stress
// sigma_pl. First axis: a for AB and CA, b for CB (slowest); second: b for AB, c otherwise.
std::vector<MapPoint> sweep_slice(const MonotonicityMapOptions& options, const MapSlice& slice, Real sigma_pl,
                                  int n_first, int n_second);

}  // namespace roller
