// rigid.SO3, rigid.SE3, rigid.euler_*, rigid.check_orthogonal, rigid.nearest_rotation.
#include <random>

#include <pybind11/eigen.h>
#include <pybind11/operators.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "rigid/common/format.hpp"
#include "rigid/lie.hpp"

namespace py = pybind11;

void bind_lie(py::module_& m) {
  using rigid::SE3d;
  using rigid::SO3d;
  using V3 = Eigen::Vector3d;

  py::class_<SO3d>(m, "SO3", "Rotation in 3-D, stored as a unit quaternion (w, x, y, z)")
      .def_static("identity", &SO3d::identity)
      .def_static("exp", &SO3d::exp, py::arg("omega"), "rotation vector (rad) -> rotation")
      .def_static("hat", &SO3d::hat, py::arg("omega"))
      .def_static("vee", &SO3d::vee, py::arg("matrix"))
      .def_static("from_matrix", &SO3d::from_matrix, py::arg("R"), py::arg("tol") = 1e-9)
      .def_static("from_quaternion", &SO3d::from_quaternion, py::arg("w"), py::arg("x"), py::arg("y"),
                  py::arg("z"))
      .def_static("from_axis_angle", &SO3d::from_axis_angle, py::arg("axis"), py::arg("angle"))
      .def_static("right_jacobian", &SO3d::right_jacobian, py::arg("omega"))
      .def_static("left_jacobian", &SO3d::left_jacobian, py::arg("omega"))
      .def_static("right_jacobian_inverse", &SO3d::right_jacobian_inverse, py::arg("omega"))
      .def_static("left_jacobian_inverse", &SO3d::left_jacobian_inverse, py::arg("omega"))
      .def_static(
          "sample",
          [](std::uint64_t seed, int n) {
            std::mt19937_64 rng(seed);
            std::vector<SO3d> out;
            for (int i = 0; i < n; ++i) out.push_back(SO3d::sample(rng));
            return out;
          },
          py::arg("seed"), py::arg("n"), "n Haar-uniform rotations from a seeded std::mt19937_64")
      .def_static(
          "from_euler",
          [](const V3& angles, const std::string& seq, bool intrinsic) {
            return rigid::from_euler(angles, rigid::EulerConvention::parse(seq, intrinsic));
          },
          py::arg("angles"), py::arg("sequence") = "ZYX", py::arg("intrinsic") = true)
      .def(
          "to_euler",
          [](const SO3d& R, const std::string& seq, bool intrinsic) {
            return rigid::to_euler(R, rigid::EulerConvention::parse(seq, intrinsic));
          },
          py::arg("sequence") = "ZYX", py::arg("intrinsic") = true)
      .def("log", &SO3d::log)
      .def("angle", &SO3d::angle)
      .def("matrix", &SO3d::matrix)
      .def("adjoint", &SO3d::adjoint)
      .def("homogeneous", &SO3d::homogeneous)
      .def("quaternion", &SO3d::quaternion, "(w, x, y, z)")
      .def("inverse", &SO3d::inverse)
      .def("interpolate", &SO3d::interpolate, py::arg("other"), py::arg("s"))
      .def("is_approx", &SO3d::is_approx, py::arg("other"), py::arg("tol") = 1e-12)
      .def("__mul__", [](const SO3d& a, const SO3d& b) { return a * b; }, py::is_operator())
      .def("__mul__", [](const SO3d& a, const V3& v) -> V3 { return a * v; }, py::is_operator())
      .def("__repr__", [](const SO3d& R) { return "SO3(quaternion wxyz=" + rigid::to_string(R.quaternion().transpose()) + ")"; });

  py::class_<SE3d>(m, "SE3", "Rigid motion (R, t): p -> R p + t; tangent (rho, omega)")
      .def(py::init<const SO3d&, const V3&>(), py::arg("R"), py::arg("t"))
      .def_static("identity", &SE3d::identity)
      .def_static("exp", &SE3d::exp, py::arg("xi"))
      .def_static("hat", &SE3d::hat, py::arg("xi"))
      .def_static("vee", &SE3d::vee, py::arg("matrix"))
      .def_static("from_matrix", &SE3d::from_matrix, py::arg("T"), py::arg("tol") = 1e-9)
      .def_static("right_jacobian", &SE3d::right_jacobian, py::arg("xi"))
      .def_static("left_jacobian", &SE3d::left_jacobian, py::arg("xi"))
      .def("log", &SE3d::log)
      .def("rotation", &SE3d::rotation)
      .def("translation", &SE3d::translation)
      .def("matrix", &SE3d::matrix)
      .def("adjoint", &SE3d::adjoint)
      .def("inverse", &SE3d::inverse)
      .def("interpolate", &SE3d::interpolate, py::arg("other"), py::arg("s"))
      .def("__mul__", [](const SE3d& a, const SE3d& b) { return a * b; }, py::is_operator())
      .def("__mul__", [](const SE3d& a, const V3& p) -> V3 { return a * p; }, py::is_operator());

  py::class_<rigid::OrthogonalityReport>(m, "OrthogonalityReport")
      .def_readonly("defect", &rigid::OrthogonalityReport::defect)
      .def_readonly("determinant", &rigid::OrthogonalityReport::determinant)
      .def_readonly("orthogonal", &rigid::OrthogonalityReport::orthogonal)
      .def_readonly("rotation", &rigid::OrthogonalityReport::rotation);
  m.def("check_orthogonal", &rigid::check_orthogonal, py::arg("M"), py::arg("tol") = 1e-9,
        "O(n) membership: max|MᵀM − I| and det M");
  m.def("nearest_rotation", &rigid::nearest_rotation, py::arg("M"), "closest SO(n) matrix (SVD)");
}
