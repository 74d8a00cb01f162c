#pragma once
// The output folder of a fresh run (docs/scenes.md, Output): a folder of this scene's earlier run
// is reused with its old outputs cleared (no step files of another run left beside the new ones);
// any other folder that is not empty is refused unless the user asks to overwrite it.
#include <filesystem>
#include <string>

namespace roller {

// Throws InputError when `dir` holds files but is not an output folder of the scene `scene_name`
// and `overwrite` is false. Otherwise creates it and removes the files a run writes (CSV tables,
// VTU/PVD fields, state files, summary, resolved scene); other files (e.g. plots) stay.
void prepare_output_folder(const std::filesystem::path& dir, const std::string& scene_name, bool overwrite);

// Whether `name` is a file a run writes into its output folder.
bool is_run_output(const std::string& name);

}  // namespace roller
