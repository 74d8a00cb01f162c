#include "results_to_python.hpp"

#include <variant>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

namespace py = pybind11;

namespace roller::python {

namespace {

// One column of a table: int64 when every cell is an index, str when any is text (each cell's
// text as the CSV file holds it), else float64.
py::object column_array(const std::vector<std::vector<CsvTable::Cell>>& rows, std::size_t col) {
  bool all_index = true, any_text = false;
  for (const auto& row : rows) {
    all_index = all_index && std::holds_alternative<Index>(row[col]);
    any_text = any_text || std::holds_alternative<std::string>(row[col]);
  }
  const auto n = static_cast<py::ssize_t>(rows.size());
  if (any_text) {
    py::list values;
    for (const auto& row : rows) values.append(py::str(cell_text(row[col])));
    return py::module_::import("numpy").attr("array")(values, py::arg("dtype") = "str");
  }
  if (all_index && !rows.empty()) {
    py::array_t<int64_t> a(n);
    auto m = a.mutable_unchecked<1>();
    for (py::ssize_t i = 0; i < n; ++i) m(i) = std::get<Index>(rows[i][col]);
    return std::move(a);
  }
  py::array_t<double> a(n);
  auto m = a.mutable_unchecked<1>();
  for (py::ssize_t i = 0; i < n; ++i)
    m(i) = std::visit(
        [](const auto& v) -> double {
          if constexpr (std::is_same_v<std::decay_t<decltype(v)>, std::string>)
            return 0.0;  // not reached: text columns are str arrays
          else
            return static_cast<double>(v);
        },
        rows[i][col]);
  return std::move(a);
}

// n_components == 1: a 1-D array; otherwise (n, n_components).
py::array field_array(const VtuField& f) {
  const auto n_comp = static_cast<py::ssize_t>(f.n_components);
  const auto n = static_cast<py::ssize_t>(f.values.size()) / n_comp;
  if (n_comp == 1) return py::array_t<double>(n, f.values.data());
  return py::array_t<double>({n, n_comp}, f.values.data());
}

py::dict fields_dict(const std::vector<VtuField>& fields) {
  py::dict d;
  for (const VtuField& f : fields) d[f.name.c_str()] = field_array(f);
  return d;
}

// An elastic roller's disc at a step (the VTU's roller_NNNN.vtu): its points placed at the centre,
// its Q4 cells and its fields.
py::dict disc_dict(const RollerBody& body) {
  py::dict d = mesh_dict(*body.mesh);
  auto points = d["points"].cast<py::array_t<double>>();
  auto p = points.mutable_unchecked<2>();
  for (py::ssize_t a = 0; a < p.shape(0); ++a) {
    p(a, 0) = body.points[static_cast<std::size_t>(a)].x();
    p(a, 1) = body.points[static_cast<std::size_t>(a)].y();
  }
  d["point_data"] = fields_dict(body.point_data);
  d["cell_data"] = fields_dict(body.cell_data);
  return d;
}

}  // namespace

py::dict tables_dict(const MemoryOutputs& outputs) {
  py::dict tables;
  for (const auto& [table, t] : outputs.tables()) {
    py::dict columns;
    for (std::size_t c = 0; c < t.columns.size(); ++c) columns[t.columns[c].c_str()] = column_array(t.rows, c);
    tables[enum_name(table)] = columns;
  }
  return tables;
}

py::list fields_list(const MemoryOutputs& outputs) {
  py::list out;
  for (const StepFields& f : outputs.fields()) {
    py::dict d;
    d["step"] = f.step;
    d["pass"] = f.pass;
    d["time"] = f.time;
    d["loaded"] = f.loaded;
    d["point_data"] = fields_dict(f.strip.point_data);
    d["cell_data"] = fields_dict(f.strip.cell_data);
    if (f.roller) {
      py::dict roller(py::arg("xc") = f.roller->centre.x(), py::arg("yc") = f.roller->centre.y(),
                      py::arg("phi") = f.roller->angle);
      if (f.roller_body) roller["disc"] = disc_dict(*f.roller_body);
      d["roller"] = roller;
    } else {
      d["roller"] = py::none();
    }
    out.append(d);
  }
  return out;
}

py::dict mesh_dict(const Mesh& mesh) {
  const auto n = static_cast<py::ssize_t>(mesh.n_nodes());
  const auto m = static_cast<py::ssize_t>(mesh.n_elements());
  const auto k = static_cast<py::ssize_t>(nodes_per_element(mesh.element_type));
  py::array_t<double> points({n, py::ssize_t{2}});
  auto p = points.mutable_unchecked<2>();
  for (py::ssize_t a = 0; a < n; ++a) {
    p(a, 0) = mesh.nodes[a].x();
    p(a, 1) = mesh.nodes[a].y();
  }
  py::array_t<int64_t> cells({m, k});
  auto c = cells.mutable_unchecked<2>();
  for (py::ssize_t e = 0; e < m; ++e)
    for (py::ssize_t j = 0; j < k; ++j) c(e, j) = mesh.elements[e][j];
  py::dict d;
  d["points"] = points;
  d["cells"] = cells;
  d["cell_type"] = enum_name(mesh.element_type);
  return d;
}

}  // namespace roller::python
