// The Python module `rigid`: numpy arrays in and out, rigid::Error raised as rigid.Error
// (a subclass of ValueError).
#include <pybind11/pybind11.h>

#include "rigid/common/error.hpp"
#include "rigid/version.hpp"

namespace py = pybind11;

void bind_mass(py::module_& m);
void bind_lie(py::module_& m);
void bind_lagrange(py::module_& m);
void bind_body(py::module_& m);
void bind_mesh(py::module_& m);
void bind_scene(py::module_& m);

PYBIND11_MODULE(rigid, m) {
  m.doc() = "rigid: rigid-body mechanics from isometries and inertia tensors to Euler's equations";
  m.attr("__version__") = RIGID_VERSION_STRING;
  py::register_exception<rigid::Error>(m, "Error", PyExc_ValueError);
  bind_lie(m);
  bind_mass(m);
  bind_lagrange(m);
  bind_body(m);
  bind_mesh(m);
  bind_scene(m);
}
