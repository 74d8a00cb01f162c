// CSV tables: one header line, then one line per add_row(), flushed at once. Fields are
// separated by ',' and lines end with '\n'; a text field containing ',', '"', CR or LF is
// quoted RFC-4180 style (enclosed in '"', inner '"' doubled).
#include "roller/io/csv_table.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "roller/core/error.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <utility>

namespace roller {

namespace {

std::string quote_if_needed(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
  return out;
}

std::string format_real(Real value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return fmt::format("{:.17g}", value);  // 17 significant digits: strtod recovers it exactly
}

struct CellFormatter {
  std::string operator()(Real value) const { return format_real(value); }
  std::string operator()(Index value) const { return fmt::format("{}", value); }
  std::string operator()(const std::string& value) const { return quote_if_needed(value); }
};

}  // namespace

std::string cell_text(const CsvTable::Cell& cell) {
  return std::visit(
      [](const auto& v) -> std::string {
        if constexpr (std::is_same_v<std::decay_t<decltype(v)>, std::string>)
          return v;
        else
          return CellFormatter{}(v);
      },
      cell);
}

CsvTable::CsvTable(const std::filesystem::path& path, std::vector<std::string> columns)
    : columns_(std::move(columns)), path_(path) {
  if (columns_.empty()) {
    throw std::invalid_argument(
        fmt::format("CsvTable '{}': no columns given; a table needs at least one", path.string()));
  }
  errno = 0;
  out_.open(path_, std::ios::out | std::ios::trunc | std::ios::binary);
  if (!out_) throw_file_error(fmt::format("cannot create CSV file '{}'", path_.string()), errno);
  out_ << header_line() << std::flush;
  if (!out_) throw_file_error(fmt::format("cannot write the header of CSV file '{}'", path_.string()), errno);
}

CsvTable::CsvTable(const std::filesystem::path& path, std::vector<std::string> columns, Index keep_through)
    : columns_(std::move(columns)), path_(path) {
  std::ifstream in(path_, std::ios::binary);
  if (!in) throw InputError(fmt::format("cannot resume CSV file '{}': it does not exist", path_.string()));
  std::string line, kept;
  std::getline(in, line);
  if (line + '\n' != header_line())
    throw InputError(fmt::format("cannot resume CSV file '{}': its header '{}' differs from '{}'", path_.string(), line,
                                 header_line().substr(0, header_line().size() - 1)));
  kept = line + '\n';
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const Index step = std::strtoll(line.c_str(), nullptr, 10);
    if (step <= keep_through) kept += line + '\n';
  }
  in.close();
  errno = 0;
  out_.open(path_, std::ios::out | std::ios::trunc | std::ios::binary);
  out_ << kept << std::flush;
  if (!out_) throw_file_error(fmt::format("cannot rewrite CSV file '{}'", path_.string()), errno);
}

std::string CsvTable::header_line() const {
  std::string line;
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    if (i > 0) line += ',';
    line += quote_if_needed(columns_[i]);
  }
  return line + '\n';
}

void CsvTable::add_row(const std::vector<Cell>& cells) {
  if (cells.size() != columns_.size()) {
    throw std::invalid_argument(fmt::format("CsvTable '{}': row has {} cells; the table has {} columns ({})",
                                            path_.string(), cells.size(), columns_.size(), fmt::join(columns_, ", ")));
  }
  std::string line;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i > 0) line += ',';
    line += std::visit(CellFormatter{}, cells[i]);
  }
  line += '\n';
  // Flushed per row so finished steps survive a later failure or a killed run.
  errno = 0;
  out_ << line << std::flush;
  if (!out_) throw_file_error(fmt::format("cannot write a row to CSV file '{}'", path_.string()), errno);
}

}  // namespace roller
