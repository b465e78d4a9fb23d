// Python bindings of linearisation and normal modes: rigid.lagrange.NormalModes and Mode,
// System.modes(at=..., parameters=...) and Scene.modes(at=...) — the numbers `rigid modes`
// prints, and .json() the document it writes.
#include <cmath>
#include <map>
#include <variant>

#include <fmt/format.h>

#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "rigid/lagrange/linearize.hpp"
#include "rigid/scene/model.hpp"
#include "rigid/scene/modes.hpp"

namespace py = pybind11;

namespace {

using rigid::lagrange::Mode;
using rigid::lagrange::NormalModes;
using rigid::lagrange::System;

// Modes of a System or a Scene, with the file the JSON document names.
struct PyModes {
  NormalModes modes;
  std::string scene;
};

std::string point_text(const NormalModes& r) {
  std::string out;
  for (std::size_t i = 0; i < r.coordinate_names.size(); ++i) {
    out += fmt::format("{}{}={:.6g}", i ? ", " : "", r.coordinate_names[i], r.q[static_cast<Eigen::Index>(i)]);
  }
  return out;
}

std::string mode_repr(const Mode& m) {
  std::string s = fmt::format("<Mode {}", rigid::lagrange::to_string(m.stability));
  if (m.omega > 0) s += fmt::format(": omega = {:.10g} rad/s ({:.10g} Hz)", m.omega, m.hz);
  if (m.growth_rate != 0) s += fmt::format(", growth rate = {:.10g} 1/s", m.growth_rate);
  return s + ">";
}

// at: {"theta1": 0.0, "psi_dot": "2*w"} or ["theta1=0", "psi_dot=2*w"] → "name=value" strings
std::vector<std::string> assignments(const py::object& at) {
  std::vector<std::string> out;
  if (at.is_none()) return out;
  if (py::isinstance<py::dict>(at)) {
    for (auto item : at.cast<py::dict>()) {
      const auto name = item.first.cast<std::string>();
      if (py::isinstance<py::str>(item.second)) {
        out.push_back(name + "=" + item.second.cast<std::string>());
      } else {
        // repr of a float is its shortest round-trip decimal, which the parser reads exactly
        out.push_back(name + "=" + py::repr(py::float_(py::reinterpret_borrow<py::object>(item.second))).cast<std::string>());
      }
    }
    return out;
  }
  return at.cast<std::vector<std::string>>();
}

}  // namespace

