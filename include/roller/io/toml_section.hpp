#pragma once
// Typed, checked access to one table of a TOML scene file. Every read records the key; finish()
// rejects keys that were never read (typos), suggesting the closest known key. All errors are
// InputError with "file:line: key = value: expected ..." so a user can fix the file at once.
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "roller/core/enum_names.hpp"
#include "roller/core/types.hpp"

namespace roller {

class TomlSection {
 public:
  // `path` is the dotted name of the table in the file ("" for the root, "mesh", "displacement[2]").
  TomlSection(const toml::table& table, std::string path, std::filesystem::path file);

  bool has(const std::string& key) const;
  std::vector<std::string> keys() const;             // sorted by name
  std::optional<Real> real(const std::string& key);  // accepts integers too
  std::optional<Index> integer(const std::string& key);
  std::optional<bool> boolean(const std::string& key);
  std::optional<std::string> string(const std::string& key);
  std::optional<std::vector<Real>> real_array(const std::string& key);
  std::optional<TomlSection> table(const std::string& key);
  std::vector<TomlSection> table_array(const std::string& key);  // [[key]] blocks, empty if absent
  // The raw node, for keys that accept several types (e.g. a number or a table).
  const toml::node* node(const std::string& key);

  // A string that must be one of `choices` (an option enum's names: core/enum_names.hpp); the
  // error lists them.
  std::optional<std::string> choice(const std::string& key, const std::vector<std::string>& choices);

  // Checked getters with a default.
  Real real_or(const std::string& key, Real fallback) { return real(key).value_or(fallback); }

  // Throws InputError for the first key that was never read.
  void finish() const;
  // Declares keys as known without reading them, so finish() can run before they are read
  // (the root checks its table names first: "[meshes]" is a typo, not a missing [mesh]).
  void allow(const std::vector<std::string>& keys) { read_.insert(keys.begin(), keys.end()); }
  // Re-throws a struct's is_valid() message "<prefix>.<field> = <value>: <rule>" as an error
  // at the scene key that holds the field (`key_of_field` maps field names to scene keys where
  // they differ).
  [[noreturn]] void fail_invalid(const std::string& why,
                                 const std::vector<std::pair<std::string, std::string>>& key_of_field) const;

  // Error helpers for callers that validate values: "file:line: path.key = value: <expected>".
  [[noreturn]] void fail(const std::string& key, const std::string& expected) const;
  std::string where(const std::string& key) const;  // "file:line: path.key"
  const std::string& path() const { return path_; }
  const std::filesystem::path& file() const { return file_; }

 private:
  std::string full_key(const std::string& key) const;
  std::string value_text(const std::string& key) const;
  const toml::table* table_;
  std::string path_;
  std::filesystem::path file_;
  std::set<std::string> read_;
};

// Levenshtein distance, for "did you mean" suggestions.
std::size_t edit_distance(const std::string& a, const std::string& b);

}  // namespace roller
