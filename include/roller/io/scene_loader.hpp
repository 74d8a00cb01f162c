#pragma once
// Reads a TOML scene file (format: docs/scenes.md) into a Scene, validating every value before
// anything is computed. Errors are InputError naming file, line, key, value and what was expected.
#include <filesystem>
#include <string>
#include <vector>

#include "roller/io/scene.hpp"

namespace roller {

// A command-line override "key=value" with a dotted key into the scene's tables
// ("material.E=2e5", "steps.count=3"). The value is read as a TOML value (numbers, booleans,
// quoted or bare strings).
struct SceneOverride {
  std::string key;
  std::string value;
};
SceneOverride parse_override(const std::string& text);  // throws InputError on "key" without '='

Scene load_scene(const std::filesystem::path& file, const std::vector<SceneOverride>& overrides = {});
Scene parse_scene(const std::string& text, const std::filesystem::path& file_name,
                  const std::vector<SceneOverride>& overrides = {});

// Resolves a selector to node indices of `mesh`; throws InputError (naming `context`, e.g.
// "displacement[0].nodes") for unknown sets or numbers outside 1..n_nodes.
std::vector<Index> resolve_nodes(const NodeSelector& selector, const Mesh& mesh, const std::string& context);

// The scene with every default filled in, as TOML: written beside the results so a run can be
// reproduced exactly (MFEM examples print their options).
std::string scene_to_toml(const Scene& scene);

}  // namespace roller
