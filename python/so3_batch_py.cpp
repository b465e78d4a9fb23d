// rigid.so3: SO(3) operations on arrays of N rotations (quaternions (N, 4), rotation vectors
// (N, 3), matrices (N, 3, 3), Euler angles (N, 3)), looped in C++. Each element goes through
// the same SO3d function as the scalar rigid.SO3 method: the numbers are the same bit for bit,
// or within an ulp where an input quaternion is normalised (read_rotation below;
// python/tests/test_so3_batch.py).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <string_view>

#include "batch.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"
#include "rigid/lie.hpp"
#include "rotation_vector.hpp"
#include "so3_kernels.hpp"

namespace py = pybind11;

namespace {

using rigid::SO3d;
using rigid::python::batch_argument;
using rigid::python::batch_result;
using rigid::python::BatchArray;
using rigid::python::broadcast_rows;
using rigid::python::for_each_row;
using rigid::python::RowError;
namespace so3_kernels = rigid::python::so3_kernels;
using V3 = Eigen::Vector3d;

// Where w sits in a stored quaternion: wxyz (rigid's order) or xyzw (SciPy's, ROS's).
struct QuaternionOrder {
  bool scalar_last = false;
};

QuaternionOrder parse_order(std::string_view function, const std::string& order) {
  if (order == "wxyz") return {false};
  if (order == "xyzw") return {true};
  throw rigid::Error(fmt::format("{}(): order is '{}', expected wxyz or xyzw", function, order));
}

// The rotation of a stored quaternion. A quaternion that is unit to |q|² − 1 ≤ 1e-8 (anything
// computed as one, or printed with 9 digits or more) is normalised by one Newton step,
// q (3 − |q|²)/2, which leaves O(δ²) ≤ 1e-16 and needs no square root or division
// (SO3d::from_integrated_quaternion); the result is within an ulp of SO3.from_quaternion's
// q / |q|. Any other nonzero quaternion is multiplied by 1/|q| (to rounding, as
// from_quaternion); one with a non-finite component or norm below 1e-12 is refused with
// SO3.from_quaternion's message; one whose |q|² overflows is scaled by its largest component
// first.
SO3d read_rotation(const double* q, QuaternionOrder o) {
  const Eigen::Vector4d wxyz = o.scalar_last ? Eigen::Vector4d(q[3], q[0], q[1], q[2])
                                             : Eigen::Vector4d(q[0], q[1], q[2], q[3]);
  const double n2 = wxyz.squaredNorm();
  if (std::isfinite(n2) && n2 >= 1e-24) [[likely]]
    return SO3d::from_integrated_quaternion(wxyz);
  if (wxyz.allFinite() && !std::isfinite(n2)) {
    const Eigen::Vector4d scaled = wxyz / wxyz.cwiseAbs().maxCoeff();
    return SO3d::from_quaternion(scaled(0), scaled(1), scaled(2), scaled(3));
  }
  return SO3d::from_quaternion(wxyz(0), wxyz(1), wxyz(2), wxyz(3));  // throws its message
}

void write_rotation(const SO3d& R, double* out, QuaternionOrder o) {
  const Eigen::Vector4d q = R.quaternion();  // (w, x, y, z)
  if (o.scalar_last) {
    out[0] = q(1), out[1] = q(2), out[2] = q(3), out[3] = q(0);
  } else {
    out[0] = q(0), out[1] = q(1), out[2] = q(2), out[3] = q(3);
  }
}

void write_matrix(const SO3d& R, double* out) {
  const Eigen::Matrix3d M = R.matrix();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out[3 * i + j] = M(i, j);  // row-major, as numpy stores it
}

V3 read_vector(const double* p) { return {p[0], p[1], p[2]}; }

void write_vector(const V3& v, double* out) { out[0] = v(0), out[1] = v(1), out[2] = v(2); }

// A single rotation argument broadcast over the rows of the other: read once, so that a
// refusal names the argument without a row.
struct RotationArgument {
  const BatchArray* batch;
  SO3d single = SO3d::identity();
  QuaternionOrder order;
  [[nodiscard]] SO3d at(py::ssize_t i) const {
    return batch->single ? single : read_rotation(batch->row(i), order);
  }
};

RotationArgument rotation_argument(const BatchArray& b, QuaternionOrder o,
                                   std::string_view function, std::string_view name) {
  RotationArgument r{&b, SO3d::identity(), o};
  if (b.single) {
    try {
      r.single = read_rotation(b.row(0), o);
    } catch (const rigid::Error& e) {
      throw rigid::Error(fmt::format("{}(): argument '{}': {}", function, name,
                                     rigid::strip_function_names(e.what())));
    }
  }
  return r;
}

// Row i of the result is write(row i of the argument `name`): the loop of every function of
// one batch argument. The argument's elements have shape `in_element`, the result's
// `out_element`; write(in, out) reads one element and writes one (with the GIL released for
// large N: it must not touch Python objects).
template <class Write>
py::array_t<double> map_rows(std::string_view fn, const py::object& argument, std::string_view name,
                             std::initializer_list<py::ssize_t> in_element,
                             std::initializer_list<py::ssize_t> out_element, const Write& write) {
  const BatchArray a = batch_argument(argument, {fn, name}, in_element);
  py::ssize_t out_size = 1;
  for (py::ssize_t k : out_element) out_size *= k;
  auto out = batch_result(a.n, a.single, out_element);
  double* dst = out.mutable_data();
  for_each_row(a.n, a.single, fn, name,
               [&](py::ssize_t i) { write(a.row(i), dst + out_size * i); });
  return out;
}

// rigid.so3.exp and rigid.so3.log: rotation vectors to rotations and back. Rows go through the
// block loops of python/so3_kernels.hpp (exact: SO3d's operations; fast=True: vectorised);
// a block those do not take goes through the per-row SO3d code, which refuses in its words.
void bind_exp_and_log(py::module_& so3) {
  so3.def(
      "exp",
      [](const py::object& omega, const std::string& output, const std::string& order, bool fast) {
        constexpr std::string_view fn = "so3.exp";
        const QuaternionOrder o = parse_order(fn, order);
        if (output != "quaternion" && output != "matrix") {
          throw rigid::Error(
              fmt::format("so3.exp(): output is '{}', expected 'quaternion' or 'matrix'", output));
        }
        const BatchArray a = batch_argument(omega, {fn, "omega"}, {3});
        const bool matrix = output == "matrix";
        auto out = batch_result(a.n, a.single, matrix ? std::initializer_list<py::ssize_t>{3, 3}
                                                      : std::initializer_list<py::ssize_t>{4});
        double* dst = out.mutable_data();
        // a block of rows at a time (so3_kernels); a block with a row refused is redone row by
        // row through SO3.exp's code, which names it
        const auto row = [&](py::ssize_t i) {
          const SO3d R = rigid::python::exp_of_rotation_vector(read_vector(a.row(i)));
          if (matrix) {
            write_matrix(R, dst + 9 * i);
          } else {
            write_rotation(R, dst + 4 * i, o);
          }
        };
        const auto rows = fast ? so3_kernels::exp_fast : so3_kernels::exp_exact;
        if (!matrix) {
          for_each_row(a.n, a.single, fn, "omega", row, [&](py::ssize_t b, py::ssize_t e) {
            return rows(a.row(b), e - b, o.scalar_last, dst + 4 * b);
          });
        } else {
          // the quaternions, then their matrices (SO3d::matrix), 256 rows at a time
          for_each_row(a.n, a.single, fn, "omega", row, [&](py::ssize_t b, py::ssize_t e) {
            constexpr py::ssize_t kRows = 256;
            std::array<double, 4 * kRows> q{};
            for (py::ssize_t s = b; s < e; s += kRows) {
              const py::ssize_t m = std::min(kRows, e - s);
              if (!rows(a.row(s), m, false, q.data())) return false;
              for (py::ssize_t i = 0; i < m; ++i) {
                const double* r = q.data() + 4 * i;
                write_matrix(SO3d::from_unit_quaternion(r[0], r[1], r[2], r[3]), dst + 9 * (s + i));
              }
            }
            return true;
          });
        }
        return out;
      },
      py::arg("omega"), py::kw_only(), py::arg("output") = "quaternion", py::arg("order") = "wxyz",
      py::arg("fast") = false,
      "Exponential map: rotation vectors omega (N, 3), axis times angle in rad (right hand), to "
      "rotations: quaternions (N, 4) (output='quaternion') or matrices (N, 3, 3) "
      "(output='matrix'). As SO3.exp(omega[i]), bit for bit. Refuses a non-finite omega. "
      "fast=True: a vectorised loop (polynomial sin and cos), each quaternion component within "
      "4 ε (ε = 2⁻⁵²) of the default's (so3_kernels::kFastExpUlps), matrix entries within 24 ε; the "
      "same refusals.");

  so3.def(
      "log",
      [](const py::object& q, const std::string& order, bool fast) {
        constexpr std::string_view fn = "so3.log";
        const QuaternionOrder o = parse_order(fn, order);
        const BatchArray a = batch_argument(q, {fn, "q"}, {4});
        auto out = batch_result(a.n, a.single, {3});
        double* dst = out.mutable_data();
        // a block of rows at a time (so3_kernels); a block with a row to scale or refuse is
        // redone row by row through read_rotation and SO3d::log
        const auto row = [&](py::ssize_t i) {
          write_vector(read_rotation(a.row(i), o).log(), dst + 3 * i);
        };
        const auto rows = fast ? so3_kernels::log_fast : so3_kernels::log_exact;
        for_each_row(a.n, a.single, fn, "q", row, [&](py::ssize_t b, py::ssize_t e) {
          return rows(a.row(b), e - b, o.scalar_last, dst + 3 * b);
        });
        return out;
      },
      py::arg("q"), py::kw_only(), py::arg("order") = "wxyz", py::arg("fast") = false,
      "Logarithm: quaternions (N, 4) to rotation vectors (N, 3) in rad with angle in [0, π] "
      "(accurate near 0 and π). As SO3.from_quaternion(*q[i]).log() (to an ulp: the quaternion "
      "is normalised by a Newton step). fast=True: a vectorised loop (polynomial atan), each "
      "component within 4 ε |ω| (ε = 2⁻⁵², |ω| the angle) of the default's "
      "(so3_kernels::kFastLogUlps); the same refusals.");
}

// rigid.so3.compose, rigid.so3.act and rigid.so3.inverse: the group operations.
void bind_group_operations(py::module_& so3) {
  so3.def(
      "compose",
      [](const py::object& a, const py::object& b, const std::string& order) {
        constexpr std::string_view fn = "so3.compose";
        const QuaternionOrder o = parse_order(fn, order);
        const BatchArray A = batch_argument(a, {fn, "a"}, {4});
        const BatchArray B = batch_argument(b, {fn, "b"}, {4});
        const py::ssize_t n = broadcast_rows(fn, "a", A, "b", B);
        const RotationArgument ra = rotation_argument(A, o, fn, "a");
        const RotationArgument rb = rotation_argument(B, o, fn, "b");
        auto out = batch_result(n, A.single && B.single, {4});
        double* dst = out.mutable_data();
        for_each_row(n, A.single && B.single, fn, "a", [&](py::ssize_t i) {
          const SO3d Ra = ra.at(i);
          SO3d Rb = SO3d::identity();
          try {
            Rb = rb.at(i);
          } catch (const rigid::Error& e) {
            throw RowError{"b", rigid::strip_function_names(e.what())};
          }
          write_rotation(Ra * Rb, dst + 4 * i, o);
        });
        return out;
      },
      py::arg("a"), py::arg("b"), py::kw_only(), py::arg("order") = "wxyz",
      "Composition a[i] * b[i] (apply b first, then a: R_AC = R_AB * R_BC) of quaternions (N, 4); "
      "either may be a single (4,) quaternion. As SO3 * SO3.");

  so3.def(
      "act",
      [](const py::object& q, const py::object& v, const std::string& order) {
        constexpr std::string_view fn = "so3.act";
        const QuaternionOrder o = parse_order(fn, order);
        const BatchArray Q = batch_argument(q, {fn, "q"}, {4});
        const BatchArray Vs = batch_argument(v, {fn, "v"}, {3});
        const py::ssize_t n = broadcast_rows(fn, "q", Q, "v", Vs);
        const RotationArgument rq = rotation_argument(Q, o, fn, "q");
        auto out = batch_result(n, Q.single && Vs.single, {3});
        double* dst = out.mutable_data();
        for_each_row(n, Q.single && Vs.single, fn, "q", [&](py::ssize_t i) {
          const SO3d R = rq.at(i);
          const V3 x = read_vector(Vs.row(Vs.single ? 0 : i));
          if (!x.allFinite())
            throw RowError{"v", fmt::format("vector {} has a non-finite component",
                                            rigid::to_string(x.transpose()))};
          write_vector(R * x, dst + 3 * i);
        });
        return out;
      },
      py::arg("q"), py::arg("v"), py::kw_only(), py::arg("order") = "wxyz",
      "Rotated vectors q[i] * v[i] (N, 3) (active rotation: v_A = R_AB v_B); either argument may "
      "be a single element. As SO3 * vector.");

  so3.def(
      "inverse",
      [](const py::object& q, const std::string& order) {
        constexpr std::string_view fn = "so3.inverse";
        const QuaternionOrder o = parse_order(fn, order);
        return map_rows(fn, q, "q", {4}, {4}, [&](const double* in, double* out) {
          write_rotation(read_rotation(in, o).inverse(), out, o);
        });
      },
      py::arg("q"), py::kw_only(), py::arg("order") = "wxyz",
      "Inverse rotations (conjugate quaternions, normalised) (N, 4). As SO3.inverse().");
}

// rigid.so3.to_matrix and rigid.so3.from_matrix: quaternions to rotation matrices and back.
void bind_matrix_conversions(py::module_& so3) {
  so3.def(
      "to_matrix",
      [](const py::object& q, const std::string& order) {
        constexpr std::string_view fn = "so3.to_matrix";
        const QuaternionOrder o = parse_order(fn, order);
        return map_rows(fn, q, "q", {4}, {3, 3}, [&](const double* in, double* R) {
          write_matrix(read_rotation(in, o), R);
        });
      },
      py::arg("q"), py::kw_only(), py::arg("order") = "wxyz",
      "Rotation matrices (N, 3, 3) of quaternions (N, 4). As SO3.matrix().");

  so3.def(
      "from_matrix",
      [](const py::object& R, double tol, const std::string& order) {
        constexpr std::string_view fn = "so3.from_matrix";
        const QuaternionOrder o = parse_order(fn, order);
        if (!(tol >= 0.0))
          throw rigid::Error(
              fmt::format("so3.from_matrix(): tol is {}, expected a tolerance >= 0", tol));
        return map_rows(fn, R, "R", {3, 3}, {4}, [&](const double* in, double* q) {
          const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> M(in);
          write_rotation(SO3d::from_matrix(M, tol), q, o);
        });
      },
      py::arg("R"), py::kw_only(), py::arg("tol") = 1e-9, py::arg("order") = "wxyz",
      "Quaternions (N, 4) of rotation matrices (N, 3, 3). As SO3.from_matrix(R[i], tol): refuses a "
      "matrix with max|RᵀR − I| > tol or det R < 0 (use rigid.nearest_rotation first for a "
      "matrix that is only roughly orthonormal).");
}

// rigid.so3.from_euler, rigid.so3.to_euler and rigid.so3.sequences: Euler angles.
void bind_euler_conversions(py::module_& so3) {
  so3.def(
      "from_euler",
      [](const py::object& angles, const std::string& sequence, bool intrinsic,
         const std::string& order) {
        constexpr std::string_view fn = "so3.from_euler";
        const QuaternionOrder o = parse_order(fn, order);
        const rigid::EulerConvention conv = rigid::EulerConvention::parse(sequence, intrinsic);
        return map_rows(fn, angles, "angles", {3}, {4}, [&](const double* in, double* q) {
          write_rotation(rigid::from_euler(read_vector(in), conv), q, o);
        });
      },
      py::arg("angles"), py::arg("sequence") = "ZYX", py::kw_only(), py::arg("intrinsic") = true,
      py::arg("order") = "wxyz",
      "Quaternions (N, 4) of Euler angles (N, 3) in rad. sequence: one of XYZ XZY YXZ YZX ZXY ZYX "
      "XYX XZX YXY YZY ZXZ ZYZ (either case); intrinsic=True: axes moving with the body, "
      "R = R_1(a) R_2(b) R_3(c); intrinsic=False: fixed axes, R = R_3(c) R_2(b) R_1(a). SciPy "
      "spells intrinsic with upper case ('ZYX') and extrinsic with lower case ('zyx'). As "
      "SO3.from_euler(angles[i], sequence, intrinsic).");

  so3.def(
      "to_euler",
      [](const py::object& q, const std::string& sequence, bool intrinsic,
         const std::string& order) {
        constexpr std::string_view fn = "so3.to_euler";
        const QuaternionOrder o = parse_order(fn, order);
        const rigid::EulerConvention conv = rigid::EulerConvention::parse(sequence, intrinsic);
        return map_rows(fn, q, "q", {4}, {3}, [&](const double* in, double* e) {
          write_vector(rigid::to_euler(read_rotation(in, o), conv), e);
        });
      },
      py::arg("q"), py::arg("sequence") = "ZYX", py::kw_only(), py::arg("intrinsic") = true,
      py::arg("order") = "wxyz",
      "Euler angles (N, 3) in rad of quaternions (N, 4), for the sequence and intrinsic/extrinsic "
      "as in from_euler. Middle angle in [−π/2, π/2] (Tait–Bryan) or [0, π] (proper Euler), the "
      "others in (−π, π]. At gimbal lock the third intrinsic angle (the first extrinsic one) is "
      "0. As SO3.to_euler(sequence, intrinsic).");

  so3.attr("sequences") = [] {
    py::list l;
    for (std::string_view s : rigid::euler_sequences()) l.append(std::string(s));
    return py::tuple(l);
  }();
}

}  // namespace

