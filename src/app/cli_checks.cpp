#include "cli_checks.hpp"

#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "roller/core/error.hpp"

namespace roller::app {

namespace fs = std::filesystem;

namespace {

// The value as a finite double, or the reason it is not one ("" when it is).
std::string finite_or_why(const std::string& text, double* value) {
  double v = 0.0;
  if (!CLI::detail::lexical_cast(text, v)) return fmt::format("'{}' is not a number", text);
  if (!std::isfinite(v)) return fmt::format("{}: expected a finite number", text);
  *value = v;
  return "";
}

}  // namespace

CLI::Validator finite_number() {
  return CLI::Validator(
      [](std::string& text) {
        double v = 0.0;
        return finite_or_why(text, &v);
      },
      "FINITE");
}

CLI::Validator finite_range(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) {
        double v = 0.0;
        if (std::string why = finite_or_why(text, &v); !why.empty()) return why;
        if (v < lo || v > hi) return fmt::format("{}: expected a number in [{:g}, {:g}]", text, lo, hi);
        return std::string();
      },
      fmt::format("FINITE in [{:g} - {:g}]", lo, hi));
}

void check_output_file(const std::string& path, const std::string& option) {
  if (path.empty()) throw InputError(fmt::format("{} '': expected a file name", option));
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(path, ec);
  if (!ec && fs::exists(status) && !fs::is_regular_file(status)) {
    const char* what = fs::is_directory(status)                                     ? "a folder"
                       : fs::is_symlink(status)                                     ? "a symbolic link"
                       : fs::is_fifo(status)                                        ? "a FIFO"
                       : fs::is_socket(status)                                      ? "a socket"
                       : fs::is_block_file(status) || fs::is_character_file(status) ? "a device"
                                                                                    : "not a regular file";
    throw InputError(fmt::format(
        "{} {}: {} stands there; roller writes a new or a regular file only and never replaces anything else "
        "(expected a file name such as limit.csv)",
        option, path, what));
  }
  const fs::path folder = fs::path(path).parent_path();
  if (!folder.empty() && !fs::is_directory(folder, ec))
    throw InputError(
        fmt::format("{} {}: the folder {} does not exist (create it first)", option, path, folder.string()));
}

}  // namespace roller::app
