// Tests of CsvTable: the file is parsed back with an independent RFC-4180 reader while the
// table is still alive (so rows must already be flushed) and numbers are compared exactly.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "../support/temp_files.hpp"
#include "roller/io/csv_table.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using namespace roller;

using test::read_text;

namespace {

// Minimal RFC-4180 reader: quoted fields may hold ',', '""' and line breaks.
std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> row;
  std::string field;
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"') {
        if (i + 1 < text.size() && text[i + 1] == '"') {
          field += '"';
          ++i;
        } else {
          quoted = false;
        }
      } else {
        field += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      row.push_back(field);
      field.clear();
    } else if (c == '\n') {
      row.push_back(field);
      field.clear();
      rows.push_back(row);
      row.clear();
    } else {
      field += c;
    }
  }
  REQUIRE_FALSE(quoted);
  REQUIRE(field.empty());  // every row ends with a newline
  REQUIRE(row.empty());
  return rows;
}

template <class E, class F>
std::string thrown_message(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "<nothing thrown>";
}

}  // namespace

TEST_CASE("CsvTable writes a header and rows that read back exactly while it is alive", "[io]") {
  test::TempDir dir("roller_csv_test");
  const fs::path file = dir.path() / "history.csv";
  CsvTable table(file, {"step", "time", "force", "note"});
  CHECK(table.columns() == std::vector<std::string>{"step", "time", "force", "note"});
  CHECK(read_text(file) == "step,time,force,note\n");

  const std::vector<double> reals = {
      0.1,  1.0 / 3.0,           -2.5e-300,       1.7976931348623157e308, 4.9406564584124654e-324,
      -0.0, 123456789.123456789, 2.0 / 3.0 * 1e-7};
  for (std::size_t i = 0; i < reals.size(); ++i) {
    table.add_row({Index(i), reals[i], reals[reals.size() - 1 - i], std::string("ok")});
    // Flushed: the row is on disk before the next one is added.
    const auto rows = parse_csv(read_text(file));
    REQUIRE(rows.size() == i + 2);
  }

  const auto rows = parse_csv(read_text(file));
  REQUIRE(rows.size() == reals.size() + 1);
  CHECK(rows[0] == std::vector<std::string>{"step", "time", "force", "note"});
  for (std::size_t i = 0; i < reals.size(); ++i) {
    const auto& row = rows[i + 1];
    INFO("row " << i << ": " << row[1] << " " << row[2]);
    REQUIRE(row.size() == 4);
    CHECK(row[0] == std::to_string(i));
    const double time = std::strtod(row[1].c_str(), nullptr);
    const double force = std::strtod(row[2].c_str(), nullptr);
    CHECK(time == reals[i]);
    CHECK(std::signbit(time) == std::signbit(reals[i]));
    CHECK(force == reals[reals.size() - 1 - i]);
    CHECK(row[3] == "ok");
  }
  CHECK(rows[1][1] == "0.10000000000000001");  // 17 significant digits
  CHECK(rows[6][1] == "-0");
}

TEST_CASE("CsvTable writes non-finite reals as nan, inf and -inf", "[io]") {
  test::TempDir dir("roller_csv_test");
  const fs::path file = dir.path() / "nonfinite.csv";
  CsvTable table(file, {"a", "b", "c", "d"});
  table.add_row({std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                 -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::quiet_NaN()});
  const auto rows = parse_csv(read_text(file));
  REQUIRE(rows.size() == 2);
  CHECK(rows[1] == std::vector<std::string>{"nan", "inf", "-inf", "nan"});
}

TEST_CASE("CsvTable quotes text holding commas, quotes or line breaks", "[io]") {
  test::TempDir dir("roller_csv_test");
  const fs::path file = dir.path() / "quoted.csv";
  CsvTable table(file, {"id", "force, N", "status"});
  table.add_row({Index(-7), std::string("say \"hi\""), std::string("a,b")});
  table.add_row({Index(8), std::string("two\nlines"), std::string("plain text")});

  const std::string text = read_text(file);
  CHECK(text ==
        "id,\"force, N\",status\n"
        "-7,\"say \"\"hi\"\"\",\"a,b\"\n"
        "8,\"two\nlines\",plain text\n");
  const auto rows = parse_csv(text);
  REQUIRE(rows.size() == 3);
  CHECK(rows[0] == std::vector<std::string>{"id", "force, N", "status"});
  CHECK(rows[1] == std::vector<std::string>{"-7", "say \"hi\"", "a,b"});
  CHECK(rows[2] == std::vector<std::string>{"8", "two\nlines", "plain text"});
}

TEST_CASE("CsvTable rejects a row whose length differs from the header and writes nothing", "[io]") {
  test::TempDir dir("roller_csv_test");
  const fs::path file = dir.path() / "short.csv";
  CsvTable table(file, {"step", "time"});
  table.add_row({Index(0), 0.0});
  const std::string before = read_text(file);

  auto msg = thrown_message<std::invalid_argument>([&] { table.add_row({Index(1)}); });
  CHECK_THAT(msg, Contains("1 cells"));
  CHECK_THAT(msg, Contains("2 columns"));
  msg = thrown_message<std::invalid_argument>([&] { table.add_row({Index(1), 0.5, std::string("extra")}); });
  CHECK_THAT(msg, Contains("3 cells"));
  CHECK(read_text(file) == before);

  table.add_row({Index(1), 0.5});  // the table is still usable afterwards
  CHECK(parse_csv(read_text(file)).size() == 3);
}

TEST_CASE("CsvTable truncates an existing file", "[io]") {
  test::TempDir dir("roller_csv_test");
  const fs::path file = dir.path() / "old.csv";
  std::ofstream(file) << "stale,content\n1,2\n";
  CsvTable table(file, {"x"});
  CHECK(read_text(file) == "x\n");
}

TEST_CASE("CsvTable at an unwritable path throws naming the path", "[io]") {
  test::TempDir dir("roller_csv_test");
  const fs::path file = dir.path() / "no_such_folder" / "table.csv";
  const auto msg = thrown_message<std::runtime_error>([&] { CsvTable table(file, {"a", "b"}); });
  CHECK_THAT(msg, Contains(file.string()));
}

TEST_CASE("csv table: a cell's text is what a CSV reader reads back", "[io][csv]") {
  CHECK(cell_text(CsvTable::Cell(Real{100.0})) == "100");
  CHECK(cell_text(CsvTable::Cell(Real{0.1})) == "0.10000000000000001");
  CHECK(cell_text(CsvTable::Cell(Index{7})) == "7");
  CHECK(cell_text(CsvTable::Cell(std::string("a, \"b\""))) == "a, \"b\"");  // unquoted
  CHECK(cell_text(CsvTable::Cell(std::string())).empty());
}
