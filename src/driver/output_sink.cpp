#include "roller/driver/output_sink.hpp"

namespace roller {

void MemoryOutputs::add_row(OutputTable table, const Row& row) {
  Table& t = tables_[table];
  if (t.columns.empty()) t.columns = names_of(row);
  t.rows.push_back(cells_of(row));
}

}  // namespace roller
