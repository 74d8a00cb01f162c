#pragma once
// The PNG figures of a command's data, drawn by the checkout's `rollerpy` (matplotlib under
// /usr/bin/python3): the C++ commands write CSV, Python draws.
#include <filesystem>
#include <string>

namespace roller::app {

// Runs `rollerpy <plot_command> <data>`; prints the command instead when `skip` is set or Python or
// the launcher is missing (exit code 0 then), and names it again when the plot fails (exit code 1).
// `who` prefixes the messages ("roller monotonicity").
int render_with_rollerpy(const std::string& plot_command, const std::filesystem::path& data, bool skip,
                         const std::string& who);

std::string shell_quote(const std::string& s);

}  // namespace roller::app
