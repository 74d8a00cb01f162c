// What the command line refuses before computing and what it never touches (docs/reliability.md):
// numbers that are not finite, files named for writing that are not regular files, a --resume
// with nothing to resume, a load that does not fit on the strip.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "../support/run_roller.hpp"
#include "../support/temp_files.hpp"
#include "roller/core/error.hpp"
#include "roller/driver/simulation.hpp"
#include "roller/io/atomic_file.hpp"

namespace fs = std::filesystem;
using Catch::Contains;
using roller::test::Run;
using roller::test::run_roller;

TEST_CASE("roller shakedown-limit: nan and inf are refused by --traction as out of range", "[app][errors]") {
  for (const char* value : {"nan", "inf", "-inf", "NaN"}) {
    const Run r = run_roller(std::string("shakedown-limit problems/shakedown_p45.toml --traction ") + value);
    INFO(r.output);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.output, Contains("--traction") && Contains("finite"));
  }
}

TEST_CASE("roller shakedown-limit writes --csv and --json only as new or regular files", "[app][errors][output]") {
  roller::test::TempDir dir("roller_cli_targets");
  const std::string base = "shakedown-limit problems/shakedown_thin_strip.toml ";
  // A FIFO, a symbolic link (to a file it must not change) and a folder: refused before computing
  // and left as they were.
  const fs::path fifo = dir.path() / "fifo", link = dir.path() / "link", victim = dir.path() / "victim.csv";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  { std::ofstream(victim) << "keep me\n"; }
  fs::create_symlink(victim, link);
  for (const char* option : {"--csv", "--json"}) {
    for (const fs::path& target : {fifo, link, dir.path()}) {
      const Run r = run_roller(base + option + " " + target.string());
      INFO(r.output);
      CHECK(r.exit_code == 2);
      CHECK_THAT(r.output, Contains(option) && Contains("never replaces"));
      CHECK_THAT(r.output, !Contains("shakedown limit of"));  // refused before computing
    }
    const Run empty = run_roller(base + option + " ''");
    CHECK(empty.exit_code == 2);
    CHECK_THAT(empty.output, Contains(std::string(option) + " ''") && Contains("expected a file name"));
    const Run no_folder = run_roller(base + option + " " + (dir.path() / "absent" / "x").string());
    CHECK(no_folder.exit_code == 2);
    CHECK_THAT(no_folder.output, Contains("does not exist"));
  }
  CHECK(fs::is_fifo(fs::symlink_status(fifo)));
  CHECK(fs::is_symlink(fs::symlink_status(link)));
  CHECK(roller::test::read_text(victim) == "keep me\n");
  // A regular file is replaced whole.
  const fs::path csv = dir.path() / "limit.csv";
  { std::ofstream(csv) << "old\n"; }
  const Run ok = run_roller(base + "--csv " + csv.string());
  INFO(ok.output);
  CHECK(ok.exit_code == 0);
  CHECK_THAT(roller::test::read_text(csv), Catch::StartsWith("depth_mm,"));
}

TEST_CASE("a file written atomically is never written through what stands at its temporary name",
          "[io][output][errors]") {
  roller::test::TempDir dir("roller_atomic");
  const fs::path target = dir.path() / "out.json", tmp = dir.path() / "out.json.tmp";
  const fs::path victim = dir.path() / "victim";
  { std::ofstream(victim) << "keep me\n"; }
  fs::create_symlink(victim, tmp);
  CHECK_THROWS_AS(roller::write_file_atomically(target, "{}\n"), roller::InputError);
  CHECK(roller::test::read_text(victim) == "keep me\n");
  fs::remove(tmp);
  REQUIRE(::mkfifo(tmp.c_str(), 0600) == 0);  // would block an open for writing for ever
  CHECK_THROWS_AS(roller::write_file_atomically(target, "{}\n"), roller::InputError);
  CHECK(fs::is_fifo(fs::symlink_status(tmp)));
  fs::remove(tmp);
  roller::write_file_atomically(target, "{}\n");
  CHECK(roller::test::read_text(target) == "{}\n");
}

TEST_CASE("roller run --resume before the first checkpoint starts over and says so", "[app][restart]") {
  roller::test::TempDir dir("roller_cli_resume");
  // An empty folder, and one where a run stopped before its first checkpoint (its first files).
  const fs::path empty = dir.path() / "empty", early = dir.path() / "early";
  fs::create_directories(empty);
  REQUIRE(run_roller("run problems/block_compression.toml --steps 2 --out " + early.string()).exit_code == 0);
  fs::remove(early / "checkpoint.cbor");
  fs::remove(early / "state_final.cbor");
  for (const fs::path& out : {empty, early}) {
    const Run r = run_roller("run problems/block_compression.toml --steps 2 --resume --out " + out.string());
    INFO(r.output);
    CHECK(r.exit_code == 0);
    CHECK_THAT(r.output, Contains("holds no checkpoint yet") && Contains("starting over"));
    const auto summary = nlohmann::json::parse(roller::test::read_text(out / "summary.json"));
    CHECK(summary["steps_done"] == 2);
    CHECK(summary["resumed"] == false);
  }
  // A scene that keeps no checkpoint can never resume: said, with the key.
  const Run never = run_roller(
      "run problems/block_compression.toml --steps 2 --set output.checkpoint_every=0 "
      "--resume --out " +
      (dir.path() / "never").string());
  CHECK(never.exit_code == 2);
  CHECK_THAT(never.output, Contains("output.checkpoint_every = 0") && Contains("without --resume"));
}

