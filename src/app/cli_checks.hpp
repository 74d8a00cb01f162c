#pragma once
// Checks of command-line values shared by the sub-commands (docs/reliability.md): numbers that
// must be finite, and the files a user names for roller to write.
#include <string>

#include <CLI/CLI.hpp>

namespace roller::app {

// A finite number (CLI11's Range lets nan through: every comparison with it is false).
CLI::Validator finite_number();
// A finite number in [lo, hi].
CLI::Validator finite_range(double lo, double hi);

// A file the user names for roller to write (`option` names it in messages, e.g. "--csv"):
// refused with InputError when the name is empty, when something other than a regular file
// stands there (a folder, a device, a FIFO, a socket, a symbolic link: roller never writes
// through or replaces them), or when its folder does not exist. Called before computing, so a bad
// name costs nothing; the file itself is then written atomically (io/atomic_file.hpp).
void check_output_file(const std::string& path, const std::string& option);

}  // namespace roller::app
