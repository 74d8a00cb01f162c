#include "rollerpy_plot.hpp"

#include <cstdlib>
#include <iostream>

#include <fmt/format.h>

namespace roller::app {

namespace fs = std::filesystem;

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char ch : s) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return q + "'";
}

int render_with_rollerpy(const std::string& plot_command, const fs::path& data, bool skip, const std::string& who) {
  static const char* const kPython = "/usr/bin/python3";
  const fs::path script = fs::path(ROLLER_SOURCE_DIR) / "rollerpy";
  const std::string command =
      fmt::format("{} {} {}", shell_quote(script.string()), plot_command, shell_quote(data.string()));
  if (skip) {
    std::cout << who << ": PNG not rendered (--no-plot); run: " << command << "\n";
    return 0;
  }
  if (!fs::exists(kPython) || !fs::exists(script)) {
    std::cout << who << ": " << kPython << " or " << script.string() << " not found; render the PNG with: " << command
              << "\n";
    return 0;
  }
  std::cout.flush();
  if (std::system(command.c_str()) != 0) {
    std::cerr << who << ": plotting failed (the data are in " << data.string() << "); rerun: " << command << "\n";
    return 1;
  }
  return 0;
}

}  // namespace roller::app
