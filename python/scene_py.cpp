// Python bindings of scene files: rigid.Scene(path, set=[...]) builds the model of a TOML
// scene (docs/scene-format.md); .run() returns the trajectory as a dict of numpy columns
// and the summary as a dict, the same numbers `rigid run` writes.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "rigid/scene/model.hpp"
#include "rigid/scene/scene.hpp"

namespace py = pybind11;

namespace {

using rigid::scene::Model;

py::dict run_to_python(const Model& model, const std::string& integrator) {
  rigid::scene::RunOptions options;
  options.integrator = integrator;
  // the GIL stays held: a model's compiled tape has one scratch buffer
  const rigid::scene::RunResult r = model.run(options);
  const rigid::io::Table& t = r.trajectory;
  py::dict columns;
  for (std::size_t c = 0; c < t.columns().size(); ++c) {
    py::array_t<double> a(static_cast<py::ssize_t>(t.rows()));
    auto v = a.mutable_unchecked<1>();
    for (std::size_t k = 0; k < t.rows(); ++k) v(static_cast<py::ssize_t>(k)) = t(k, c);
    columns[py::str(t.columns()[c])] = a;
  }
  const rigid::scene::RunSummary& s = r.summary;
  py::dict summary;
  summary["kind"] = s.kind;
  summary["integrator"] = s.integrator;
  summary["t_end"] = s.t_end;
  summary["dt"] = s.dt;
  summary["steps"] = s.steps;
  summary["rhs_evaluations"] = s.rhs_evaluations;
  summary["wall_time_s"] = s.wall_seconds;
  py::dict parameters, diagnostics;
  for (const auto& [name, value] : s.parameters) parameters[py::str(name)] = value;
  for (const auto& [name, value] : s.diagnostics) diagnostics[py::str(name)] = value;
  summary["parameters"] = parameters;
  summary["diagnostics"] = diagnostics;
  summary["warnings"] = s.warnings;
  py::dict out;
  out["columns"] = columns;
  out["summary"] = summary;
  return out;
}

}  // namespace

void bind_scene(py::module_& m) {
  py::class_<Model>(m, "Scene",
                    "A scene file turned into a model (parameters evaluated, mass properties and "
                    "equations built). Errors are rigid.Error with file:line:col.")
      .def(py::init([](const std::string& path, const std::vector<std::string>& set) {
             rigid::scene::Scene s = rigid::scene::load_scene(path);
             rigid::scene::apply_overrides(s, set);
             return Model(s);
           }),
           py::arg("path"), py::arg("set") = std::vector<std::string>{},
           "Loads a TOML scene; `set` holds 'name=value' parameter overrides.")
      .def_property_readonly("kind", [](const Model& mo) {
        return mo.kind() == rigid::scene::SceneKind::kCoordinates ? "coordinates" : "free_bodies";
      })
      .def_property_readonly("parameters", [](const Model& mo) {
        py::dict d;
        for (const auto& p : mo.parameters()) d[py::str(p.name)] = p.value;
        return d;
      })
      .def_property_readonly("t_end", &Model::t_end)
      .def("integrator", &Model::integrator, py::arg("requested") = std::string{},
           "The method a run uses (the requested one, the scene's, or the kind's default).")
      .def("equations", &Model::equations, py::arg("latex") = false, "The equations of motion.")
      .def("check", [](const Model& mo, const std::string& integrator) {
             rigid::scene::RunOptions o;
             o.integrator = integrator;
             mo.check(o);
           }, py::arg("integrator") = std::string{},
           "Runs the checks of a run (initial conditions, mass matrix, steps) without integrating.")
      .def("run", &run_to_python, py::arg("integrator") = std::string{},
           "Simulates to t_end: {'columns': {name: numpy array}, 'summary': {...}} with the "
           "columns of docs/scene-format.md.");
}
