#pragma once
// Scenes from Python values: a dict of the scene file's tables (docs/scenes.md) and overrides
// {"key": value} with --set's dotted keys, path segments included ("roller.path[1].fy"). The
// dict is written as TOML and read by the scene loader, so it is checked exactly as a file is.
#include <filesystem>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>

#include "roller/io/scene_loader.hpp"

namespace roller::python {

// A Python value as TOML text: bool, int, float, str, list (an array, or an array of tables when
// it holds dicts) and dict (an inline table); anything else is an InputError naming `key`.
std::string toml_text(const pybind11::handle& value, const std::string& key);
// The dict as a TOML document (its top-level dicts become tables).
std::string toml_document(const pybind11::dict& scene);
std::vector<SceneOverride> overrides_of(const pybind11::dict& set);

}  // namespace roller::python
