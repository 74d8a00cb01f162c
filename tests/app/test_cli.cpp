// The roller command line as a user runs it: the default scene end to end (files written, exit
// code 0), bad input (exit code 2 with file/key/value in the message), failed steps (exit code 1,
// completed steps kept on disk).
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "../support/run_roller.hpp"
#include "../support/temp_files.hpp"
#include "roller/io/checksum.hpp"
#include "roller/io/scene_keys.hpp"

namespace fs = std::filesystem;

using roller::test::Run;
using roller::test::run_roller;

TEST_CASE("roller run: the default scene runs end to end and writes its results", "[app]") {
  const fs::path out = fs::temp_directory_path() / "roller_cli_block";
  fs::remove_all(out);
  const Run r = run_roller("run problems/block_compression.toml --out " + out.string() + " --steps 3");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains("step    3/3"));
  for (const char* f :
       {"fields.pvd", "step_0000.vtu", "step_0003.vtu", "solver.csv", "summary.json", "scene.resolved.toml"})
    CHECK(fs::exists(out / f));
  const std::string csv = roller::test::read_text(out / "solver.csv");
  CHECK_THAT(csv, Catch::StartsWith("step,pass,time,iterations,residual,max_penetration,wall_s"));
  CHECK_THAT(csv, Catch::Contains("k_eff_positive_definite"));
  const auto summary = nlohmann::json::parse(roller::test::read_text(out / "summary.json"));
  CHECK(summary["converged"] == true);
  // Peak memory of the process: more than the mesh and less than this machine has.
  CHECK(summary["peak_memory_mb"].get<double>() > 1.0);
  CHECK(summary["peak_memory_mb"].get<double>() < 24.0 * 1024.0);
  CHECK_THAT(r.output, Catch::Contains("peak memory"));
  fs::remove_all(out);
}

TEST_CASE("roller run: bad input exits with code 2 and a precise message", "[app]") {
  const Run bad_set = run_roller("run problems/block_compression.toml --out /tmp/roller_cli_bad --set material.nu=0.6");
  CHECK(bad_set.exit_code == 2);
  CHECK_THAT(bad_set.output, Catch::Contains("material.nu = 0.6") && Catch::Contains("0 <= nu < 0.5"));
  const Run missing = run_roller("run problems/does_not_exist.toml");
  CHECK(missing.exit_code == 2);
  CHECK_THAT(missing.output, Catch::Contains("does_not_exist.toml"));
  const Run bad_flag = run_roller("run problems/block_compression.toml --refine 0");
  CHECK(bad_flag.exit_code == 2);
  CHECK_THAT(bad_flag.output, Catch::Contains("--refine"));
  const Run unknown_flag = run_roller("run problems/block_compression.toml --refinement 2");
  CHECK(unknown_flag.exit_code == 2);
  CHECK_THAT(unknown_flag.output, Catch::Contains("--refinement"));
}

TEST_CASE("roller --version names roller's version and commit and the Ipopt and MUMPS versions", "[app]") {
  const Run r = run_roller("--version");
  INFO(r.output);
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::StartsWith("roller 0.") && Catch::Contains("commit ") && Catch::Contains("Ipopt 3.") &&
                           Catch::Contains("MUMPS 5."));
}

TEST_CASE("roller run: a step that cannot converge stops the run with code 1, completed steps kept", "[app]") {
  // One Newton iteration per increment and no cuts cannot converge the plastic block.
  const fs::path out = fs::temp_directory_path() / "roller_cli_fail";
  fs::remove_all(out);
  const Run r = run_roller("run problems/block_compression.toml --out " + out.string() +
                           " --set newton.max_iterations=1 --set steps.max_cuts=0");
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains("step 1 failed"));
  CHECK(fs::exists(out / "step_0000.vtu"));
  CHECK_THAT(roller::test::read_text(out / "summary.json"), Catch::Contains("\"converged\": false"));
  // The one Newton iteration allowed ran out: a budget, not a breakdown (smaller steps may succeed).
  CHECK_THAT(roller::test::read_text(out / "solver.csv"), Catch::Contains(",limit_reached\n"));
  fs::remove_all(out);
}

