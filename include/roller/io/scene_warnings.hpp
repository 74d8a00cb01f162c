#pragma once
// Values a scene may hold legally that are almost surely a slip of units or of scale (roller works
// in mm, N, MPa, s): each warning names the key, the value and what was likely meant. They do not
// stop the run; `roller run` prints them and summary.json lists them.
#include <string>
#include <vector>

#include "roller/io/scene.hpp"
#include "roller/mesh/mesh.hpp"

namespace roller {

std::vector<std::string> scene_warnings(const Scene& scene, const Mesh& mesh);

// A slip of units that would give a wrong answer rather than a failed step is an error: a
// segment's force whose Hertz contact on the top surface's modulus is wider than the strip (a
// modulus in Pa, a force in N rather than N/mm) would spread the load off the strip. Throws
// InputError naming the key, the value and the likely unit.
void check_load_fits_strip(const Scene& scene);

// A traction ratio (roller.path q_over_p), or a horizontal force fx beyond mu times the vertical
// force at a segment's end, cannot be carried by a rolling roller: InputError before computing,
// naming both.
void check_traction_below_friction(const Scene& scene);

}  // namespace roller
