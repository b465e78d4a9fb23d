// The extension module `rigid._rigid` behind the package `rigid` (python/rigid/__init__.py
// re-exports it): numpy arrays in and out, rigid::Error raised as rigid.Error (a ValueError).
#include <pybind11/pybind11.h>

#include <string>

#include "rigid/common/error.hpp"
#include "rigid/common/wording.hpp"
#include "rigid/version.hpp"

namespace py = pybind11;

void bind_mass(py::module_& m);
void bind_lie(py::module_& m);
void bind_lagrange(py::module_& m);
void bind_body(py::module_& m);
void bind_mesh(py::module_& m);
void bind_scene(py::module_& m);
void bind_modes(py::module_& m);
void bind_spring(py::module_& m);
void bind_integrate(py::module_& m);
void bind_robot(py::module_& m);
void bind_robot_regressor(py::module_& m);
void plain_argument_errors(py::module_& m, const std::string& prefix);  // argument_errors.cpp

PYBIND11_MODULE(_rigid, m) {
  m.doc() = "rigid: rigid-body mechanics from isometries and inertia tensors to Euler's equations";
  m.attr("__version__") = RIGID_VERSION_STRING;
  // classes and submodules are named after the package users import (rigid.SO3, rigid.mass), in
  // their reprs and in every docstring's signature; the module's own name is restored at the end
  m.attr("__name__") = "rigid";
  // rigid.Error (a ValueError) with the remedy worded for Python (`shell=True`, not --shell);
  // a cancelled run (Ctrl-C while the GIL was released) is a KeyboardInterrupt
  static py::exception<rigid::Error> error(m, "Error", PyExc_ValueError);
  error.attr("__doc__") =
      "Bad input or a refused computation: the message says what, where, the value, what was expected "
      "and the remedy (the text the command line prints). A ValueError.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const rigid::Cancelled& e) {
      PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
    } catch (const rigid::Error& e) {
      error(rigid::word_for(rigid::Surface::kPython, e.what()).c_str());
    }
  });
  bind_lie(m);
  bind_mass(m);
  bind_lagrange(m);
  bind_body(m);
  bind_mesh(m);
  bind_scene(m);
  bind_modes(m);
  bind_spring(m);
  bind_integrate(m);
  bind_robot(m);
  bind_robot_regressor(m);
  // arguments that match no signature: rigid's TypeError, not pybind11's list of overloads
  plain_argument_errors(m, "rigid");
  m.attr("__name__") = "rigid._rigid";
}