TEST_CASE("a load whose Hertz contact is wider than the strip is an error naming the unit slip", "[app][errors]") {
  // A surface modulus in the wrong unit: a stationary pass would spread the load far beyond the
  // strip's ends and put a fraction of it on the strip.
  const Run r =
      run_roller("run problems/shakedown_p45.toml --set 'passes.method=\"stationary\"' --set material.E=1e-6 --out " +
                 (fs::temp_directory_path() / ("roller_cli_soft_" + std::to_string(::getpid()))).string());
  INFO(r.output);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Contains("roller.path[0].fy") && Contains("wider than the strip") &&
                           Contains("mesh.length = 200") && Contains("MPa"));
  // The same through shakedown-limit's elastic press.
  const Run limit = run_roller("shakedown-limit problems/shakedown_p45.toml --set material.E=1e-6");
  CHECK(limit.exit_code == 2);
  CHECK_THAT(limit.output, Contains("wider than the strip"));
}

TEST_CASE("an allocation that fails is reported with what to do, not as std::bad_alloc", "[driver][errors]") {
  const std::string message = roller::message_of(std::bad_alloc());
  CHECK_THAT(message, Contains("out of memory") && Contains("out_of_core") && Contains("ulimit -v"));
  CHECK(roller::status_of(std::bad_alloc()) == roller::RunStatus::SystemError);
  CHECK(roller::message_of(roller::InputError("x.toml: bad")) == "x.toml: bad");
}

TEST_CASE("a run of passes says each pass and its verdict on the console", "[app][passes]") {
  roller::test::TempDir dir("roller_cli_verdict");
  const Run r = run_roller(
      "run problems/shakedown_p45.toml --set 'passes.method=\"stationary\"' --set passes.count=3 "
      "--out " +
      (dir.path() / "out").string());
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.output, Contains("roller: pass 1/3 done: mean plastic strain increment") &&
                           Contains("roller: pass 3/3 done:") && Contains("of pass 1's") && Contains("s to go"));
  // The last line gives the verdict and its rule, as summary.json's message does.
  const std::string last = r.output.substr(r.output.rfind("roller: ", r.output.size() - 2));
  CHECK_THAT(last, Contains("verdict after 3 passes: ") && Contains("mean increment of equivalent plastic strain"));
  const auto summary = nlohmann::json::parse(roller::test::read_text(dir.path() / "out" / "summary.json"));
  CHECK_THAT(summary["message"].get<std::string>(), Contains("verdict after 3 passes: "));
}

TEST_CASE("the monotonicity warning says what it means once, and summary.json records it", "[app][monitor]") {
  roller::test::TempDir dir("roller_cli_monitor");
  const Run r = run_roller("run problems/z4_v25.toml --steps 10 --out " + (dir.path() / "out").string());
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const std::string needle = "operator A (the strip's incremental constitutive operator";
  REQUIRE_THAT(r.output, Contains(needle) && Contains("routine") && Contains("does not by itself affect the answer"));
  CHECK(r.output.find(needle) == r.output.rfind(needle));  // once
  const auto summary = nlohmann::json::parse(roller::test::read_text(dir.path() / "out" / "summary.json"));
  int recorded = 0;
  for (const auto& w : summary["warnings"]) recorded += w.get<std::string>().find(needle) != std::string::npos;
  CHECK(recorded == 1);
}

TEST_CASE("roller shakedown-limit --map takes a folder and refuses what is not one, before computing",
          "[app][errors]") {
  roller::test::TempDir dir("roller_cli_map");
  const fs::path file = dir.path() / "a_file";
  { std::ofstream(file) << "keep me\n"; }
  for (const std::string& target : {file.string(), std::string("''")}) {
    const Run r = run_roller("shakedown-limit problems/shakedown_p45.toml --map " + target);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.output, Contains("--map") && Contains("expected a folder") && !Contains("elastic press"));
  }
  CHECK(roller::test::read_text(file) == "keep me\n");
  const Run twice =
      run_roller("shakedown-limit problems/shakedown_p45.toml --map " + dir.path().string() + " --traction 0.2");
  CHECK(twice.exit_code == 2);
  CHECK_THAT(twice.output, Contains("--map sweeps the traction"));
}
