#pragma once
// A run continued from a step it saved, as if it had been killed after that step.
#include <filesystem>
#include <string>

#include <fmt/format.h>

#include "run_roller.hpp"

namespace roller::test {

// The run `run` (a roller command line ending in "--out ") as if killed after step `step`: a copy
// of its finished folder `whole` in `split`, with that step's state as the checkpoint, continued
// with --resume (which drops the rows after the step and recomputes them).
inline Run resume_copy(const std::string& run, const std::filesystem::path& whole, const std::filesystem::path& split,
                       int step) {
  namespace fs = std::filesystem;
  fs::copy(whole, split);
  fs::copy_file(whole / fmt::format("state_{:04d}.cbor", step), split / "checkpoint.cbor",
                fs::copy_options::overwrite_existing);
  return run_roller(run + split.string() + " --resume");
}

}  // namespace roller::test
