#pragma once
// Where a run's results go. The run decides what each step gives: the rows of its tables
// (output_columns.hpp) and, at the steps output.every asks for, the strip's fields and the
// roller's pose. A sink keeps them: the output folder's files (CSV tables and VTU series), or
// memory (MemoryOutputs, for roller run from Python: docs/python.md).
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "roller/contact/roller.hpp"
#include "roller/driver/output_columns.hpp"
#include "roller/io/field_output.hpp"

namespace roller {

// The strip's fields of a written step (the strip's, its contact's and, with strip inertia, its
// velocity and acceleration) and the roller there (none without a roller).
// An elastic roller's disc at a step (driver/roller_disc_fields.hpp): its mesh about the origin,
// the points placed at the roller's centre (the frame that moves with the centre without turning),
// its displacement, stresses and the contact's forces on it.
struct RollerBody {
  std::shared_ptr<const Mesh> mesh;
  std::vector<Vec2> points;
  std::vector<VtuField> point_data, cell_data;
};

struct StepFields {
  int step = 0;
  int pass = 1;
  Real time = 0.0;
  StripFields strip;
  std::optional<RollerPose> roller;
  // A stationary pass's loaded state (the strip under the roller, in its frame) written beside the
  // pass's own fields, the residual strip: step_NNNN_loaded.vtu at time (step - 1/2) dt.
  bool loaded = false;
  // An elastic roller's disc (written as roller_NNNN.vtu instead of the rigid roller's circle).
  std::shared_ptr<const RollerBody> roller_body;
};

class OutputSink {
 public:
  virtual ~OutputSink() = default;
  virtual void add_row(OutputTable table, const Row& row) = 0;
  virtual void add_fields(StepFields fields) = 0;
};

// Everything in memory: each table's rows (cells as the CSV files hold them) and the fields of
// every written step.
class MemoryOutputs : public OutputSink {
 public:
  struct Table {
    std::vector<std::string> columns;
    std::vector<std::vector<CsvTable::Cell>> rows;
  };
  void add_row(OutputTable table, const Row& row) override;
  void add_fields(StepFields fields) override { fields_.push_back(std::move(fields)); }

  const std::map<OutputTable, Table>& tables() const { return tables_; }
  const std::vector<StepFields>& fields() const { return fields_; }

 private:
  std::map<OutputTable, Table> tables_;
  std::vector<StepFields> fields_;
};

}  // namespace roller
