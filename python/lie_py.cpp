// rigid.SO2, rigid.SE2, rigid.SO3, rigid.SE3, rigid.SOn, rigid.SEn, Euler conversions,
// rigid.check_orthogonal, rigid.nearest_rotation.
#include <random>

#include <pybind11/eigen.h>
#include <pybind11/operators.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "rigid/common/format.hpp"
#include "rigid/lie.hpp"

namespace py = pybind11;

void bind_so3_batch(py::module_& m);  // so3_batch_py.cpp: rigid.so3

void bind_lie(py::module_& m) {
  using rigid::SE2d;
  using rigid::SE3d;
  using rigid::SEn;
  using rigid::SO2d;
  using rigid::SO3d;
  using rigid::SOn;
  using V2 = Eigen::Vector2d;
  using V3 = Eigen::Vector3d;
  using VX = Eigen::VectorXd;
  using T1 = SO2d::Tangent;

  py::class_<SO2d>(m, "SO2", "Rotation in 2-D, stored as a unit complex number c + i s; tangent: the angle (float, rad)")
      .def_static("identity", &SO2d::identity)
      .def_static("exp", [](double theta) { return SO2d::exp(T1(theta)); }, py::arg("theta"),
                  "angle (rad, counter-clockwise) -> rotation")
      .def_static("from_angle", &SO2d::from_angle, py::arg("theta"))
      .def_static("from_complex", &SO2d::from_complex, py::arg("c"), py::arg("s"))
      .def_static("from_matrix", &SO2d::from_matrix, py::arg("R"), py::arg("tol") = 1e-9)
      .def_static("hat", [](double theta) { return SO2d::hat(T1(theta)); }, py::arg("theta"))
      .def_static("vee", [](const Eigen::Matrix2d& W) { return SO2d::vee(W)(0); }, py::arg("matrix"))
      .def_static(
          "sample",
          [](std::uint64_t seed, int n) {
            std::mt19937_64 rng(seed);
            std::vector<SO2d> out;
            for (int i = 0; i < n; ++i) out.push_back(SO2d::sample(rng));
            return out;
          },
          py::arg("seed"), py::arg("n"), "n Haar-uniform rotations from a seeded std::mt19937_64")
      .def_readonly_static("dimension", &SO2d::kDim)
      .def("log", [](const SO2d& R) { return R.log()(0); }, "angle in (-pi, pi]")
      .def("angle", &SO2d::angle)
      .def("matrix", &SO2d::matrix)
      .def("adjoint", &SO2d::adjoint)
      .def("homogeneous", &SO2d::homogeneous)
      .def("complex", [](const SO2d& R) { return V2(R.real(), R.imag()); }, "(c, s)")
      .def("inverse", &SO2d::inverse)
      .def("interpolate", &SO2d::interpolate, py::arg("other"), py::arg("s"))
      .def("is_approx", &SO2d::is_approx, py::arg("other"), py::arg("tol") = 1e-12)
      .def("__mul__", [](const SO2d& a, const SO2d& b) { return a * b; }, py::is_operator())
      .def("__mul__", [](const SO2d& a, const V2& v) -> V2 { return a * v; }, py::is_operator())
      .def("__repr__", [](const SO2d& R) { return fmt::format("SO2(angle={})", R.angle()); });

  py::class_<SE2d>(m, "SE2", "Rigid motion of the plane (R, t): p -> R p + t; tangent (rho_x, rho_y, theta)")
      .def(py::init<const SO2d&, const V2&>(), py::arg("R"), py::arg("t"))
      .def_static("identity", &SE2d::identity)
      .def_static("exp", &SE2d::exp, py::arg("xi"))
      .def_static("hat", &SE2d::hat, py::arg("xi"))
      .def_static("vee", &SE2d::vee, py::arg("matrix"))
      .def_static("from_matrix", &SE2d::from_matrix, py::arg("T"), py::arg("tol") = 1e-9)
      .def_static("right_jacobian", &SE2d::right_jacobian, py::arg("xi"))
      .def_static("left_jacobian", &SE2d::left_jacobian, py::arg("xi"))
      .def_static("right_jacobian_inverse", &SE2d::right_jacobian_inverse, py::arg("xi"))
      .def_static("left_jacobian_inverse", &SE2d::left_jacobian_inverse, py::arg("xi"))
      .def_static(
          "sample",
          [](std::uint64_t seed, int n, double half_extent) {
            std::mt19937_64 rng(seed);
            std::vector<SE2d> out;
            for (int i = 0; i < n; ++i) out.push_back(SE2d::sample(rng, half_extent));
            return out;
          },
          py::arg("seed"), py::arg("n"), py::arg("half_extent") = 1.0)
      .def_readonly_static("dimension", &SE2d::kDim)
      .def("log", &SE2d::log)
      .def("rotation", &SE2d::rotation)
      .def("translation", &SE2d::translation)
      .def("matrix", &SE2d::matrix)
      .def("homogeneous", &SE2d::homogeneous)
      .def("adjoint", &SE2d::adjoint)
      .def("inverse", &SE2d::inverse)
      .def("interpolate", &SE2d::interpolate, py::arg("other"), py::arg("s"))
      .def("act_vector", &SE2d::act_vector, py::arg("v"))
      .def("__mul__", [](const SE2d& a, const SE2d& b) { return a * b; }, py::is_operator())
      .def("__mul__", [](const SE2d& a, const V2& p) -> V2 { return a * p; }, py::is_operator());

  py::class_<SOn>(m, "SOn", "Rotation of R^n for any n >= 2 (n x n matrix); tangent in R^(n(n-1)/2), basis as in SOn::hat")
      .def_static("identity", &SOn::identity, py::arg("n"))
      .def_static("exp", &SOn::exp, py::arg("omega"), "so(n) coordinates -> rotation (n from the size)")
      .def_static("hat", &SOn::hat, py::arg("omega"))
      .def_static("vee", &SOn::vee, py::arg("matrix"), py::arg("tol") = 1e-9)
      .def_static("ad", &SOn::ad, py::arg("omega"))
      .def_static("from_matrix", &SOn::from_matrix, py::arg("R"), py::arg("tol") = 1e-9)
      .def_static("dimension_of", &SOn::dimension_of, py::arg("n"))
      .def_static("right_jacobian", &SOn::right_jacobian, py::arg("omega"))
      .def_static("left_jacobian", &SOn::left_jacobian, py::arg("omega"))
      .def_static("right_jacobian_inverse", &SOn::right_jacobian_inverse, py::arg("omega"))
      .def_static("left_jacobian_inverse", &SOn::left_jacobian_inverse, py::arg("omega"))
      .def_static(
          "sample",
          [](int dim, std::uint64_t seed, int count) {
            std::mt19937_64 rng(seed);
            std::vector<SOn> out;
            for (int i = 0; i < count; ++i) out.push_back(SOn::sample(dim, rng));
            return out;
          },
          py::arg("n"), py::arg("seed"), py::arg("count"), "count Haar-uniform rotations of R^n (seeded)")
      .def("log", &SOn::log)
      .def("angles", &SOn::angles, "rotation angles of the planes, descending, in [0, pi]")
      .def("matrix", &SOn::matrix)
      .def("homogeneous", &SOn::homogeneous)
      .def("adjoint", &SOn::adjoint)
      .def_property_readonly("n", &SOn::n)
      .def_property_readonly("dimension", &SOn::dimension)
      .def("inverse", &SOn::inverse)
      .def("interpolate", &SOn::interpolate, py::arg("other"), py::arg("s"))
      .def("is_approx", &SOn::is_approx, py::arg("other"), py::arg("tol") = 1e-12)
      .def("__mul__", [](const SOn& a, const SOn& b) { return a * b; }, py::is_operator())
      .def("__mul__", [](const SOn& a, const VX& v) -> VX { return a * v; }, py::is_operator())
      .def("__repr__", [](const SOn& R) { return fmt::format("SOn(n={}, matrix={})", R.n(), rigid::to_string(R.matrix())); });

  py::class_<SEn>(m, "SEn", "Rigid motion of R^n (R, t) for any n >= 2; tangent (rho, omega) in R^(n(n+1)/2)")
      .def(py::init<const SOn&, const VX&>(), py::arg("R"), py::arg("t"))
      .def_static("identity", &SEn::identity, py::arg("n"))
      .def_static("exp", &SEn::exp, py::arg("xi"))
      .def_static("hat", &SEn::hat, py::arg("xi"))
      .def_static("vee", &SEn::vee, py::arg("matrix"), py::arg("tol") = 1e-9)
      .def_static("ad", &SEn::ad, py::arg("xi"))
      .def_static("from_matrix", &SEn::from_matrix, py::arg("T"), py::arg("tol") = 1e-9)
      .def_static("dimension_of", &SEn::dimension_of, py::arg("n"))
      .def_static("right_jacobian", &SEn::right_jacobian, py::arg("xi"))
      .def_static("left_jacobian", &SEn::left_jacobian, py::arg("xi"))
      .def_static("right_jacobian_inverse", &SEn::right_jacobian_inverse, py::arg("xi"))
      .def_static("left_jacobian_inverse", &SEn::left_jacobian_inverse, py::arg("xi"))
      .def_static(
          "sample",
          [](int dim, std::uint64_t seed, int count, double half_extent) {
            std::mt19937_64 rng(seed);
            std::vector<SEn> out;
            for (int i = 0; i < count; ++i) out.push_back(SEn::sample(dim, rng, half_extent));
            return out;
          },
          py::arg("n"), py::arg("seed"), py::arg("count"), py::arg("half_extent") = 1.0)
      .def("log", &SEn::log)
      .def("rotation", &SEn::rotation)
      .def("translation", &SEn::translation)
      .def("matrix", &SEn::matrix)
      .def("homogeneous", &SEn::homogeneous)
      .def("adjoint", &SEn::adjoint)
      .def_property_readonly("n", &SEn::n)
      .def_property_readonly("dimension", &SEn::dimension)
      .def("inverse", &SEn::inverse)
      .def("interpolate", &SEn::interpolate, py::arg("other"), py::arg("s"))
      .def("act_vector", &SEn::act_vector, py::arg("v"))
      .def("__mul__", [](const SEn& a, const SEn& b) { return a * b; }, py::is_operator())
      .def("__mul__", [](const SEn& a, const VX& p) -> VX { return a * p; }, py::is_operator());

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
      .def_static("right_jacobian_inverse", &SE3d::right_jacobian_inverse, py::arg("xi"))
      .def_static("left_jacobian_inverse", &SE3d::left_jacobian_inverse, py::arg("xi"))
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
  bind_so3_batch(m);
}
