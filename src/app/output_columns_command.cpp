// roller output-columns: the columns of every CSV table a run writes, with their units, from the
// list the outputs themselves are written with (driver/output_columns.hpp).
#include <algorithm>
#include <iostream>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "commands.hpp"
#include "roller/driver/output_columns.hpp"

namespace roller::app {

Command add_output_columns_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("output-columns",
                                     "list the columns of every CSV table a run writes, with their units "
                                     "(docs/scenes.md, Output)");
  auto markdown = std::make_shared<bool>(false);
  cmd->add_flag("--markdown", *markdown, "print the table of docs/scenes.md instead");
  return [markdown] {
    if (*markdown) {
      std::cout << output_tables_markdown();
      return 0;
    }
    std::size_t w_file = 4, w_name = 6;
    for (const TableColumns& t : output_tables()) {
      w_file = std::max(w_file, t.file.size());
      for (const Column& c : t.columns) w_name = std::max(w_name, std::string(c.name).size());
    }
    std::cout << fmt::format("{:<{}}  {:<{}}  {}\n", "file", w_file, "column", w_name, "unit");
    for (const TableColumns& t : output_tables())
      for (const Column& c : t.columns)
        std::cout << fmt::format("{:<{}}  {:<{}}  {}\n", t.file, w_file, c.name, w_name, c.unit);
    return 0;
  };
}

}  // namespace roller::app
