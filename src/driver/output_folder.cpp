#include "output_folder.hpp"

#include <regex>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "roller/core/error.hpp"

namespace roller {

namespace {

// The scene name recorded in the folder's scene.resolved.toml ("" when there is none).
std::string recorded_scene(const std::filesystem::path& dir) {
  const std::filesystem::path resolved = dir / "scene.resolved.toml";
  std::error_code ec;
  if (!std::filesystem::is_regular_file(resolved, ec)) return "";
  try {
    return toml::parse_file(resolved.string())["name"].value_or(std::string());
  } catch (const toml::parse_error&) {
    return "";
  }
}

}  // namespace

bool is_run_output(const std::string& name) {
  static const std::regex pattern(
      R"((fields\.pvd|roller\.pvd|roller_\d{4}(_loaded)?\.vt[pu]|solver\.csv|contact\.csv|roller\.csv|passes\.csv|residual_depth\.csv|fatigue\.csv|passes\.png|)"
      R"(residual_depth\.png|summary\.json|scene\.resolved\.toml|)"
      R"(checkpoint\.cbor|state_final\.cbor|state_\d{4}\.cbor|step_\d{4}(_loaded)?\.vtu)(\.tmp)?)");
  return std::regex_match(name, pattern);
}

void prepare_output_folder(const std::filesystem::path& dir, const std::string& scene_name, bool overwrite) {
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec))
    throw InputError(fmt::format("--out {}: not a folder", dir.string()));
  try {
    if (!std::filesystem::exists(dir)) {
      std::filesystem::create_directories(dir);
      return;
    }
    const bool empty = std::filesystem::is_empty(dir);
    const std::string recorded = recorded_scene(dir);
    if (!empty && recorded != scene_name && !overwrite)
      throw InputError(fmt::format(
          "--out {}: the folder is not empty and holds no output of scene '{}'{}; expected a new or empty folder, "
          "this scene's earlier output, or --overwrite (which removes the run files in it)",
          dir.string(), scene_name, recorded.empty() ? "" : fmt::format(" (it holds scene '{}')", recorded)));
    for (const auto& entry : std::filesystem::directory_iterator(dir))
      if (entry.is_regular_file() && is_run_output(entry.path().filename().string()))
        std::filesystem::remove(entry.path());
  } catch (const std::filesystem::filesystem_error& e) {
    // Not a place for a folder (under a file, in /proc, a name too long) or not writable: the
    // user's path (exit 2); a full disk or an I/O error: the machine's (exit 3).
    throw_file_error(fmt::format("--out {}: cannot use it as the output folder ({})", dir.string(),
                                 e.path1().empty() ? dir.string() : e.path1().string()),
                     e.code().value());
  }
}

}  // namespace roller
