// The output tables' column schema: every column has a known unit, no table names a column twice,
// a run writes exactly the schema's header, and docs/scenes.md shows the schema as it is.
#include <catch2/catch.hpp>

#include <set>
#include <string>

#include "../support/run_roller.hpp"
#include "../support/temp_files.hpp"
#include "roller/driver/output_columns.hpp"

using namespace roller;

TEST_CASE("output columns: each has a known unit and a name unique in its table", "[driver][outputs]") {
  const std::set<std::string> units{"-", "1", "s", "rad", "mm", "mm/s", "mm/s^2", "MPa", "N/mm", "N mm/mm"};
  const auto tables = output_tables();
  REQUIRE(tables.size() == 6);
  for (const TableColumns& t : tables) {
    std::set<std::string> names;
    for (const Column& c : t.columns) {
      INFO(t.file << ": " << c.name << " [" << c.unit << "]");
      CHECK(units.count(c.unit) == 1);
      CHECK(names.insert(c.name).second);
    }
    CHECK(std::string(t.columns.at(0).name) == "step");
  }
}

TEST_CASE("output columns: a run's CSV headers are the schema's names", "[driver][outputs]") {
  const test::TempDir dir("output_columns");
  const test::Run r = test::run_roller("run " + std::string(ROLLER_SOURCE_DIR) +
                                       "/problems/hertz.toml --steps 1 --out " + (dir.path() / "out").string());
  REQUIRE(r.exit_code == 0);
  for (const TableColumns& t : output_tables()) {
    // Multi-pass runs only (fatigue.csv: with a [fatigue] section).
    if (t.file == "passes.csv" || t.file == "residual_depth.csv" || t.file == "fatigue.csv") continue;
    const std::string text = test::read_text(dir.path() / "out" / t.file);
    const std::string header = text.substr(0, text.find('\n'));
    std::string expected;
    for (const std::string& name : names_of(t.columns)) expected += (expected.empty() ? "" : ",") + name;
    CHECK(header == expected);
  }
}

TEST_CASE("output columns: docs/scenes.md shows every table's columns with their units", "[driver][outputs][docs]") {
  const std::string docs = test::read_text(std::string(ROLLER_SOURCE_DIR) + "/docs/scenes.md");
  INFO("regenerate with: roller output-columns --markdown");
  CHECK(docs.find(output_tables_markdown()) != std::string::npos);
}
