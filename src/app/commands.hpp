#pragma once
// Sub-commands of the roller CLI. Each registers itself on the app and returns a callable
// that runs it (returning the process exit code) when its sub-command was chosen.
#include <functional>

#include <CLI/CLI.hpp>

namespace roller::app {

using Command = std::function<int()>;

// roller monotonicity ... (docs/monotonicity.md): maps of the positive definiteness of operator A.
Command add_monotonicity_command(CLI::App& app);

// roller scene-keys: every scene-file key with its type, default, allowed values and meaning.
Command add_scene_keys_command(CLI::App& app);

// roller shakedown-limit SCENE: Melan's bound from one elastic solution (docs/model.md).
Command add_shakedown_limit_command(CLI::App& app);

// roller output-columns: every CSV table's columns with their units.
Command add_output_columns_command(CLI::App& app);

}  // namespace roller::app
