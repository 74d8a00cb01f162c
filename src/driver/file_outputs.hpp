#pragma once
// The output folder as a sink of a run's results (docs/scenes.md, Output): solver.csv,
// contact.csv, roller.csv, passes.csv and residual_depth.csv (a row flushed as it comes),
// fields.pvd with its VTU files (points in the reference configuration with the displacement:
// ParaView's Warp By Vector gives the deformed strip) and, with a roller, roller.pvd with its
// circle at the same steps. A resumed run continues the tables after the resumed step and keeps
// the earlier VTU files in the series.
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>

#include "roller/driver/output_sink.hpp"
#include "roller/io/background_writer.hpp"
#include "roller/io/csv_table.hpp"
#include "roller/io/vtu_writer.hpp"

namespace roller {

class FileOutputs : public OutputSink {
 public:
  // Opens the scene's tables (continued after `steps_done` when resuming). Field files go to
  // `writer` (written while the next step is solved).
  FileOutputs(const Scene& scene, const Mesh& mesh, const std::filesystem::path& out_dir, bool resume, int steps_done,
              BackgroundWriter& writer);
  // The writer's jobs add to this object's series: none may outlive it.
  ~FileOutputs() override { writer_.drain(); }
  FileOutputs(const FileOutputs&) = delete;
  FileOutputs& operator=(const FileOutputs&) = delete;

  void add_row(OutputTable table, const Row& row) override;
  void add_fields(StepFields fields) override;

 private:
  // A step's files; `loaded`: a stationary pass's loaded state beside them (StepFields::loaded).
  std::filesystem::path vtu_path(int step, bool loaded = false) const;
  // The roller's: its circle (.vtp), an elastic roller's disc (.vtu).
  std::filesystem::path roller_path(int step, bool loaded = false) const;

  const Scene& scene_;
  const Mesh& mesh_;
  BackgroundWriter& writer_;
  std::filesystem::path out_dir_;
  std::map<OutputTable, std::unique_ptr<CsvTable>> tables_;
  PvdSeries series_;                        // added to by the writer's jobs, one at a time (series_mutex_)
  std::optional<PvdSeries> roller_series_;  // roller.pvd, with a roller: its circle at the same steps
  std::mutex series_mutex_;
};

}  // namespace roller
