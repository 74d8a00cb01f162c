#pragma once
// A run's in-memory results as Python values with numpy arrays (docs/python.md, "roller in
// process"): each table a dict of columns (int64, float64 or str arrays), each written step's
// fields a dict of arrays (n_nodes or n_elements rows, one column per component), the mesh's
// reference points and cells.
#include <pybind11/pybind11.h>

#include "roller/driver/output_sink.hpp"
#include "roller/mesh/mesh.hpp"

namespace roller::python {

pybind11::dict tables_dict(const MemoryOutputs& outputs);
pybind11::list fields_list(const MemoryOutputs& outputs);
pybind11::dict mesh_dict(const Mesh& mesh);

}  // namespace roller::python
