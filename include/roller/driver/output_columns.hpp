#pragma once
// The columns of a run's CSV tables (docs/scenes.md, Output): each row is one list of columns,
// name, unit and value side by side, so that the header, the rows and the documented units all
// come from the same place (`roller output-columns` prints them from here). A table's header is
// the names of a row of an empty record.
#include <string>
#include <vector>

#include "roller/core/enum_names.hpp"
#include "roller/driver/simulation.hpp"
#include "roller/driver/step_monitor.hpp"
#include "roller/io/csv_table.hpp"

namespace roller {

struct Column {
  const char* name;
  const char* unit;  // "-" for counts, indices and text; "1" for dimensionless ratios
  CsvTable::Cell value;
};
using Row = std::vector<Column>;

std::vector<std::string> names_of(const Row& row);
std::vector<CsvTable::Cell> cells_of(const Row& row);

Row solver_row(const Simulation::StepRecord& r, const MonitorReport& monitor, double wall_s);
Row contact_row(int step, int pass, const NodeContactRecord& c);
Row roller_row(int step, int pass, Real time, const Simulation::RollerRecord& r);
Row pass_row(int step, const PassRecord& r);
Row depth_row(int step, int pass, Real x, const DepthSample& d);
Row fatigue_row(int step, int pass, Real x, const FatigueAtDepth& d);

// Contact pressure and tangential traction of a node [MPa]: its forces over its tributary length
// (contact.csv's p_n, p_t and the VTU's contact fields).
Vec2 tractions(const NodeContactRecord& c);

enum class OutputTable { Solver, Contact, Roller, Passes, ResidualDepth, Fatigue };
template <>
struct EnumNames<OutputTable> {
  static constexpr std::array<std::pair<OutputTable, const char*>, 6> names{
      {{OutputTable::Solver, "solver"},
       {OutputTable::Contact, "contact"},
       {OutputTable::Roller, "roller"},
       {OutputTable::Passes, "passes"},
       {OutputTable::ResidualDepth, "residual_depth"},
       {OutputTable::Fatigue, "fatigue"}}};
};

// The tables a scene's run fills: solver always, contact and roller with a roller, passes and
// residual_depth with more than one pass, fatigue with [fatigue].
std::vector<OutputTable> tables_of(const Scene& scene);
// A table's columns (the names of a row of an empty record) and its file in the output folder.
Row empty_row(OutputTable table);
std::string file_name(OutputTable table);

// Every table a run may write, with its columns (from rows of empty records).
struct TableColumns {
  std::string file;
  Row columns;
};
std::vector<TableColumns> output_tables();
// The tables as the Markdown table of docs/scenes.md ("Units of the tables' columns"): one line per
// file, its columns with their units in brackets.
std::string output_tables_markdown();

}  // namespace roller
