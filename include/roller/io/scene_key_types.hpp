#pragma once
// What a scene-file table and key are (SceneTable, SceneKey): the shapes that the declarations
// of every key (scene_keys.hpp) are made of.
#include <cstddef>
#include <functional>
#include <string>

#include <toml++/toml.h>

#include "roller/io/scene.hpp"
#include "roller/io/toml_section.hpp"

namespace roller {

// A table of the scene file: "" (the root), "mesh", "contact.ipopt", or an array of tables
// ("displacement", "roller.path": [[...]] blocks). Listed parents first; a table's sub-tables
// are read after its own keys, in the order of the list.
struct SceneTable {
  std::string path;      // dotted
  bool array = false;    // [[path]] blocks
  std::string required;  // non-empty: the table must be present, and this says what it holds
  // Reading, when the table (each block of an array) is present, before its keys: makes what
  // they are read into (the roller, its suspension, a path segment), or rejects the table.
  std::function<void(TomlSection&, Scene&)> enter;
  // Reading, after its keys and sub-tables: the rules relating several fields (the structs'
  // is_valid), reported at the key that holds the field. `block` is the index of the block.
  std::function<void(TomlSection&, Scene&, std::size_t block)> check;
  // Writing: the number of blocks of an array, 0 or 1 for a table (absent: always written).
  std::function<std::size_t(const Scene&)> count;

  std::string name() const;    // the last component of path ("ipopt")
  std::string parent() const;  // path without its last component ("contact")
};

// One key. In an array of tables, `block` selects the block (0 elsewhere).
struct SceneKey {
  std::string table;         // path of its SceneTable
  std::string name;          // the key within that table
  std::string type;          // "number", "integer", "bool", "string", "choice", or a shape ("table", ...)
  std::string default_text;  // as written in a scene, or what an absent key means
  std::string range;         // allowed values ("> 0", "0 <= nu < 0.5", "\"Q4\" | \"T3\""); "" = any
  std::string doc;           // one line
  // Reads the key (absent: its default) from the section of its table, checking its type and range.
  std::function<void(TomlSection&, Scene&, std::size_t block)> read;
  // Inserts the key's resolved value into the table being written (nothing when it has none).
  std::function<void(toml::table&, const Scene&, std::size_t block)> write;

  // "mesh.nx", "roller.path[].dx" (a key of every [[roller.path]] block).
  std::string dotted() const;
};

}  // namespace roller
