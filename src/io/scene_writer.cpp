// scene_to_toml: the resolved scene (every default filled in) in the scene-file format, written
// key by key from the declarations of io/scene_keys.hpp.
#include <sstream>

#include <toml++/toml.h>

#include "roller/io/scene_keys.hpp"
#include "roller/io/scene_loader.hpp"

namespace roller {

namespace {

void write_table(const SceneTable& table, toml::table& out, const Scene& scene, std::size_t block) {
  for (const SceneKey* k : keys_of(table.path)) k->write(out, scene, block);
  for (const SceneTable* sub : sub_tables_of(table.path)) {
    const std::size_t n = sub->count ? sub->count(scene) : 1;
    if (sub->array) {
      toml::array blocks;
      for (std::size_t i = 0; i < n; ++i) {
        toml::table t;
        write_table(*sub, t, scene, i);
        blocks.push_back(std::move(t));
      }
      if (n > 0) out.insert(sub->name(), std::move(blocks));
    } else if (n > 0) {
      toml::table t;
      write_table(*sub, t, scene, block);
      out.insert(sub->name(), std::move(t));
    }
  }
}

}  // namespace

std::string scene_to_toml(const Scene& scene) {
  toml::table root;
  write_table(scene_table(""), root, scene, 0);
  std::ostringstream out;
  out << "# Resolved scene: every value roller used, defaults included.\n" << root << "\n";
  // Forces given as pressures (roller.path.p0, p0_over_k) appear as the fy they gave, and how.
  if (scene.roller)
    for (std::size_t i = 0; i < scene.roller->path.size(); ++i)
      if (!scene.roller->path[i].fy_origin.empty())
        out << "# roller.path[" << i << "].fy = " << *scene.roller->path[i].fy << " N/mm from "
            << scene.roller->path[i].fy_origin << "\n";
  return out.str();
}

}  // namespace roller