TEST_CASE("roller run --resume continues a shortened run to the same results as an uninterrupted one",
          "[app][restart][slow]") {
  // Z4 has strip inertia and a suspended roller: the Houbolt histories must survive the break.
  const fs::path whole = fs::temp_directory_path() / ("roller_cli_whole_" + std::to_string(::getpid()));
  const fs::path split = fs::temp_directory_path() / ("roller_cli_split_" + std::to_string(::getpid()));
  fs::remove_all(whole);
  fs::remove_all(split);
  const std::string scene = "run problems/z4_v25.toml --steps 10 --out ";
  REQUIRE(run_roller(scene + whole.string()).exit_code == 0);
  REQUIRE(run_roller("run problems/z4_v25.toml --steps 6 --out " + split.string()).exit_code == 0);
  // A killed run leaves rows after its last checkpoint; they must be replaced, not duplicated.
  { std::ofstream(split / "roller.csv", std::ios::app) << "7,junk\n"; }
  const Run resumed = run_roller(scene + split.string() + " --resume");
  INFO(resumed.output);
  REQUIRE(resumed.exit_code == 0);
  CHECK_THAT(resumed.output, Catch::Contains("resuming after step 6"));
  CHECK(roller::test::read_text(split / "roller.csv") == roller::test::read_text(whole / "roller.csv"));
  CHECK(roller::test::read_text(split / "contact.csv") == roller::test::read_text(whole / "contact.csv"));
  CHECK(roller::test::read_text(split / "step_0010.vtu") == roller::test::read_text(whole / "step_0010.vtu"));
  CHECK(roller::test::read_text(split / "fields.pvd") == roller::test::read_text(whole / "fields.pvd"));
  // Without a checkpoint there is nothing to lose: the run starts over and says so.
  const fs::path empty = fs::temp_directory_path() / ("roller_cli_empty_" + std::to_string(::getpid()));
  fs::create_directories(empty);
  const Run none = run_roller(scene + empty.string() + " --resume");
  CHECK(none.exit_code == 0);
  CHECK_THAT(none.output, Catch::Contains("holds no checkpoint yet") && Catch::Contains("starting over"));
  CHECK(roller::test::read_text(empty / "roller.csv") == roller::test::read_text(whole / "roller.csv"));
  for (const auto& d : {whole, split, empty}) fs::remove_all(d);
}

TEST_CASE("roller run --resume continues only the run that wrote the checkpoint, from an intact file",
          "[app][restart]") {
  const fs::path out = fs::temp_directory_path() / ("roller_cli_ckpt_" + std::to_string(::getpid()));
  fs::remove_all(out);
  REQUIRE(run_roller("run problems/block_compression.toml --steps 3 --out " + out.string()).exit_code == 0);
  // Another value of the scene: refused (it would mix two runs).
  const Run other =
      run_roller("run problems/block_compression.toml --set material.E=1e5 --out " + out.string() + " --resume");
  CHECK(other.exit_code == 2);
  CHECK_THAT(other.output, Catch::Contains("checkpoint.cbor: written by a run of another scene or with other values"));
  // Fewer steps than the checkpoint has done: refused (it reported the checkpoint's steps as done).
  const Run fewer = run_roller("run problems/block_compression.toml --steps 2 --out " + out.string() + " --resume");
  CHECK(fewer.exit_code == 2);
  CHECK_THAT(fewer.output, Catch::Contains("after step 3 but the run has 2 steps"));
  // A file of an older roller, intact but without a key this one reads: the key named, not "damaged".
  {
    const std::string text = roller::test::read_text(out / "checkpoint.cbor");
    nlohmann::json doc = nlohmann::json::from_cbor(std::vector<std::uint8_t>(text.begin(), text.end()));
    doc.erase("checksum");
    doc.erase("last_length");
    const std::vector<std::uint8_t> signed_bytes = nlohmann::json::to_cbor(doc);
    doc["checksum"] =
        roller::fnv1a_hex(std::string_view(reinterpret_cast<const char*>(signed_bytes.data()), signed_bytes.size()));
    const std::vector<std::uint8_t> older = nlohmann::json::to_cbor(doc);
    std::ofstream(out / "checkpoint.cbor", std::ios::binary)
        .write(reinterpret_cast<const char*>(older.data()), static_cast<std::streamsize>(older.size()));
  }
  const Run older = run_roller("run problems/block_compression.toml --steps 5 --out " + out.string() + " --resume");
  CHECK(older.exit_code == 2);
  CHECK_THAT(older.output, Catch::Contains("checkpoint.cbor: a key this roller reads is missing") &&
                               Catch::Contains("last_length") && Catch::Contains("older roller"));
  // A damaged file: one flipped byte in the middle fails the checksum.
  std::string bytes = roller::test::read_text(out / "checkpoint.cbor");
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x10);
  { std::ofstream(out / "checkpoint.cbor", std::ios::binary) << bytes; }
  const Run damaged = run_roller("run problems/block_compression.toml --steps 5 --out " + out.string() + " --resume");
  CHECK(damaged.exit_code == 2);
  CHECK_THAT(damaged.output, Catch::Contains("checkpoint.cbor") &&
                                 (Catch::Contains("damaged") || Catch::Contains("not a roller state file")));
  fs::remove_all(out);
}

