#pragma once
// The roller executable run as a user runs it: exit code and everything it printed.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

namespace roller::test {

struct Run {
  int exit_code;
  std::string output;
};

inline Run run_roller(const std::string& args) {
  // Unique per process and call: CTest runs test cases in parallel processes.
  static int calls = 0;
  const std::filesystem::path log =
      std::filesystem::temp_directory_path() /
      std::filesystem::path("roller_cli_test_" + std::to_string(::getpid()) + "_" + std::to_string(++calls) + ".log");
  const std::string cmd = std::string(ROLLER_ROLLER_EXE) + " " + args + " > " + log.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  std::ifstream in(log);
  std::stringstream s;
  s << in.rdbuf();
  std::filesystem::remove(log);
  return {WEXITSTATUS(status), s.str()};
}

}  // namespace roller::test
