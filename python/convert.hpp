#pragma once
// Array arguments from Python, with messages that name the function, the argument and the
// expected shape. A binding takes the argument as a py::object (so pybind11 never answers
// "incompatible function arguments") and converts it here:
//
//   const auto p = convert::points(points, {"rigid.mass.point_masses", "points"});
//
// Accepted: anything numpy.asarray turns into an array of real numbers (lists, tuples, numpy
// arrays of any float or integer dtype, non-contiguous views, read-only arrays). Refused with
// rigid.Error (a ValueError): a wrong shape ("rigid.mass.point_masses(): argument 'points' must
// have shape (n, 3); got (3, 5)"), a dtype that is not real numbers (complex, strings, objects,
// booleans), a ragged sequence, NaN or infinity where a finite value is required. Refused with
// TypeError: an object that is no array at all (None, a dict, a str).
//
// python/batch.hpp (the rigid.so3 batch arguments, (N, k...) or one (k...) element) builds on
// real_array, shape_text and refuse here, so batch and scalar refusals read alike.
//
// The function is named as Python users call it (rigid.mass.point_masses): the module's
// exception translator strips bare C++ names ("point_masses(): ") from library messages, but
// keeps dotted Python names.
#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "rigid/common/error.hpp"

namespace rigid::python::convert {

namespace py = pybind11;

/// Where an argument goes: the Python function (as users call it) and the argument's name.
struct Arg {
  std::string_view function;
  std::string_view name;
};

/// Whether NaN and infinity are accepted.
enum class Finite { kRequired, kAllowed };

/// A float64, C-contiguous copy (or view) of an array-like of real numbers.
using RealArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// "(5, 4)", "(3,)", "()": a numpy shape as Python prints it (a 1-tuple with its comma).
inline std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t k = 0; k < a.ndim(); ++k) {
    s += fmt::format("{}{}", k ? ", " : "", a.shape(k));
  }
  return s + (a.ndim() == 1 ? ",)" : ")");
}

/// The name of a Python object's type ("list", "NoneType"), for messages.
inline std::string type_name(const py::handle& value) {
  return py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>();
}

/// rigid::Error "<function>(): argument '<name>' <what>".
[[noreturn]] inline void refuse(const Arg& arg, const std::string& what) {
  throw rigid::Error(fmt::format("{}(): argument '{}' {}", arg.function, arg.name, what));
}

/// The argument as a float64 array of any shape; `expected` (e.g. "(n, 3)") is the shape the
/// messages name.
inline RealArray real_array(const py::handle& value, const Arg& arg, std::string_view expected,
                            Finite finite = Finite::kRequired) {
  // (py::array's default constructor would allocate an empty numpy array: 35 ns per call)
  const py::array a = [&]() -> py::array {
    if (py::isinstance<py::array>(value)) {
      return py::reinterpret_borrow<py::array>(value);  // the common case: no conversion call
    }
    try {
      // numpy.asarray, looked up once (kept for the life of the process, never destroyed after
      // the interpreter is gone)
      static const auto* asarray = new py::object(py::module_::import("numpy").attr("asarray"));
      return (*asarray)(value);
    } catch (const py::error_already_set&) {
      // numpy refuses ragged nested sequences ("inhomogeneous shape")
      refuse(arg, fmt::format("must be an array of numbers of shape {}; got a {} that is not "
                              "rectangular",
                              expected, type_name(value)));
    }
  }();
  const char kind = a.dtype().kind();
  if (a.ndim() == 0 && kind != 'f' && kind != 'i' && kind != 'u' && kind != 'c' && kind != 'b') {
    // None, a dict, a str: not an array at all
    throw py::type_error(
        fmt::format("{}(): argument '{}' must be an array of numbers of shape {}; got {}",
                    arg.function, arg.name, expected, type_name(value)));
  }
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    refuse(arg, fmt::format("must hold real numbers (a float or integer dtype) of shape {}; "
                            "got dtype {}",
                            expected, py::str(a.dtype()).cast<std::string>()));
  }
  RealArray out = RealArray::ensure(a);
  if (!out) {
    PyErr_Clear();
    refuse(arg, fmt::format("must be an array of real numbers of shape {}", expected));
  }
  if (finite == Finite::kRequired) {
    const double* d = out.data();
    for (py::ssize_t k = 0; k < out.size(); ++k) {
      if (!std::isfinite(d[k])) {
        // the multi-index of the first bad entry, as numpy prints it
        std::string index;
        py::ssize_t rest = k;
        std::vector<py::ssize_t> ix(static_cast<std::size_t>(out.ndim()));
        for (py::ssize_t dim = out.ndim() - 1; dim >= 0; --dim) {
          ix[static_cast<std::size_t>(dim)] = rest % out.shape(dim);
          rest /= out.shape(dim);
        }
        for (std::size_t j = 0; j < ix.size(); ++j)
          index += fmt::format("{}{}", j ? ", " : "", ix[j]);
        refuse(arg, fmt::format("must be finite; got {} at [{}]", d[k], index));
      }
    }
  }
  return out;
}

