#pragma once
// The message of the InputError a scene text raises ("" when it loads), for tests of bad input.
#include <string>
#include <vector>

#include "roller/core/error.hpp"
#include "roller/io/scene_loader.hpp"

namespace roller::test {

inline std::string error_of(const std::string& text, const std::vector<SceneOverride>& overrides = {}) {
  try {
    parse_scene(text, "bad.toml", overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace roller::test
