#pragma once
// Every key of a scene file, declared once (src/io/scene_keys.cpp): its dotted name, type,
// default, allowed values, one line of documentation, and how it is read and written. The
// loader (load_scene), the writer of the resolved scene (scene_to_toml), the "did you mean"
// suggestions for unknown keys, `roller scene-keys` and the test that docs/scenes.md mentions
// every key all walk these two lists. docs/scenes.md stays the user's reference.
#include <string>
#include <vector>

#include "roller/io/scene_key_types.hpp"

namespace roller {

const std::vector<SceneTable>& scene_tables();
const std::vector<SceneKey>& scene_keys();  // grouped by table, in reading order

// The table of a given path (throws std::out_of_range for an undeclared one), its keys and its
// direct sub-tables in declaration order.
const SceneTable& scene_table(const std::string& path);
std::vector<const SceneKey*> keys_of(const std::string& table);
std::vector<const SceneTable*> sub_tables_of(const std::string& table);

}  // namespace roller