/// A matrix of shape (rows, cols); -1 is any size, named by `rows_name`/`cols_name` in messages
/// ("n"). Row-major as numpy prints it: a[i, j] is row i.
inline Eigen::MatrixXd matrix(const py::handle& value, const Arg& arg, Eigen::Index rows,
                              Eigen::Index cols, Finite finite = Finite::kRequired,
                              std::string_view rows_name = "n", std::string_view cols_name = "m") {
  const std::string expected =
      fmt::format("({}, {})", rows < 0 ? std::string(rows_name) : std::to_string(rows),
                  cols < 0 ? std::string(cols_name) : std::to_string(cols));
  const RealArray a = real_array(value, arg, expected, finite);
  if (a.ndim() != 2 || (rows >= 0 && a.shape(0) != rows) || (cols >= 0 && a.shape(1) != cols)) {
    refuse(arg, fmt::format("must have shape {}; got {}", expected, shape_text(a)));
  }
  Eigen::MatrixXd m(a.shape(0), a.shape(1));
  const auto v = a.unchecked<2>();
  for (py::ssize_t i = 0; i < a.shape(0); ++i)
    for (py::ssize_t j = 0; j < a.shape(1); ++j) m(i, j) = v(i, j);
  return m;
}

/// A vector of shape (n,) (n = -1: any length, named `n_name`).
inline Eigen::VectorXd vector(const py::handle& value, const Arg& arg, Eigen::Index n = -1,
                              Finite finite = Finite::kRequired, std::string_view n_name = "n") {
  const std::string expected =
      fmt::format("({},)", n < 0 ? std::string(n_name) : std::to_string(n));
  const RealArray a = real_array(value, arg, expected, finite);
  if (a.ndim() != 1 || (n >= 0 && a.shape(0) != n)) {
    refuse(arg, fmt::format("must have shape {}; got {}", expected, shape_text(a)));
  }
  Eigen::VectorXd v(a.shape(0));
  for (py::ssize_t i = 0; i < a.shape(0); ++i) v(i) = a.data()[i];
  return v;
}

/// A vector of fixed length N ((3,) for a 3-vector), without a heap allocation.
template <int N>
Eigen::Matrix<double, N, 1> fixed_vector(const py::handle& value, const Arg& arg,
                                         Finite finite = Finite::kRequired) {
  const std::string expected = fmt::format("({},)", N);
  const RealArray a = real_array(value, arg, expected, finite);
  if (a.ndim() != 1 || a.shape(0) != N) {
    refuse(arg, fmt::format("must have shape {}; got {}", expected, shape_text(a)));
  }
  return Eigen::Map<const Eigen::Matrix<double, N, 1>>(a.data());
}

/// A matrix of fixed shape (R, C), row-major as numpy prints it, without a heap allocation.
template <int R, int C>
Eigen::Matrix<double, R, C> fixed_matrix(const py::handle& value, const Arg& arg,
                                         Finite finite = Finite::kRequired) {
  const std::string expected = fmt::format("({}, {})", R, C);
  const RealArray a = real_array(value, arg, expected, finite);
  if (a.ndim() != 2 || a.shape(0) != R || a.shape(1) != C) {
    refuse(arg, fmt::format("must have shape {}; got {}", expected, shape_text(a)));
  }
  using RowMajor = Eigen::Matrix<double, R, C, C == 1 ? Eigen::ColMajor : Eigen::RowMajor>;
  return Eigen::Map<const RowMajor>(a.data());
}

inline Eigen::Vector3d vector3(const py::handle& value, const Arg& arg,
                               Finite finite = Finite::kRequired) {
  return fixed_vector<3>(value, arg, finite);
}

inline Eigen::Vector4d vector4(const py::handle& value, const Arg& arg,
                               Finite finite = Finite::kRequired) {
  return fixed_vector<4>(value, arg, finite);
}

inline Eigen::Matrix3d matrix3(const py::handle& value, const Arg& arg,
                               Finite finite = Finite::kRequired) {
  return fixed_matrix<3, 3>(value, arg, finite);
}

