#include "file_outputs.hpp"

#include <fmt/format.h>

namespace roller {

namespace {

// What a file of step `step` is (ParaView shows field data under Information): step, pass, time.
std::vector<VtuField> step_field_data(int step, int pass, Real time) {
  std::vector<VtuField> data(3);
  data[0].name = "step";
  data[0].values = {static_cast<Real>(step)};
  data[1].name = "pass";
  data[1].values = {static_cast<Real>(pass)};
  data[2].name = "time";
  data[2].values = {time};
  return data;
}

}  // namespace

FileOutputs::FileOutputs(const Scene& scene, const Mesh& mesh, const std::filesystem::path& out_dir, bool resume,
                         int steps_done, BackgroundWriter& writer)
    : scene_(scene), mesh_(mesh), writer_(writer), out_dir_(out_dir), series_(out_dir / "fields.pvd") {
  for (OutputTable table : tables_of(scene)) {
    const std::filesystem::path path = out_dir / file_name(table);
    std::vector<std::string> columns = names_of(empty_row(table));
    tables_[table] = resume ? std::make_unique<CsvTable>(path, std::move(columns), steps_done)
                            : std::make_unique<CsvTable>(path, std::move(columns));
  }
  if (scene.roller) roller_series_.emplace(out_dir / "roller.pvd");
  if (!resume) return;
  for (int step = 0; step <= steps_done; ++step)
    for (const bool loaded : {true, false}) {  // in the order of their times
      const Real time = (step - (loaded ? 0.5 : 0.0)) * scene.steps.dt;
      if (std::filesystem::exists(vtu_path(step, loaded))) series_.add(time, vtu_path(step, loaded));
      if (roller_series_ && std::filesystem::exists(roller_path(step, loaded)))
        roller_series_->add(time, roller_path(step, loaded));
    }
}

std::filesystem::path FileOutputs::vtu_path(int step, bool loaded) const {
  return out_dir_ / fmt::format("step_{:04d}{}.vtu", step, loaded ? "_loaded" : "");
}
std::filesystem::path FileOutputs::roller_path(int step, bool loaded) const {
  const bool disc = scene_.roller && scene_.roller->elastic();
  return out_dir_ / fmt::format("roller_{:04d}{}.{}", step, loaded ? "_loaded" : "", disc ? "vtu" : "vtp");
}

void FileOutputs::add_row(OutputTable table, const Row& row) { tables_.at(table)->add_row(cells_of(row)); }

void FileOutputs::add_fields(StepFields f) {
  // The mesh and its reference coordinates never change; the fields are this step's copies. One
  // job writes the step's files (the strip's and the roller's: the writer keeps few jobs queued),
  // and a series lists a file once it is complete.
  writer_.submit([this, f = std::move(f)] {
    const std::vector<VtuField> info = step_field_data(f.step, f.pass, f.time);
    const std::filesystem::path vtu = vtu_path(f.step, f.loaded), roller_file = roller_path(f.step, f.loaded);
    write_vtu(vtu, mesh_, mesh_.nodes, f.strip.point_data, f.strip.cell_data, VtuCompression::ZLib, info);
    if (f.roller_body) {
      const RollerBody& b = *f.roller_body;
      write_vtu(roller_file, *b.mesh, b.points, b.point_data, b.cell_data, VtuCompression::ZLib, info);
    } else if (f.roller) {
      write_roller_vtp(roller_file, f.roller->centre, scene_.roller->radius, f.roller->angle, info);
    }
    const std::lock_guard<std::mutex> lock(series_mutex_);
    series_.add(f.time, vtu);
    if (f.roller && roller_series_) roller_series_->add(f.time, roller_file);
  });
}

}  // namespace roller