void bind_so3_batch(py::module_& m) {
  auto so3 = m.def_submodule(
      "so3",
      "SO(3) on arrays of N rotations, looped in C++ (no Python loop; the GIL is released from "
      "4096 rows on and the rows are split over the cores from 32768 on; Ctrl-C "
      "interrupts).\n\n"
      "Rotations are unit quaternions of shape (N, 4) in the order given by the keyword `order` "
      "('wxyz', the default, or 'xyzw' as SciPy); any nonzero quaternion is normalised (as "
      "SO3.from_quaternion, to within an ulp). Rotation vectors and Euler angles are (N, 3) in "
      "rad, matrices "
      "(N, 3, 3) with R @ v rotating v. A single element ((4,), (3,), (3, 3)) gives a single "
      "result; in compose and act a single element is combined with every row of the other "
      "argument. Each element is computed by the same code as the rigid.SO3 method: the same "
      "numbers, to an ulp where a quaternion is normalised (exp and log with fast=True: to the few "
      "ulps their docstrings state). Bad input (shape, dtype, a non-finite "
      "or zero quaternion, a "
      "matrix that is not a rotation) raises rigid.Error naming the argument and the row.");

  bind_exp_and_log(so3);
  bind_group_operations(so3);
  bind_matrix_conversions(so3);
  bind_euler_conversions(so3);
}
