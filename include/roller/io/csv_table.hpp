#pragma once
// A CSV table written row by row and flushed after each row, so results of steps already done
// stay on disk if a later step fails or the run is killed.
#include <filesystem>
#include <fstream>
#include <string>
#include <variant>
#include <vector>

#include "roller/core/types.hpp"

namespace roller {

class CsvTable {
 public:
  using Cell = std::variant<Real, Index, std::string>;

  // Creates (truncates) the file and writes the header line. Throws std::runtime_error naming
  // the path when it cannot be opened.
  CsvTable(const std::filesystem::path& path, std::vector<std::string> columns);
  // Continues an existing table (a resumed run): keeps the rows whose first column (the step) is
  // <= keep_through, drops later ones, and appends after them. Throws std::runtime_error when
  // the file is missing or its header differs from `columns`.
  CsvTable(const std::filesystem::path& path, std::vector<std::string> columns, Index keep_through);
  // Appends a row; throws std::invalid_argument if the cell count differs from the columns.
  // Reals are written with 17 significant digits (round-trip exact); non-finite reals as
  // "nan"/"inf"/"-inf" so they are never hidden.
  void add_row(const std::vector<Cell>& cells);
  const std::vector<std::string>& columns() const { return columns_; }

 private:
  std::string header_line() const;
  std::ofstream out_;
  std::vector<std::string> columns_;
  std::filesystem::path path_;
};

// A cell's text as a CSV reader reads it back from the file (unquoted): reals with 17 significant
// digits, as written.
std::string cell_text(const CsvTable::Cell& cell);

}  // namespace roller
