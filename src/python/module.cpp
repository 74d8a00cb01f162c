// rollerpy._roller: roller in the Python process (docs/python.md, "roller in process"). Scenes
// are loaded from a file or a dict with --set's overrides, runs give their tables and fields as
// numpy arrays, with or without the output folder's files. The package's rollerpy.inprocess wraps
// this module in typed results; use that.
#include <atomic>
#include <cmath>
#include <iostream>
#include <mutex>
#include <optional>
#include <thread>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "python_sink.hpp"
#include "results_to_python.hpp"
#include "roller/analysis/fatigue.hpp"
#include "roller/core/error.hpp"
#include "roller/core/version.hpp"
#include "roller/driver/output_columns.hpp"
#include "roller/driver/simulation.hpp"
#include "roller/io/scene_loader.hpp"
#include "roller/io/scene_warnings.hpp"
#include "roller/material/uniaxial_point.hpp"
#include "scene_from_python.hpp"

namespace py = pybind11;

namespace roller::python {

namespace {

Scene load(const std::filesystem::path& file, const py::dict& set) { return load_scene(file, overrides_of(set)); }

// Relative paths in the dict (restart.from) are taken from `base_dir`.
Scene from_dict(const py::dict& scene, const py::dict& set, const std::filesystem::path& base_dir) {
  return parse_scene(toml_document(scene), base_dir / "<dict>", overrides_of(set));
}

py::dict summary_dict(const RunSummary& s) {
  py::dict d;
  d["status"] = enum_name(s.status);
  d["exit_code"] = exit_code(s.status, s.signal);
  d["converged"] = s.converged;
  d["steps_done"] = s.steps_done;
  d["message"] = s.message;
  d["wall_s"] = s.wall_s;
  d["iterations"] = s.totals.iterations;
  d["cuts"] = s.totals.cuts;
  d["max_penetration"] = s.totals.max_penetration;
  d["peak_memory_mb"] = s.peak_memory_mb;
  return d;
}

// One run at a time in the process: MUMPS's sequential build and the libraries under it keep
// global state, and two runs from two threads at once crashed the interpreter in MUMPS's
// initialisation. A second thread waits (without the GIL) for the first run to end; a run started
// from a run's own progress callback would wait for ever, so it is refused.
// summary.json's fatigue block: the last pass's governing indices (an infinite life or index: None).
py::dict fatigue_dict(const FatigueAnswer& a) {
  auto finite = [](Real v) { return std::isfinite(v) ? py::object(py::float_(v)) : py::object(py::none()); };
  return py::dict(py::arg("pass") = a.pass, py::arg("dang_van_index") = a.dang_van_index,
                  py::arg("dang_van_depth") = a.dang_van_depth, py::arg("subsurface_index") = a.subsurface_index,
                  py::arg("subsurface_depth") = a.subsurface_depth, py::arg("surface_index") = finite(a.surface_index),
                  py::arg("traction_coefficient") = a.traction_coefficient, py::arg("peak_pressure") = a.peak_pressure,
                  py::arg("shear_yield") = a.shear_yield, py::arg("shear_strain_per_pass") = a.shear_strain_per_pass,
                  py::arg("ratchetting_life") = finite(a.ratchetting_life));
}

std::mutex run_mutex;
std::atomic<std::thread::id> run_owner{};

py::dict run(const Scene& scene, const std::optional<std::filesystem::path>& out, bool overwrite,
             const py::object& progress, bool verbose, bool resume) {
  if (run_owner.load() == std::this_thread::get_id())
    throw InputError("rollerpy.run was called from within a run (its progress callback): one run at a time");
  std::unique_lock<std::mutex> lock(run_mutex, std::defer_lock);
  std::optional<Simulation> sim;  // after the lock: destroyed before the lock is released
  struct Owner {
    ~Owner() { run_owner.store(std::thread::id{}); }
  } owner;
  {
    const py::gil_scoped_release nogil;
    lock.lock();
    run_owner.store(std::this_thread::get_id());
    sim.emplace(scene);
  }
  py::dict result;
  result["scene"] = sim->scene().name;
  result["steps"] = sim->scene().total_steps();
  std::vector<std::string> warnings = scene_warnings(sim->scene(), sim->model().mesh());
  result["mesh"] = mesh_dict(sim->model().mesh());
  PythonSink sink(progress, sim->scene().total_steps());
  RunOptions options;
  options.write_files = out.has_value();
  if (out) options.out_dir = *out;
  options.overwrite = overwrite;
  options.resume = resume;
  options.progress = verbose ? &std::cout : nullptr;
  options.stop_signal = &sink.stop();
  options.sink = &sink;
  RunSummary summary;
  {
    const py::gil_scoped_release nogil;
    summary = sim->run(options);
  }
  warnings.insert(warnings.end(), summary.warnings.begin(), summary.warnings.end());  // the run-time monitor's
  result["warnings"] = warnings;
  result["summary"] = summary_dict(summary);
  result["tables"] = tables_dict(sink);
  py::dict table_files;  // every table the scene's run fills, with its file: a resumed run's are read back
  for (const OutputTable table : tables_of(sim->scene())) table_files[enum_name(table)] = file_name(table);
  result["table_files"] = table_files;
  result["fields"] = fields_list(sink);
  if (const std::optional<ShakedownClassification>& c = summary.verdict)
    result["verdict"] = py::dict(py::arg("verdict") = enum_name(c->verdict), py::arg("criterion") = c->criterion);
  if (const std::optional<FatigueAnswer>& f = sim->state().fatigue) result["fatigue"] = fatigue_dict(*f);
  // What stopped the run early (Ctrl-C, or the progress callback's exception), for the wrapper
  // to raise with the results so far.
  result["error"] = sink.pending_error() ? sink.pending_error()->value() : py::none();
  return result;
}

// The scene's material driven in uniaxial stress through axial strains or stresses (rollerpy
// material-loops): columns of the samples as numpy arrays.
py::dict uniaxial_path(const Scene& scene, const std::string& control, const std::vector<Real>& turning_points,
                       int steps_per_branch) {
  if (control != "strain" && control != "stress")
    throw InputError("uniaxial_path: control = '" + control + "': expected 'strain' or 'stress'");
  if (!scene.material.plastic)
    throw InputError(scene.file.string() + ": [material] has no yield_stress: it is elastic");
  const std::vector<UniaxialSample> samples =
      control == "strain" ? uniaxial_strain_path(scene.material, turning_points, steps_per_branch)
                          : uniaxial_stress_path(scene.material, turning_points, steps_per_branch);
  auto column = [&](Real UniaxialSample::*field) {
    py::array_t<Real> a(static_cast<py::ssize_t>(samples.size()));
    auto v = a.mutable_unchecked<1>();
    for (std::size_t i = 0; i < samples.size(); ++i) v(static_cast<py::ssize_t>(i)) = samples[i].*field;
    return a;
  };
  py::dict d;
  d["strain"] = column(&UniaxialSample::strain);
  d["stress"] = column(&UniaxialSample::stress);
  d["plastic_strain"] = column(&UniaxialSample::plastic_strain);
  d["eq_plastic_strain"] = column(&UniaxialSample::eq_plastic_strain);
  return d;
}

// The fatigue criteria of one point's stress cycle (rows [xx, yy, zz, xy] in MPa), as a run
// computes them (analysis/fatigue.hpp): rollerpy rcf-map evaluates them on closed-form cycles.
py::dict fatigue_of_cycle(const py::array_t<Real, py::array::c_style | py::array::forcecast>& cycle, Real a) {
  if (cycle.ndim() != 2 || cycle.shape(1) != 4)
    throw InputError("fatigue_of_cycle: the cycle must be an array of rows [xx, yy, zz, xy]");
  const auto c = cycle.unchecked<2>();
  std::vector<Vec4> path;
  for (py::ssize_t i = 0; i < c.shape(0); ++i) path.push_back(Vec4(c(i, 0), c(i, 1), c(i, 2), c(i, 3)));
  const DangVan dv = dang_van(path, a);
  const EkbergSubsurface sub = ekberg_subsurface(path, a);
  return py::dict(py::arg("dang_van") = dv.value, py::arg("dang_van_shear") = dv.shear,
                  py::arg("dang_van_hydrostatic") = dv.hydrostatic, py::arg("path_radius") = dv.radius,
                  py::arg("fi_sub") = sub.value, py::arg("shear_amplitude") = sub.shear_amplitude,
                  py::arg("max_hydrostatic") = sub.max_hydrostatic);
}

}  // namespace

}  // namespace roller::python

