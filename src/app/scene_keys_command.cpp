// roller scene-keys: every key a scene file may hold, one line each (dotted key, type, default,
// allowed values, meaning), from the declarations the loader reads them with
// (io/scene_keys.hpp). docs/scenes.md explains them at length.
#include <algorithm>
#include <iostream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "commands.hpp"
#include "roller/io/scene_keys.hpp"

namespace roller::app {

Command add_scene_keys_command(CLI::App& app) {
  app.add_subcommand("scene-keys",
                     "list every scene-file key: dotted key, type, default, allowed values, meaning "
                     "(docs/scenes.md)");
  return [] {
    struct Row {
      std::string key, type, default_text, range, doc;
    };
    std::vector<Row> rows{{"key", "type", "default", "allowed", "meaning"}};
    for (const SceneKey& k : scene_keys())
      rows.push_back({k.dotted(), k.type, k.default_text, k.range.empty() ? "-" : k.range, k.doc});
    std::size_t w_key = 0, w_type = 0, w_default = 0, w_range = 0;
    for (const Row& r : rows) {
      w_key = std::max(w_key, r.key.size());
      w_type = std::max(w_type, r.type.size());
      w_default = std::max(w_default, r.default_text.size());
      w_range = std::max(w_range, r.range.size());
    }
    for (const Row& r : rows)
      std::cout << fmt::format("{:<{}}  {:<{}}  {:<{}}  {:<{}}  {}\n", r.key, w_key, r.type, w_type, r.default_text,
                               w_default, r.range, w_range, r.doc);
    return 0;
  };
}

}  // namespace roller::app
