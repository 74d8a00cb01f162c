// Which files of an output folder a run owns (driver/output_folder.hpp): a rerun or --overwrite
// removes exactly these, so that no file of an earlier run stays beside the new one's.
#include <catch2/catch.hpp>

#include "driver/output_folder.hpp"
#include "roller/driver/output_columns.hpp"

using namespace roller;

TEST_CASE("output folder: every file a run writes is a run output, the user's files are not", "[driver][output]") {
  for (const OutputTable t : {OutputTable::Solver, OutputTable::Contact, OutputTable::Roller, OutputTable::Passes,
                              OutputTable::ResidualDepth, OutputTable::Fatigue}) {
    INFO(file_name(t));
    CHECK(is_run_output(file_name(t)));
  }
  for (const char* name : {"fields.pvd", "roller.pvd", "step_0003.vtu", "step_0003_loaded.vtu", "roller_0003.vtp",
                           "roller_0003_loaded.vtp", "roller_0003.vtu", "roller_0003_loaded.vtu", "summary.json",
                           "state_0004.cbor", "checkpoint.cbor.tmp", "passes.png", "residual_depth.png"}) {
    INFO(name);
    CHECK(is_run_output(name));
  }
  for (const char* name : {"notes.txt", "step_3.vtu", "my_fields.vtu", "roller.toml", "fatigue.csv.bak"}) {
    INFO(name);
    CHECK_FALSE(is_run_output(name));
  }
}
