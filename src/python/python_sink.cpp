#include "python_sink.hpp"

#include <variant>

namespace py = pybind11;

namespace roller::python {

py::dict row_dict(const Row& row) {
  py::dict d;
  for (const Column& c : row) std::visit([&](const auto& v) { d[c.name] = v; }, c.value);
  return d;
}

void PythonSink::add_row(OutputTable table, const Row& row) {
  MemoryOutputs::add_row(table, row);
  if (table != OutputTable::Solver) return;
  const py::gil_scoped_acquire gil;
  try {
    if (!progress_.is_none()) {
      py::dict d = row_dict(row);
      d["steps"] = total_steps_;
      progress_(d);
    }
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  } catch (py::error_already_set& e) {
    if (!error_) error_.emplace(std::move(e));
    stop_.store(SIGINT);
  }
}

}  // namespace roller::python
