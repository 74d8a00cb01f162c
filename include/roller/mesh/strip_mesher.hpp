#pragma once
// Structured meshes of the strip L x H (bottom edge on y = 0 = the symmetry plane, left edge
// on x = 0): docs/model.md, Geometry and units; the thesis's meshes in docs/thesis-meshes.md.
#include <string>
#include <vector>

#include "roller/mesh/mesh.hpp"

namespace roller {

// Spacing of the grid lines along one axis.
struct Grading {
  enum class Kind {
    Uniform,    // equal intervals
    Geometric,  // intervals grow geometrically away from `focus` (finest at focus)
  };
  Kind kind = Kind::Uniform;
  Real ratio = 1.0;  // Geometric: ratio of the largest to the smallest interval (>= 1)
  Real focus = 0.0;  // Geometric: coordinate [mm] where the mesh is finest (may be inside the
                     // strip, then both sides grade away from it, or at either end)
};

// Diagonal used to split each quad into two T3 triangles.
enum class Diagonal { Rising, Falling, Alternating };
template <>
struct EnumNames<Diagonal> {
  static constexpr std::array<std::pair<Diagonal, const char*>, 3> names{
      {{Diagonal::Rising, "rising"}, {Diagonal::Falling, "falling"}, {Diagonal::Alternating, "alternating"}}};
};

struct StripMeshSpec {
  ElementType element = ElementType::Q4;
  Real length = 100.0;  // L_s [mm]
  Real height = 20.0;   // H: half-thickness of the strip [mm]
  int nx = 10;          // elements along x (before refinement)
  int ny = 4;           // elements along y (before refinement)
  Grading grading_x;
  Grading grading_y;
  // Explicit grid lines (strictly increasing, from 0 to length/height). When given they
  // replace nx/grading along that axis; refinement subdivides every interval equally.
  std::vector<Real> x_lines;
  std::vector<Real> y_lines;
  // Heights y [mm] the horizontal grid lines must include (layer boundaries, [mesh]
  // follow_layers): before refinement, the line nearest to each is moved onto it when closer than
  // 0.3 of its interval, else a line is added there (pin_lines).
  std::vector<Real> pinned_y;
  Diagonal diagonal = Diagonal::Rising;
  int refine = 1;  // every interval is split into `refine` equal parts (>= 1)
  // The right edge is the left edge: the strip repeats along x with period `length` (a ring, an
  // endless track; Mesh::period).
  bool periodic = false;

  bool is_valid(std::string* why) const;
};

// Number of nodes the mesh will have, computed without building it (a Real: nx * refine of a
// hostile scene overflows an int).
Real strip_node_count(const StripMeshSpec& spec);

// Builds the mesh with the numbering documented in mesh.hpp and the named node sets.
Mesh make_strip_mesh(const StripMeshSpec& spec);

// `lines` (strictly increasing, ends fixed) with every value of `pins` strictly inside them on a
// line: an inner line within 0.3 of its neighbouring interval of a pin moves onto it, otherwise
// the pin is added as a line; pins outside (first, last) are ignored.
std::vector<Real> pin_lines(std::vector<Real> lines, const std::vector<Real>& pins);

// Grid line coordinates along one axis (n intervals over [0, extent] with the grading), exposed
// for tests and for scenes that inspect the spacing.
std::vector<Real> grid_lines(Real extent, int n, const Grading& grading);

}  // namespace roller