PYBIND11_MODULE(_roller, m) {
  using namespace roller;
  using namespace roller::python;
  m.doc() = "roller in process: scenes, runs, results as numpy arrays (docs/python.md)";
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception<SystemError>(m, "ResourceError", PyExc_RuntimeError);

  py::class_<Scene>(m, "Scene", "a checked scene (docs/scenes.md)")
      .def_readonly("name", &Scene::name)
      .def_readonly("title", &Scene::title)
      .def_property_readonly("file", [](const Scene& s) { return s.file.string(); })
      .def_property_readonly("total_steps", &Scene::total_steps)
      .def("toml", &scene_to_toml, "the scene with every default filled in (scene.resolved.toml)");

  m.def("load_scene", &load, py::arg("file"), py::arg("set") = py::dict(),
        "a scene file with overrides {'key': value} (keys as --set's, e.g. 'roller.path[1].fy')");
  m.def("scene_from_dict", &from_dict, py::arg("scene"), py::arg("set") = py::dict(), py::arg("base_dir") = ".",
        "a scene from a dict of the scene file's tables, with overrides");
  m.def("run", &run, py::arg("scene"), py::arg("out") = py::none(), py::arg("overwrite") = false,
        py::arg("progress") = py::none(), py::arg("verbose") = false, py::arg("resume") = false,
        "runs the scene (or resumes it from the folder `out`); its results in memory, and in `out` when given");
  m.def("uniaxial_path", &uniaxial_path, py::arg("scene"), py::arg("control"), py::arg("turning_points"),
        py::arg("steps_per_branch") = 50,
        "the scene's [material] at a point in uniaxial stress, from the virgin state through the axial strains "
        "(control='strain') or stresses [MPa] (control='stress'); columns strain, stress, plastic_strain, "
        "eq_plastic_strain");
  m.def("fatigue_of_cycle", &fatigue_of_cycle, py::arg("cycle"), py::arg("a"),
        "Dang Van's value max(tau + a sigma_h) and Ekberg's FI_sub = tau_eq,a + a sigma_h,max [MPa] of a stress "
        "cycle (an n x 4 array of [xx, yy, zz, xy] rows), with their parts (docs/model.md, Fatigue)");
  m.def("version", [] {
    const BuildInfo b = build_info();
    return py::dict(py::arg("version") = b.version, py::arg("commit") = b.commit, py::arg("ipopt") = b.ipopt_version,
                    py::arg("mumps") = b.mumps_version);
  });
}