TEST_CASE("roller scene-keys lists every scene key, one line each", "[app]") {
  const Run r = run_roller("scene-keys");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  std::istringstream lines(r.output);
  std::vector<std::string> rows;
  for (std::string line; std::getline(lines, line);) rows.push_back(line);
  REQUIRE(rows.size() == roller::scene_keys().size() + 1);  // a header, then the keys in order
  CHECK_THAT(rows[0], Catch::StartsWith("key "));
  for (std::size_t i = 0; i < roller::scene_keys().size(); ++i)
    CHECK_THAT(rows[i + 1], Catch::StartsWith(roller::scene_keys()[i].dotted() + " "));
  CHECK_THAT(r.output,
             Catch::Contains("contact.ipopt.tol") && Catch::Contains("1e-09") && Catch::Contains("0 < tol < 1"));
}

TEST_CASE("roller run writes into a new folder or its own earlier output, another only with --overwrite",
          "[app][output]") {
  const fs::path out = fs::temp_directory_path() / ("roller_cli_folder_" + std::to_string(::getpid()));
  fs::remove_all(out);
  const std::string block = "run problems/block_compression.toml --out " + out.string();
  REQUIRE(run_roller(block + " --steps 3").exit_code == 0);
  REQUIRE(fs::exists(out / "step_0003.vtu"));
  { std::ofstream(out / "notes.txt") << "mine\n"; }
  // The same scene again, shorter: its old outputs go (no step file of the longer run stays),
  // other files stay.
  REQUIRE(run_roller(block + " --steps 2").exit_code == 0);
  CHECK_FALSE(fs::exists(out / "step_0003.vtu"));
  CHECK(fs::exists(out / "step_0002.vtu"));
  CHECK(fs::exists(out / "notes.txt"));
  // Another scene: refused, the folder untouched; with --overwrite it runs.
  const std::string hertz = "run problems/hertz.toml --steps 1 --out " + out.string();
  const Run refused = run_roller(hertz);
  CHECK(refused.exit_code == 2);
  CHECK_THAT(refused.output, Catch::Contains("holds no output of scene 'hertz'") &&
                                 Catch::Contains("holds scene 'block_compression'") && Catch::Contains("--overwrite"));
  CHECK(fs::exists(out / "step_0002.vtu"));
  REQUIRE(run_roller(hertz + " --overwrite").exit_code == 0);
  CHECK_FALSE(fs::exists(out / "step_0002.vtu"));
  CHECK(fs::exists(out / "notes.txt"));
  // A folder with other files only: refused too.
  const fs::path foreign = fs::temp_directory_path() / ("roller_cli_foreign_" + std::to_string(::getpid()));
  fs::create_directories(foreign);
  { std::ofstream(foreign / "thesis.pdf") << "x"; }
  CHECK(run_roller("run problems/block_compression.toml --steps 1 --out " + foreign.string()).exit_code == 2);
  fs::remove_all(out);
  fs::remove_all(foreign);
}