/// A square matrix of shape (n, n), any n (an empty one is the library's to refuse); `n_name` names
/// n in messages ("n", "n+1").
inline Eigen::MatrixXd square_matrix(const py::handle& value, const Arg& arg,
                                     Finite finite = Finite::kRequired,
                                     std::string_view n_name = "n") {
  const std::string expected = fmt::format("({0}, {0})", n_name);
  const RealArray a = real_array(value, arg, expected, finite);
  if (a.ndim() != 2 || a.shape(0) != a.shape(1)) {
    refuse(arg, fmt::format("must have shape {}; got {}", expected, shape_text(a)));
  }
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  return Eigen::Map<const RowMajor>(a.data(), a.shape(0), a.shape(1));
}

/// A list of numbers of shape (n,), as std::vector (masses, output times).
inline std::vector<double> values(const py::handle& value, const Arg& arg,
                                  Finite finite = Finite::kRequired) {
  const Eigen::VectorXd v = vector(value, arg, -1, finite);
  return {v.data(), v.data() + v.size()};
}

/// n points of dimension d (d = 3: (n, 3)), one per row, returned as the columns of a d × n
/// matrix (the library's layout). A d × n array (points as columns) is refused with its
/// transpose named: for n = d it could not be told apart, so one convention holds everywhere.
inline Eigen::MatrixXd points(const py::handle& value, const Arg& arg, Eigen::Index d = 3,
                              Finite finite = Finite::kRequired) {
  const std::string expected = fmt::format("(n, {})", d);
  const RealArray a = real_array(value, arg, expected, finite);
  if (a.ndim() != 2 || a.shape(1) != d) {
    std::string hint;
    if (a.ndim() == 2 && a.shape(0) == d)
      hint = fmt::format(" (one point per row: pass {}.T for points as columns)", arg.name);
    refuse(arg, fmt::format("must have shape {}; got {}{}", expected, shape_text(a), hint));
  }
  Eigen::MatrixXd m(d, a.shape(0));
  const auto v = a.unchecked<2>();
  for (py::ssize_t i = 0; i < a.shape(0); ++i)
    for (py::ssize_t j = 0; j < d; ++j) m(j, i) = v(i, j);
  return m;
}

/// A number argument given by keyword (a catalogue size, mass=, density=): a float or int (or a
/// numpy scalar or 0-d array of one), not a bool; NaN passes (the library names it with its unit).
inline double number(const py::handle& value, const Arg& arg) {
  if (!py::isinstance<py::bool_>(value)) {
    const RealArray a = [&] {
      try {
        return real_array(value, arg, "() (a number)", Finite::kAllowed);
      } catch (const rigid::Error&) {
        return RealArray();
      } catch (const py::type_error&) {
        return RealArray();
      }
    }();
    if (a && a.ndim() == 0) return a.data()[0];
  }
  throw py::type_error(fmt::format("{}(): argument '{}' must be a number; got {}", arg.function,
                                   arg.name, py::repr(value).cast<std::string>()));
}

/// A list of numbers the library returns (sample times, energies) as a float64 numpy array of
/// shape (n,): every numeric result reaches Python as an array, never as a list of floats.
inline py::array_t<double> array(const std::vector<double>& v) {
  py::array_t<double> out(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), out.mutable_data());
  return out;
}

/// A path argument: a str or an os.PathLike (pathlib.Path), as text. Refuses other types with
/// TypeError naming the argument.
inline std::string path(const py::handle& value, const Arg& arg) {
  const py::object os = py::module_::import("os");
  if (!py::isinstance<py::str>(value) && !py::isinstance(value, os.attr("PathLike"))) {
    throw py::type_error(
        fmt::format("{}(): argument '{}' must be a path (str or pathlib.Path); got {}",
                    arg.function, arg.name, type_name(value)));
  }
  const py::object p = os.attr("fspath")(value);
  if (!py::isinstance<py::str>(p)) {
    throw py::type_error(fmt::format("{}(): argument '{}' must be a path given as text; got bytes",
                                     arg.function, arg.name));
  }
  return p.cast<std::string>();
}

/// A path as messages show it: at most 80 characters (a document passed as a file name can
/// be long).
inline std::string shown(const std::string& file) {
  return file.size() <= 80 ? file : file.substr(0, 77) + "...";
}

/// Whether `file` is an existing regular file; false (never an exception) for a name the
/// system refuses (too long, a NUL byte).
inline bool is_file(const std::string& file) {
  std::error_code ec;
  return std::filesystem::is_regular_file(file, ec);
}

/// f() for a call that reads `file`: a file-system exception (a name too long for the system)
/// becomes rigid.Error naming the function and the file.
template <class F>
auto reading(std::string_view function, const std::string& file, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const std::filesystem::filesystem_error& e) {
    throw rigid::Error(
        fmt::format("{}(): cannot read '{}': {}", function, shown(file), e.code().message()));
  }
}

}  // namespace rigid::python::convert
