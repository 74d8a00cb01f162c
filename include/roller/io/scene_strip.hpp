#pragma once
// The scene's strip made (its mesh, each element of its centroid's layer), once the scene's load
// is known to fit it and the machine to hold the run it starts, and the nodes that may touch the
// roller.
#include <memory>
#include <vector>

#include "roller/assembly/strip_model.hpp"
#include "roller/io/scene.hpp"

namespace roller {

// InputError for a load wider than the strip or a traction beyond friction (io/scene_warnings.hpp),
// SystemError with advice when the machine cannot hold the run. The dof map is the caller's to set.
std::unique_ptr<StripModel> make_scene_strip(const Scene& scene);

// The nodes that may touch the roller (contact.candidates); none without a roller.
std::vector<Index> contact_candidate_nodes(const Scene& scene, const Mesh& mesh);

}  // namespace roller
