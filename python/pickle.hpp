#pragma once
// Pickling of the value types (rigid.MassProperties, the Lie groups, ...): py::pickle with a
// state of plain floats and numpy arrays, restored bit for bit, so that multiprocessing and
// copy.deepcopy ship exactly the value that was pickled.
//
// Most value types have a public constructor that keeps its arguments as they are (SE3(R, t),
// MassProperties(m, c, I) of a symmetric I). Two do not: SO2::from_complex normalises (c, s)
// and SOn::from_matrix projects a matrix that is orthonormal only to a tolerance; either may
// move the last bit. For those the state is validated by the public factory and then written
// back exactly into the private members, reached through an explicit template instantiation
// (which C++ exempts from access checking: C++20 [temp.spec]/6): no header changes, and the
// invariant is still checked by the factory.
#include <fmt/format.h>
#include <pybind11/pybind11.h>

#include <string>
#include <string_view>

#include "rigid/common/error.hpp"

namespace rigid::python::pickle {

namespace py = pybind11;

/// Grant<Tag, &T::member_> defines member(Tag) returning the member pointer (see above).
template <class Tag, typename Tag::type M>
struct Grant {
  friend typename Tag::type member(Tag) { return M; }
};

/// The state tuple for `type` ("rigid.SO3.__setstate__", as messages name it) with `size` entries, or rigid.Error naming what came.
inline py::tuple state_tuple(const py::object& state, std::string_view type, std::size_t size) {
  if (!py::isinstance<py::tuple>(state) || py::len(state) != size) {
    throw rigid::Error(fmt::format(
        "{}(): the state must be the tuple of {} values that __getstate__ returns; "
        "got {}",
        type, size, py::repr(state).cast<std::string>()));
  }
  return py::reinterpret_borrow<py::tuple>(state);
}

/// A state entry that must be a float.
inline double state_float(const py::tuple& state, std::size_t k, std::string_view type) {
  const py::object v = state[k];
  if (!py::isinstance<py::float_>(v)) {
    throw rigid::Error(fmt::format("{}(): state entry {} must be a float; got {}",
                                   type, k, py::repr(v).cast<std::string>()));
  }
  return v.cast<double>();
}

}  // namespace rigid::python::pickle