void bind_modes(py::module_& root) {
  py::module_ m = root.attr("lagrange").cast<py::module_>();

  py::class_<Mode>(m, "Mode", "One normal mode: δq(t) = Re(shape · e^{λ t}).")
      .def_readonly("eigenvalue", &Mode::eigenvalue, "λ (1/s), Im λ ≥ 0")
      .def_readonly("omega", &Mode::omega, "angular frequency |Im λ| (rad/s)")
      .def_readonly("hz", &Mode::hz, "frequency omega/2π (Hz)")
      .def_readonly("omega_squared", &Mode::omega_squared,
                    "ω² of K φ = ω² M φ (1/s², negative: unstable); nan for the state-space problem")
      .def_readonly("growth_rate", &Mode::growth_rate, "Re λ (1/s)")
      .def_property_readonly("stability", [](const Mode& md) { return rigid::lagrange::to_string(md.stability); },
                             "'stable', 'unstable' or 'marginal' (this mode alone, from its "
                             "eigenvalue).")
      .def_readonly("shape", &Mode::shape,
                    "complex shape over all coordinates, M-normalised, largest component real > 0")
      .def("__repr__", &mode_repr);

  py::class_<PyModes>(m, "NormalModes",
                      "The linearisation M δq̈ + C δq̇ + K δq = 0 about an equilibrium or steady "
                      "motion, and its modes (docs/lagrange.md, Normal modes).")
      .def_property_readonly("coordinates", [](const PyModes& p) { return p.modes.coordinate_names; },
                             "The coordinates of the system, in order.")
      .def_property_readonly("ignorable", [](const PyModes& p) { return p.modes.ignorable_names; },
                             "cyclic coordinates whose momentum is held (Routh reduction)")
      .def_property_readonly("reduced_coordinates", [](const PyModes& p) { return p.modes.reduced_names; },
                             "The coordinates the modes are computed in (the ignorable ones "
                             "removed).")
      .def_property_readonly("q", [](const PyModes& p) { return p.modes.q; }, "the point")
      .def_property_readonly("q_dot", [](const PyModes& p) { return p.modes.q_dot; },
                             "The velocities at the point (the cyclic rates of a steady motion, "
                             "else 0).")
      .def_property_readonly("searched", [](const PyModes& p) { return p.modes.searched; },
                             "True if the point was found by a Newton search (coordinates not "
                             "given in `at`).")
      .def_property_readonly("iterations", [](const PyModes& p) { return p.modes.iterations; },
                             "Newton iterations of the search (0 when nothing was searched).")
      .def_property_readonly("residual", [](const PyModes& p) { return p.modes.residual; },
                             "max |q̈| at the point")
      .def_property_readonly("stability", [](const PyModes& p) { return rigid::lagrange::to_string(p.modes.stability); },
                             "'stable', 'marginal' or 'unstable'")
      .def_property_readonly("gyroscopic", [](const PyModes& p) { return p.modes.gyroscopic; },
                             "solved as the state-space eigenproblem (C ≠ 0 or K not symmetric)")
      .def_property_readonly("M", [](const PyModes& p) { return p.modes.M; },
                             "Mass matrix of the linearisation M δq̈ + C δq̇ + K δq = 0 (SI units "
                             "of the coordinates).")
      .def_property_readonly("C", [](const PyModes& p) { return p.modes.C; },
                             "Velocity (damping and gyroscopic) matrix C of the linearisation.")
      .def_property_readonly("K", [](const PyModes& p) { return p.modes.K; },
                             "Stiffness matrix K of the linearisation.")
      .def_property_readonly("M_reduced", [](const PyModes& p) { return p.modes.M_reduced; },
                             "M in the reduced coordinates (ignorable ones removed).")
      .def_property_readonly("C_reduced", [](const PyModes& p) { return p.modes.C_reduced; },
                             "C in the reduced coordinates.")
      .def_property_readonly("K_reduced", [](const PyModes& p) { return p.modes.K_reduced; },
                             "K in the reduced coordinates.")
      .def_property_readonly("eigenvalues", [](const PyModes& p) { return p.modes.eigenvalues; },
                             "Every eigenvalue λ (1/s) of the linearisation.")
      .def_property_readonly("modes", [](const PyModes& p) { return p.modes.modes; },
                             "The modes (rigid.lagrange.Mode), one per eigenvalue pair.")
      .def_property_readonly("omega", [](const PyModes& p) {
        Eigen::VectorXd w(static_cast<Eigen::Index>(p.modes.modes.size()));
        for (std::size_t k = 0; k < p.modes.modes.size(); ++k) w[static_cast<Eigen::Index>(k)] = p.modes.modes[k].omega;
        return w;
      }, "the modes' angular frequencies (rad/s)")
      .def("json", [](const PyModes& p) { return rigid::scene::modes_json(p.modes, p.scene); },
           "The JSON document `rigid modes -o` writes.")
      .def("__str__", [](const PyModes& p) { return rigid::lagrange::to_text(p.modes); })
      .def("__repr__", [](const PyModes& p) {
        std::string w;
        for (const Mode& md : p.modes.modes) w += fmt::format("{}{:.6g}", w.empty() ? "" : ", ", md.omega);
        return fmt::format("<NormalModes {} at ({}): omega = [{}] rad/s>",
                           rigid::lagrange::to_string(p.modes.stability), point_text(p.modes), w);
      });

  auto system = py::reinterpret_borrow<py::object>(py::type::of<System>());
  system.attr("modes") = py::cpp_function(
      [](const System& s, const py::object& at, const std::map<std::string, double>& parameters) {
        rigid::lagrange::LinearizeOptions o;
        for (const std::string& a : assignments(at)) {
          const auto eq = a.find('=');
          if (eq == std::string::npos) throw rigid::Error(fmt::format("at: '{}' is not name=value", a));
          o.at.push_back({a.substr(0, eq), rigid::lagrange::evaluate_constant(
                                               rigid::lagrange::Expression(a.substr(eq + 1)),
                                               s.parameters(), fmt::format("at '{}'", a))});
        }
        for (const auto& [name, value] : parameters) o.parameters.push_back({name, value});
        return PyModes{rigid::lagrange::normal_modes(s, o), ""};
      },
      py::name("modes"), py::is_method(system), py::arg("at") = py::none(),
      py::arg("parameters") = std::map<std::string, double>{},
      "Linearises about an equilibrium or steady motion: `at` holds coordinates at values and "
      "gives cyclic rates ({'theta1': 0.0, 'psi_dot': 60.0} or ['theta1=0']); the other "
      "coordinates are found from the initial values. Returns rigid.lagrange.NormalModes.");

  auto scene = py::reinterpret_borrow<py::object>(py::type::of<rigid::scene::Model>());
  scene.attr("system") = py::module_::import("builtins").attr("property")(py::cpp_function(
      [](const rigid::scene::Model& model) -> const System& { return model.system(); },
      py::is_method(scene), py::return_value_policy::reference_internal,
      "The rigid.lagrange.System of a scene of coordinates (its equations, M, f, accelerations)."));
  scene.attr("modes") = py::cpp_function(
      [](const rigid::scene::Model& model, const py::object& at) {
        return PyModes{rigid::scene::normal_modes(model, assignments(at)), model.scene().file.string()};
      },
      py::name("modes"), py::is_method(scene), py::arg("at") = py::none(),
      "The normal modes of a scene of coordinates, as `rigid modes SCENE --at ...`: `at` as in "
      "System.modes (values may be expressions of the scene's parameters). Returns "
      "rigid.lagrange.NormalModes.");
}
