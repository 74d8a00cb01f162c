#pragma once
// VTK XML unstructured-grid (.vtu) files and the .pvd collection that ParaView opens as a time
// series. Fields are written as base64-encoded binary inline data (Float64 values, Int64 connectivity
// and offsets, UInt8 cell types).
#include <filesystem>
#include <string>
#include <vector>

#include "roller/core/types.hpp"
#include "roller/mesh/mesh.hpp"

namespace roller {

// One data array: n_components values per node (point data) or per element (cell data),
// stored tuple-major: values[i * n_components + c].
struct VtuField {
  std::string name;
  int n_components = 1;  // 1 scalar, 3 vector (2D vectors are padded with z = 0 by the caller),
                         // or any count (e.g. 4 for [xx, yy, zz, xy] tensors)
  std::vector<Real> values;
  std::vector<std::string> component_names;  // optional, written as ComponentName0.. attributes
};

// How the DataArrays are stored: zlib-compressed blocks (VTK's vtkZLibDataCompressor, which
// ParaView reads; a 2.9e5-dof step shrinks several times) or raw.
enum class VtuCompression { ZLib, None };

// Writes `mesh` with node coordinates `coordinates` (may differ from mesh.nodes) and the given
// point and cell data, and `field_data` (arrays of the whole dataset: one tuple each, e.g. the step
// and time). Throws std::runtime_error naming the path if the file cannot be written, and
// std::invalid_argument naming the field when a field's size does not match n_nodes *
// n_components (point), n_elements * n_components (cell) or n_components (field data).
void write_vtu(const std::filesystem::path& path, const Mesh& mesh, const std::vector<Vec2>& coordinates,
               const std::vector<VtuField>& point_data, const std::vector<VtuField>& cell_data,
               VtuCompression compression = VtuCompression::ZLib, const std::vector<VtuField>& field_data = {});

// The roller as VTK PolyData (.vtp, ASCII): its circle (a closed line of `segments` points) and a
// radius at its rotation angle, so that rolling and slip show in ParaView beside the strip.
void write_roller_vtp(const std::filesystem::path& path, const Vec2& centre, Real radius, Real angle,
                      const std::vector<VtuField>& field_data = {}, int segments = 180);

// A .pvd collection. Each add() inserts a dataset entry in time order and rewrites the .pvd file
// at once, so a run that stops early leaves a valid series of the steps already written.
class PvdSeries {
 public:
  explicit PvdSeries(std::filesystem::path pvd_path);
  // `vtu_file` is stored relative to the .pvd's folder when it lies inside it.
  void add(Real time, const std::filesystem::path& vtu_file);
  const std::filesystem::path& path() const { return path_; }

 private:
  void rewrite() const;
  std::filesystem::path path_;
  std::vector<std::pair<Real, std::string>> entries_;
};

}  // namespace roller