TEST_CASE("a state file that cannot be written ends the run with exit code 2, its summary written", "[app][output]") {
  const fs::path out = fs::temp_directory_path() / ("roller_cli_nowrite_" + std::to_string(::getpid()));
  fs::remove_all(out);
  // A folder where the checkpoint's temporary file would go: the output folder cannot be used as
  // it is (exit 2, like a read-only one; a full disk is exit 3: python/tests/test_reliability.py).
  fs::create_directories(out / "checkpoint.cbor.tmp");
  const Run r = run_roller("run problems/block_compression.toml --steps 3 --overwrite --out " + out.string());
  INFO(r.output);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("something other than a regular file stands at") &&
                           Catch::Contains("checkpoint.cbor.tmp"));
  CHECK_THAT(r.output, Catch::Contains("roller: input error:") && Catch::Contains("cannot write the state file"));
  REQUIRE(fs::exists(out / "summary.json"));
  const auto summary = nlohmann::json::parse(roller::test::read_text(out / "summary.json"));
  CHECK(summary["converged"] == false);
  CHECK(summary["status"] == "input_error");
  CHECK(summary["exit_code"] == 2);
  CHECK_THAT(summary["message"].get<std::string>(), Catch::Contains("cannot write the state file"));
  CHECK(fs::exists(out / "step_0001.vtu"));  // the step done before is on disk
  fs::remove_all(out);
}

TEST_CASE("roller shakedown-limit prints the limit and writes it by depth, bad input exits with code 2", "[app]") {
  const fs::path csv = fs::temp_directory_path() / ("roller_cli_limit_" + std::to_string(::getpid()) + ".csv");
  const fs::path json = fs::temp_directory_path() / ("roller_cli_limit_" + std::to_string(::getpid()) + ".json");
  const Run r = run_roller("shakedown-limit problems/shakedown_thin_strip.toml --csv " + csv.string() + " --json " +
                           json.string());
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains("elastic shakedown limit") && Catch::Contains("p0/k = "));
  const auto limit = nlohmann::json::parse(roller::test::read_text(json));
  const double p0k = limit["elastic"]["p0_over_k"].get<double>();
  CHECK(p0k > limit["first_yield_p0_over_k"].get<double>());
  // The CSV's rows, every depth solved: the strictest of them is the limit the JSON gives.
  std::istringstream rows(roller::test::read_text(csv));
  std::string line;
  std::getline(rows, line);
  CHECK_THAT(line, Catch::StartsWith("depth_mm,depth_over_a,first_yield_p0_over_k,elastic_p0_over_k"));
  double smallest = 1e300;
  int n = 0;
  while (std::getline(rows, line)) {
    std::istringstream cells(line);
    std::string cell;
    for (int c = 0; c < 4; ++c) std::getline(cells, cell, ',');
    REQUIRE_FALSE(cell.empty());  // every row solved
    if (cell != "inf") smallest = std::min(smallest, std::stod(cell));
    ++n;
  }
  CHECK(n > 30);
  CHECK(smallest == Approx(p0k).epsilon(1e-5));
  fs::remove(csv);
  fs::remove(json);

  const Run no_roller = run_roller("shakedown-limit problems/block_compression.toml");
  CHECK(no_roller.exit_code == 2);
  CHECK_THAT(no_roller.output, Catch::Contains("block_compression.toml") && Catch::Contains("[roller]"));
  const Run bad_traction = run_roller("shakedown-limit problems/shakedown_p45.toml --traction -0.1");
  CHECK(bad_traction.exit_code == 2);
  CHECK_THAT(bad_traction.output, Catch::Contains("--traction"));
}
