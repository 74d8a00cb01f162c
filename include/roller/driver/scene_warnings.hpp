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

}  // namespace roller
