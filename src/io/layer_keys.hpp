#pragma once
// The scene keys of layered strips (docs/scenes.md, `[[layer]]`): material.yield_profile,
// mesh.follow_layers, and the [[layer]] table, whose keys are every [material] key read into a
// copy of [material] (so a key the [material] table gains is a layer key too) plus thickness.
// Internal to io/scene_keys.cpp.
#include <vector>

#include "roller/io/scene_key_types.hpp"

namespace roller {

// Appends material.yield_profile, mesh.follow_layers, layer.thickness and a layer twin of every
// [material] key declared in `keys` so far.
void add_layer_keys(std::vector<SceneKey>& keys);

// Makes `table` the [[layer]] array: each block a copy of [material], checked like it.
void declare_layer_table(SceneTable& table);

// Fails at mesh.height when the layers together are thicker than the strip (in [mesh]'s check).
void check_layers_fit(TomlSection& mesh_section, const Scene& scene);

// Fails at dynamics.strip_inertia when a layer has no density (in [dynamics]' check).
void check_layers_have_density(TomlSection& dynamics_section, const Scene& scene);

}  // namespace roller
