// rigid.SO2, rigid.SE2, rigid.SO3, rigid.SE3, rigid.SOn, rigid.SEn, Euler conversions,
// rigid.check_orthogonal, rigid.nearest_rotation.
//
// Every array argument is taken as a py::object and read by python/convert.hpp, so that a wrong
// shape or dtype names the function (as Python users call it), the argument and the expected
// shape; NaN and infinity are refused where the result would be NaN. `*` is one __mul__ per
// class that dispatches on its operand: another element (composition) or an array (action).
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <random>
#include <string>
#include <string_view>

#include "convert.hpp"
#include "rigid/common/format.hpp"
#include "rigid/lie.hpp"
#include "rotation_vector.hpp"

namespace py = pybind11;
namespace cv = rigid::python::convert;

void bind_so3_batch(py::module_& m);  // so3_batch_py.cpp: rigid.so3

namespace {

// An angle (rad) from Python, refused when it is NaN or infinite (the rotation would be NaN).
double finite_angle(double theta, const rigid::python::convert::Arg& arg) {
  if (!std::isfinite(theta)) rigid::python::convert::refuse(arg, fmt::format("must be finite; got {}", theta));
  return theta;
}

// The docstrings the groups share, filled in with the group's name, its tangent coordinates
// and its matrix form; conventions of [Sola2018] as in include/rigid/lie/*.hpp.
struct GroupDocs {
  std::string identity, exp, hat, vee, from_matrix, right_jacobian, left_jacobian,
      right_jacobian_inverse, left_jacobian_inverse, sample, log, matrix, adjoint, homogeneous,
      inverse, interpolate, is_approx, rotation, translation, act_vector, n, dimension,
      dimension_of, ad, init, angle, from_angle, from_complex, from_axis_angle;
};

GroupDocs group_docs(const std::string& g, const std::string& tangent, const std::string& matrix,
                     bool motion) {
  GroupDocs d;
  d.identity = fmt::format("The identity element of {}.", g);
  d.exp = fmt::format("Exponential map: tangent coordinates {} -> element of {}.", tangent, g);
  d.hat = fmt::format("hat(xi): the Lie-algebra matrix of the tangent coordinates {}.", tangent);
  d.vee = fmt::format(
      "vee(M): the tangent coordinates {} of a Lie-algebra matrix (inverse of hat).", tangent);
  d.from_matrix = fmt::format(
      "The element of {} whose matrix is the {} (checked within tol: RᵀR = I, "
      "det R = +1{}); raises rigid.Error giving the defect otherwise.",
      g, matrix, motion ? ", last row (0, ..., 0, 1)" : "");
  d.right_jacobian =
      "Right Jacobian Jr(xi) of exp: exp(xi + d) ≈ exp(xi) exp(Jr(xi) d) [Sola2018].";
  d.left_jacobian =
      "Left Jacobian Jl(xi) of exp: exp(xi + d) ≈ exp(Jl(xi) d) exp(xi); Jl(xi) = Jr(-xi) "
      "[Sola2018].";
  d.right_jacobian_inverse = "The inverse Jr(xi)⁻¹ of the right Jacobian, in closed form.";
  d.left_jacobian_inverse = "The inverse Jl(xi)⁻¹ of the left Jacobian, in closed form.";
  d.sample =
      motion ? fmt::format(
                   "Random elements of {} from a seeded std::mt19937_64: Haar-uniform rotation, "
                   "translation uniform in [-half_extent, half_extent] (m) on each axis.",
                   g)
             : fmt::format("Haar-uniform random elements of {} from a seeded std::mt19937_64.", g);
  d.log = fmt::format(
      "Logarithm: the tangent coordinates {} with exp(log(X)) = X (rotation angle in [0, π]).",
      tangent);
  d.matrix = fmt::format("The {}.", matrix);
  d.adjoint = "The adjoint matrix Ad(X) on tangent coordinates: X exp(xi) X⁻¹ = exp(Ad(X) xi).";
  d.homogeneous = "The homogeneous matrix [[R, t], [0, 1]] (t = 0 for a rotation): acts on (p, 1).";
  d.inverse =
      motion ? "The inverse motion (Rᵀ, -Rᵀ t): p -> Rᵀ (p - t)." : "The inverse rotation (Rᵀ).";
  d.interpolate =
      "Geodesic interpolation self · exp(s · log(self⁻¹ · other)): self at s = 0, other at s = 1.";
  d.is_approx =
      "True if self and other are the same element within tol (the angle of self⁻¹ · other, rad).";
  d.rotation = "The rotation part R.";
  d.translation = "The translation part t (m): p -> R p + t.";
  d.act_vector = "Acts on a free vector (no translation): R v.";
  d.n = "n, the dimension of the space acted on.";
  d.dimension = motion ? "Dimension of the tangent space, n(n+1)/2."
                       : "Dimension of the tangent space, n(n-1)/2.";
  d.dimension_of = fmt::format("The tangent dimension of {} for a given n.", g);
  d.ad = "The small adjoint ad(xi): the matrix of the Lie bracket [xi, ·] on tangent coordinates.";
  d.init = "The rigid motion p -> R p + t from its rotation R and translation t (m).";
  d.angle = "The rotation angle (rad): in (-π, π] for SO(2), in [0, π] for SO(3).";
  d.from_angle = "The rotation by theta (rad, counter-clockwise).";
  d.from_complex = "The rotation of the complex number c + i s (normalised).";
  d.from_axis_angle =
      "The rotation by `angle` (rad) about `axis` (normalised); raises rigid.Error on a zero axis.";
  return d;
}

// f(x) for the argument x read as a vector of length N.
template <int N, class F>
auto on_vector(std::string_view function, std::string_view name, F f) {
  return [=](const py::object& x) { return f(cv::fixed_vector<N>(x, {function, name})); };
}

// f(x) for the argument x read as an R × C matrix.
template <int R, int C, class F>
auto on_matrix(std::string_view function, std::string_view name, F f) {
  return [=](const py::object& x) { return f(cv::fixed_matrix<R, C>(x, {function, name})); };
}

// f(x, tol) for the argument x read as an R × C matrix (from_matrix).
template <int R, int C, class F>
auto on_matrix_tol(std::string_view function, std::string_view name, F f) {
  return [=](const py::object& x, double tol) {
    return f(cv::fixed_matrix<R, C>(x, {function, name}), tol);
  };
}

// f(x) for the argument x read as a vector of any length (`dim` names it: "n(n-1)/2"); the
// library checks that the length belongs to a group.
template <class F>
auto on_tangent(std::string_view function, std::string_view name, std::string_view dim, F f) {
  return [=](const py::object& x) {
    return f(cv::vector(x, {function, name}, -1, cv::Finite::kRequired, dim));
  };
}

// f(x, tol) for the argument x read as a square matrix of any size (`size` names it).
template <class F>
auto on_square_tol(std::string_view function, std::string_view name, std::string_view size, F f) {
  return [=](const py::object& x, double tol) {
    return f(cv::square_matrix(x, {function, name}, cv::Finite::kRequired, size), tol);
  };
}

// a * other: the product with another element of G, or G acting on an array of length n
// (a point for motions, a vector for rotations). `function` ("SO3.__mul__") names `*` in
// refusals of the array.
// The G that `other` holds, or nullptr when it holds none. pybind11's record of the class is
// looked up once per process (py::isinstance followed by a cast looks it up twice per call: 10 %
// of an SO3 * SO3 call), and the type is checked first (a failed pybind11 load of an array
// would look for a foreign module's class by attribute, 0.2 µs); the class lives as long as
// the module.
template <class G>
const G* element_of(const py::handle& other) {
  static const py::detail::type_info* const info = py::detail::get_type_info(typeid(G));
  if (!PyObject_TypeCheck(other.ptr(), info->type)) return nullptr;
  py::detail::type_caster_generic caster(info);
  if (!caster.load(other, /*convert=*/false)) return nullptr;
  return static_cast<const G*>(caster.value);
}

template <class G, class Act>
py::object multiply(const G& a, const py::object& other, std::string_view function, Eigen::Index n,
                    Act act) {
  if (const G* b = element_of<G>(other)) return py::cast(a * *b);
  return py::cast(act(cv::vector(other, {function, "other"}, n)));
}

template <class G, int N>
py::object multiply_fixed(const G& a, const py::object& other, std::string_view function) {
  using V = Eigen::Matrix<double, N, 1>;
  if (const G* b = element_of<G>(other)) return py::cast(a * *b);
  return py::cast(V(a * cv::fixed_vector<N>(other, {function, "other"})));
}

}  // namespace

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
  using cv::fixed_vector;
  using T1 = SO2d::Tangent;

  const GroupDocs dso2 = group_docs("SO(2)", "theta (rad, counter-clockwise)", "2×2 rotation matrix R", false);
  py::class_<SO2d>(
      m, "SO2",
      "Rotation in 2-D, stored as a unit complex number c + i s; tangent: the angle (float, rad)")
      .def_static("identity", &SO2d::identity, dso2.identity.c_str())
      .def_static(
          "exp",
          [](double theta) { return SO2d::exp(T1(finite_angle(theta, {"rigid.SO2.exp", "theta"}))); },
          py::arg("theta"), "angle (rad, counter-clockwise) -> rotation; refuses a non-finite angle")
      .def_static(
          "from_angle",
          [](double theta) { return SO2d::from_angle(finite_angle(theta, {"rigid.SO2.from_angle", "theta"})); },
          py::arg("theta"), dso2.from_angle.c_str())
      .def_static("from_complex", &SO2d::from_complex, py::arg("c"), py::arg("s"),
                  dso2.from_complex.c_str())
      .def_static("from_matrix",
                  on_matrix_tol<2, 2>("rigid.SO2.from_matrix", "R", &SO2d::from_matrix),
                  py::arg("R"), py::arg("tol") = 1e-9, dso2.from_matrix.c_str())
      .def_static(
          "hat", [](double theta) { return SO2d::hat(T1(finite_angle(theta, {"rigid.SO2.hat", "theta"}))); },
          py::arg("theta"),
          dso2.hat.c_str())
      .def_static("vee",
                  on_matrix<2, 2>("rigid.SO2.vee", "matrix",
                                  [](const Eigen::Matrix2d& W) { return SO2d::vee(W)(0); }),
                  py::arg("matrix"), dso2.vee.c_str())
      .def_static(
          "sample",
          [](std::uint64_t seed, int n) {
            std::mt19937_64 rng(seed);
            std::vector<SO2d> out;
            for (int i = 0; i < n; ++i) out.push_back(SO2d::sample(rng));
            return out;
          },
          py::arg("seed"), py::arg("n"), "n Haar-uniform rotations from a seeded std::mt19937_64")
      .def_readonly_static("dimension", &SO2d::kDim, dso2.dimension.c_str())
      .def(
          "log", [](const SO2d& R) { return R.log()(0); }, "angle in (-pi, pi]")
      .def("angle", &SO2d::angle, dso2.angle.c_str())
      .def("matrix", &SO2d::matrix, dso2.matrix.c_str())
      .def("adjoint", &SO2d::adjoint, dso2.adjoint.c_str())
      .def("homogeneous", &SO2d::homogeneous, dso2.homogeneous.c_str())
      .def(
          "complex", [](const SO2d& R) { return V2(R.real(), R.imag()); }, "(c, s)")
      .def("inverse", &SO2d::inverse, dso2.inverse.c_str())
      .def("interpolate", &SO2d::interpolate, py::arg("other"), py::arg("s"),
           dso2.interpolate.c_str())
      .def("is_approx", &SO2d::is_approx, py::arg("other"), py::arg("tol") = 1e-12,
           dso2.is_approx.c_str())
      .def(
          "__mul__",
          [](const SO2d& a, const py::object& other) {
            return multiply_fixed<SO2d, 2>(a, other, "SO2.__mul__");
          },
          py::arg("other"), py::is_operator(),
          "Composition self * other (other: an SO2), or the rotated vector R v (other: shape "
          "(2,)).")
      .def("__repr__", [](const SO2d& R) { return fmt::format("SO2(angle={})", R.angle()); });

  const GroupDocs dse2 = group_docs("SE(2)", "(rho_x, rho_y, theta) (m, m, rad)", "3×3 homogeneous matrix [[R, t], [0, 1]]", true);
  py::class_<SE2d>(m, "SE2",
                   "Rigid motion of the plane (R, t): p -> R p + t; tangent (rho_x, rho_y, theta)")
      .def(py::init([](const SO2d& R, const py::object& t) {
             return SE2d(R, fixed_vector<2>(t, {"rigid.SE2", "t"}));
           }),
           py::arg("R"), py::arg("t"), dse2.init.c_str())
      .def_static("identity", &SE2d::identity, dse2.identity.c_str())
      .def_static("exp", on_vector<3>("rigid.SE2.exp", "xi", &SE2d::exp), py::arg("xi"),
                  dse2.exp.c_str())
      .def_static("hat", on_vector<3>("rigid.SE2.hat", "xi", &SE2d::hat), py::arg("xi"),
                  dse2.hat.c_str())
      .def_static("vee", on_matrix<3, 3>("rigid.SE2.vee", "matrix", &SE2d::vee), py::arg("matrix"),
                  dse2.vee.c_str())
      .def_static("from_matrix",
                  on_matrix_tol<3, 3>("rigid.SE2.from_matrix", "T", &SE2d::from_matrix),
                  py::arg("T"), py::arg("tol") = 1e-9, dse2.from_matrix.c_str())
      .def_static("right_jacobian",
                  on_vector<3>("rigid.SE2.right_jacobian", "xi", &SE2d::right_jacobian),
                  py::arg("xi"), dse2.right_jacobian.c_str())
      .def_static("left_jacobian",
                  on_vector<3>("rigid.SE2.left_jacobian", "xi", &SE2d::left_jacobian),
                  py::arg("xi"), dse2.left_jacobian.c_str())
      .def_static(
          "right_jacobian_inverse",
          on_vector<3>("rigid.SE2.right_jacobian_inverse", "xi", &SE2d::right_jacobian_inverse),
          py::arg("xi"), dse2.right_jacobian_inverse.c_str())
      .def_static(
          "left_jacobian_inverse",
          on_vector<3>("rigid.SE2.left_jacobian_inverse", "xi", &SE2d::left_jacobian_inverse),
          py::arg("xi"), dse2.left_jacobian_inverse.c_str())
      .def_static(
          "sample",
          [](std::uint64_t seed, int n, double half_extent) {
            std::mt19937_64 rng(seed);
            std::vector<SE2d> out;
            for (int i = 0; i < n; ++i) out.push_back(SE2d::sample(rng, half_extent));
            return out;
          },
          py::arg("seed"), py::arg("n"), py::arg("half_extent") = 1.0, dse2.sample.c_str())
      .def_readonly_static("dimension", &SE2d::kDim, dse2.dimension.c_str())
      .def("log", &SE2d::log, dse2.log.c_str())
      .def("rotation", &SE2d::rotation, dse2.rotation.c_str())
      .def("translation", &SE2d::translation, dse2.translation.c_str())
      .def("matrix", &SE2d::matrix, dse2.matrix.c_str())
      .def("homogeneous", &SE2d::homogeneous, dse2.homogeneous.c_str())
      .def("adjoint", &SE2d::adjoint, dse2.adjoint.c_str())
      .def("inverse", &SE2d::inverse, dse2.inverse.c_str())
      .def("interpolate", &SE2d::interpolate, py::arg("other"), py::arg("s"),
           dse2.interpolate.c_str())
      .def(
          "act_vector",
          [](const SE2d& X, const py::object& v) -> V2 {
            return X.act_vector(fixed_vector<2>(v, {"SE2.act_vector", "v"}));
          },
          py::arg("v"), dse2.act_vector.c_str())
      .def(
          "__mul__",
          [](const SE2d& a, const py::object& other) {
            return multiply_fixed<SE2d, 2>(a, other, "SE2.__mul__");
          },
          py::arg("other"), py::is_operator(),
          "Composition self * other (other: an SE2), or the moved point R p + t (other: shape "
          "(2,)).")
      .def("__repr__", [](const SE2d& X) {
        return fmt::format("SE2(angle={}, translation={})", X.rotation().angle(), rigid::to_string(X.translation().transpose()));
      });

  const GroupDocs dson = group_docs("SO(n)", "omega in R^(n(n-1)/2) (rad; basis as in hat)", "n×n rotation matrix R", false);
  py::class_<SOn>(m, "SOn",
                  "Rotation of R^n for any n >= 2 (n x n matrix); tangent in R^(n(n-1)/2), basis "
                  "as in SOn::hat")
      .def_static("identity", &SOn::identity, py::arg("n"), dson.identity.c_str())
      .def_static("exp", on_tangent("rigid.SOn.exp", "omega", "n(n-1)/2", &SOn::exp),
                  py::arg("omega"), "so(n) coordinates -> rotation (n from the size)")
      .def_static("hat", on_tangent("rigid.SOn.hat", "omega", "n(n-1)/2", &SOn::hat),
                  py::arg("omega"), dson.hat.c_str())
      .def_static("vee", on_square_tol("rigid.SOn.vee", "matrix", "n", &SOn::vee),
                  py::arg("matrix"), py::arg("tol") = 1e-9, dson.vee.c_str())
      .def_static("ad", on_tangent("rigid.SOn.ad", "omega", "n(n-1)/2", &SOn::ad), py::arg("omega"),
                  dson.ad.c_str())
      .def_static("from_matrix",
                  on_square_tol("rigid.SOn.from_matrix", "R", "n", &SOn::from_matrix), py::arg("R"),
                  py::arg("tol") = 1e-9, dson.from_matrix.c_str())
      .def_static("dimension_of", &SOn::dimension_of, py::arg("n"), dson.dimension_of.c_str())
      .def_static("right_jacobian",
                  on_tangent("rigid.SOn.right_jacobian", "omega", "n(n-1)/2", &SOn::right_jacobian),
                  py::arg("omega"), dson.right_jacobian.c_str())
      .def_static("left_jacobian",
                  on_tangent("rigid.SOn.left_jacobian", "omega", "n(n-1)/2", &SOn::left_jacobian),
                  py::arg("omega"), dson.left_jacobian.c_str())
      .def_static("right_jacobian_inverse",
                  on_tangent("rigid.SOn.right_jacobian_inverse", "omega", "n(n-1)/2",
                             &SOn::right_jacobian_inverse),
                  py::arg("omega"), dson.right_jacobian_inverse.c_str())
      .def_static("left_jacobian_inverse",
                  on_tangent("rigid.SOn.left_jacobian_inverse", "omega", "n(n-1)/2",
                             &SOn::left_jacobian_inverse),
                  py::arg("omega"), dson.left_jacobian_inverse.c_str())
      .def_static(
          "sample",
          [](int dim, std::uint64_t seed, int count) {
            std::mt19937_64 rng(seed);
            std::vector<SOn> out;
            for (int i = 0; i < count; ++i) out.push_back(SOn::sample(dim, rng));
            return out;
          },
          py::arg("n"), py::arg("seed"), py::arg("count"),
          "count Haar-uniform rotations of R^n (seeded)")
      .def("log", &SOn::log, dson.log.c_str())
      .def("angles", &SOn::angles, "rotation angles of the planes, descending, in [0, pi]")
      .def("matrix", &SOn::matrix, dson.matrix.c_str())
      .def("homogeneous", &SOn::homogeneous, dson.homogeneous.c_str())
      .def("adjoint", &SOn::adjoint, dson.adjoint.c_str())
      .def_property_readonly("n", &SOn::n, dson.n.c_str())
      .def_property_readonly("dimension", &SOn::dimension, dson.dimension.c_str())
      .def("inverse", &SOn::inverse, dson.inverse.c_str())
      .def("interpolate", &SOn::interpolate, py::arg("other"), py::arg("s"),
           dson.interpolate.c_str())
      .def("is_approx", &SOn::is_approx, py::arg("other"), py::arg("tol") = 1e-12,
           dson.is_approx.c_str())
      .def(
          "__mul__",
          [](const SOn& a, const py::object& other) {
            return multiply(a, other, "SOn.__mul__", a.n(),
                            [&](const VX& v) -> VX { return a * v; });
          },
          py::arg("other"), py::is_operator(),
          "Composition self * other (other: an SOn of the same n), or the rotated vector R v "
          "(other: shape (n,)).")
      .def("__repr__", [](const SOn& R) {
        return fmt::format("SOn(n={}, matrix={})", R.n(), rigid::to_string(R.matrix()));
      });

  const GroupDocs dsen = group_docs("SE(n)", "(rho, omega) in R^(n(n+1)/2) (m, rad)", "(n+1)×(n+1) homogeneous matrix [[R, t], [0, 1]]", true);
  py::class_<SEn>(m, "SEn",
                  "Rigid motion of R^n (R, t) for any n >= 2; tangent (rho, omega) in R^(n(n+1)/2)")
      .def(py::init([](const SOn& R, const py::object& t) {
             return SEn(R, cv::vector(t, {"rigid.SEn", "t"}, R.n()));
           }),
           py::arg("R"), py::arg("t"), dsen.init.c_str())
      .def_static("identity", &SEn::identity, py::arg("n"), dsen.identity.c_str())
      .def_static("exp", on_tangent("rigid.SEn.exp", "xi", "n(n+1)/2", &SEn::exp), py::arg("xi"),
                  dsen.exp.c_str())
      .def_static("hat", on_tangent("rigid.SEn.hat", "xi", "n(n+1)/2", &SEn::hat), py::arg("xi"),
                  dsen.hat.c_str())
      .def_static("vee", on_square_tol("rigid.SEn.vee", "matrix", "n+1", &SEn::vee),
                  py::arg("matrix"), py::arg("tol") = 1e-9, dsen.vee.c_str())
      .def_static("ad", on_tangent("rigid.SEn.ad", "xi", "n(n+1)/2", &SEn::ad), py::arg("xi"),
                  dsen.ad.c_str())
      .def_static("from_matrix",
                  on_square_tol("rigid.SEn.from_matrix", "T", "n+1", &SEn::from_matrix),
                  py::arg("T"), py::arg("tol") = 1e-9, dsen.from_matrix.c_str())
      .def_static("dimension_of", &SEn::dimension_of, py::arg("n"), dsen.dimension_of.c_str())
      .def_static("right_jacobian",
                  on_tangent("rigid.SEn.right_jacobian", "xi", "n(n+1)/2", &SEn::right_jacobian),
                  py::arg("xi"), dsen.right_jacobian.c_str())
      .def_static("left_jacobian",
                  on_tangent("rigid.SEn.left_jacobian", "xi", "n(n+1)/2", &SEn::left_jacobian),
                  py::arg("xi"), dsen.left_jacobian.c_str())
      .def_static("right_jacobian_inverse",
                  on_tangent("rigid.SEn.right_jacobian_inverse", "xi", "n(n+1)/2",
                             &SEn::right_jacobian_inverse),
                  py::arg("xi"), dsen.right_jacobian_inverse.c_str())
      .def_static("left_jacobian_inverse",
                  on_tangent("rigid.SEn.left_jacobian_inverse", "xi", "n(n+1)/2",
                             &SEn::left_jacobian_inverse),
                  py::arg("xi"), dsen.left_jacobian_inverse.c_str())
      .def_static(
          "sample",
          [](int dim, std::uint64_t seed, int count, double half_extent) {
            std::mt19937_64 rng(seed);
            std::vector<SEn> out;
            for (int i = 0; i < count; ++i) out.push_back(SEn::sample(dim, rng, half_extent));
            return out;
          },
          py::arg("n"), py::arg("seed"), py::arg("count"), py::arg("half_extent") = 1.0,
          dsen.sample.c_str())
      .def("log", &SEn::log, dsen.log.c_str())
      .def("rotation", &SEn::rotation, dsen.rotation.c_str())
      .def("translation", &SEn::translation, dsen.translation.c_str())
      .def("matrix", &SEn::matrix, dsen.matrix.c_str())
      .def("homogeneous", &SEn::homogeneous, dsen.homogeneous.c_str())
      .def("adjoint", &SEn::adjoint, dsen.adjoint.c_str())
      .def_property_readonly("n", &SEn::n, dsen.n.c_str())
      .def_property_readonly("dimension", &SEn::dimension, dsen.dimension.c_str())
      .def("inverse", &SEn::inverse, dsen.inverse.c_str())
      .def("interpolate", &SEn::interpolate, py::arg("other"), py::arg("s"),
           dsen.interpolate.c_str())
      .def(
          "act_vector",
          [](const SEn& X, const py::object& v) -> VX {
            return X.act_vector(cv::vector(v, {"SEn.act_vector", "v"}, X.n()));
          },
          py::arg("v"), dsen.act_vector.c_str())
      .def(
          "__mul__",
          [](const SEn& a, const py::object& other) {
            return multiply(a, other, "SEn.__mul__", a.n(),
                            [&](const VX& p) -> VX { return a * p; });
          },
          py::arg("other"), py::is_operator(),
          "Composition self * other (other: an SEn of the same n), or the moved point R p + t "
          "(other: shape (n,)).")
      .def("__repr__", [](const SEn& X) {
        return fmt::format("SEn(n={}, matrix={})", X.n(), rigid::to_string(X.matrix()));
      });

  const GroupDocs dso3 = group_docs("SO(3)", "omega (rotation vector: axis · angle, rad)", "3×3 rotation matrix R_AB (v_A = R_AB v_B)", false);
  py::class_<SO3d>(m, "SO3", "Rotation in 3-D, stored as a unit quaternion (w, x, y, z)")
      .def_static("identity", &SO3d::identity, dso3.identity.c_str())
      .def_static(
          "exp",
          [](const py::object& omega) {
            constexpr cv::Arg arg{"rigid.SO3.exp", "omega"};
            const V3 w = fixed_vector<3>(omega, arg, cv::Finite::kAllowed);
            try {
              return rigid::python::exp_of_rotation_vector(w);
            } catch (const rigid::Error& e) {  // as rigid.so3.exp words it
              throw rigid::Error(
                  fmt::format("{}(): argument '{}': {}", arg.function, arg.name, e.what()));
            }
          },
          py::arg("omega"), "rotation vector (rad) -> rotation; refuses a non-finite omega")
      .def_static("hat", on_vector<3>("rigid.SO3.hat", "omega", &SO3d::hat), py::arg("omega"),
                  dso3.hat.c_str())
      .def_static("vee", on_matrix<3, 3>("rigid.SO3.vee", "matrix", &SO3d::vee), py::arg("matrix"),
                  dso3.vee.c_str())
      .def_static("from_matrix",
                  on_matrix_tol<3, 3>("rigid.SO3.from_matrix", "R", &SO3d::from_matrix),
                  py::arg("R"), py::arg("tol") = 1e-9, dso3.from_matrix.c_str())
      .def_static(
          "from_quaternion", &SO3d::from_quaternion, py::arg("w"), py::arg("x"), py::arg("y"),
          py::arg("z"),
          "The rotation of the quaternion (w, x, y, z), normalised; raises rigid.Error if it is "
          "not finite or its norm is below 1e-12.")
      .def_static(
          "from_axis_angle",
          [](const py::object& axis, double angle) {
            return SO3d::from_axis_angle(
                fixed_vector<3>(axis, {"rigid.SO3.from_axis_angle", "axis"}), angle);
          },
          py::arg("axis"), py::arg("angle"), dso3.from_axis_angle.c_str())
      .def_static("right_jacobian",
                  on_vector<3>("rigid.SO3.right_jacobian", "omega", &SO3d::right_jacobian),
                  py::arg("omega"), dso3.right_jacobian.c_str())
      .def_static("left_jacobian",
                  on_vector<3>("rigid.SO3.left_jacobian", "omega", &SO3d::left_jacobian),
                  py::arg("omega"), dso3.left_jacobian.c_str())
      .def_static(
          "right_jacobian_inverse",
          on_vector<3>("rigid.SO3.right_jacobian_inverse", "omega", &SO3d::right_jacobian_inverse),
          py::arg("omega"), dso3.right_jacobian_inverse.c_str())
      .def_static(
          "left_jacobian_inverse",
          on_vector<3>("rigid.SO3.left_jacobian_inverse", "omega", &SO3d::left_jacobian_inverse),
          py::arg("omega"), dso3.left_jacobian_inverse.c_str())
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
          [](const py::object& angles, const std::string& seq, bool intrinsic) {
            // NaN passes here: the library refuses it in the words of rigid.so3.from_euler and
            // the CLI (tests/cli/test_rotation_seam.py)
            const V3 a =
                fixed_vector<3>(angles, {"rigid.SO3.from_euler", "angles"}, cv::Finite::kAllowed);
            return rigid::from_euler(a, rigid::EulerConvention::parse(seq, intrinsic));
          },
          py::arg("angles"), py::arg("sequence") = "ZYX", py::arg("intrinsic") = true,
          "The rotation of Euler angles (rad) about the axes of `sequence` (any of the 12, e.g. "
          "'ZYX', 'ZXZ'; "
          "intrinsic: about the moving axes, else about the fixed axes).")
      .def(
          "to_euler",
          [](const SO3d& R, const std::string& seq, bool intrinsic) {
            return rigid::to_euler(R, rigid::EulerConvention::parse(seq, intrinsic));
          },
          py::arg("sequence") = "ZYX", py::arg("intrinsic") = true,
          "The Euler angles (rad) of this rotation for `sequence` and intrinsic/extrinsic, as "
          "from_euler takes them.")
      .def("log", &SO3d::log, dso3.log.c_str())
      .def("angle", &SO3d::angle, dso3.angle.c_str())
      .def("matrix", &SO3d::matrix, dso3.matrix.c_str())
      .def("adjoint", &SO3d::adjoint, dso3.adjoint.c_str())
      .def("homogeneous", &SO3d::homogeneous, dso3.homogeneous.c_str())
      .def("quaternion", &SO3d::quaternion, "(w, x, y, z)")
      .def("inverse", &SO3d::inverse, dso3.inverse.c_str())
      .def("interpolate", &SO3d::interpolate, py::arg("other"), py::arg("s"),
           dso3.interpolate.c_str())
      .def("is_approx", &SO3d::is_approx, py::arg("other"), py::arg("tol") = 1e-12,
           dso3.is_approx.c_str())
      .def(
          "__mul__",
          [](const SO3d& a, const py::object& other) {
            return multiply_fixed<SO3d, 3>(a, other, "SO3.__mul__");
          },
          py::arg("other"), py::is_operator(),
          "Composition self * other (R_AC = R_AB * R_BC; other: an SO3), or the rotated vector "
          "R v (v_A = R_AB v_B; other: shape (3,)).")
      .def("__repr__", [](const SO3d& R) {
        return "SO3(quaternion wxyz=" + rigid::to_string(R.quaternion().transpose()) + ")";
      });

  const GroupDocs dse3 = group_docs("SE(3)", "(rho, omega) (m, rad; translation part first)", "4×4 homogeneous matrix [[R, t], [0, 1]]", true);
  py::class_<SE3d>(m, "SE3", "Rigid motion (R, t): p -> R p + t; tangent (rho, omega)")
      .def(py::init([](const SO3d& R, const py::object& t) {
             return SE3d(R, fixed_vector<3>(t, {"rigid.SE3", "t"}));
           }),
           py::arg("R"), py::arg("t"), dse3.init.c_str())
      .def_static("identity", &SE3d::identity, dse3.identity.c_str())
      .def_static("exp", on_vector<6>("rigid.SE3.exp", "xi", &SE3d::exp), py::arg("xi"),
                  dse3.exp.c_str())
      .def_static("hat", on_vector<6>("rigid.SE3.hat", "xi", &SE3d::hat), py::arg("xi"),
                  dse3.hat.c_str())
      .def_static("vee", on_matrix<4, 4>("rigid.SE3.vee", "matrix", &SE3d::vee), py::arg("matrix"),
                  dse3.vee.c_str())
      .def_static("from_matrix",
                  on_matrix_tol<4, 4>("rigid.SE3.from_matrix", "T", &SE3d::from_matrix),
                  py::arg("T"), py::arg("tol") = 1e-9, dse3.from_matrix.c_str())
      .def_static("right_jacobian",
                  on_vector<6>("rigid.SE3.right_jacobian", "xi", &SE3d::right_jacobian),
                  py::arg("xi"), dse3.right_jacobian.c_str())
      .def_static("left_jacobian",
                  on_vector<6>("rigid.SE3.left_jacobian", "xi", &SE3d::left_jacobian),
                  py::arg("xi"), dse3.left_jacobian.c_str())
      .def_static(
          "right_jacobian_inverse",
          on_vector<6>("rigid.SE3.right_jacobian_inverse", "xi", &SE3d::right_jacobian_inverse),
          py::arg("xi"), dse3.right_jacobian_inverse.c_str())
      .def_static(
          "left_jacobian_inverse",
          on_vector<6>("rigid.SE3.left_jacobian_inverse", "xi", &SE3d::left_jacobian_inverse),
          py::arg("xi"), dse3.left_jacobian_inverse.c_str())
      .def("log", &SE3d::log, dse3.log.c_str())
      .def("rotation", &SE3d::rotation, dse3.rotation.c_str())
      .def("translation", &SE3d::translation, dse3.translation.c_str())
      .def("matrix", &SE3d::matrix, dse3.matrix.c_str())
      .def("adjoint", &SE3d::adjoint, dse3.adjoint.c_str())
      .def("inverse", &SE3d::inverse, dse3.inverse.c_str())
      .def("interpolate", &SE3d::interpolate, py::arg("other"), py::arg("s"),
           dse3.interpolate.c_str())
      .def(
          "__mul__",
          [](const SE3d& a, const py::object& other) {
            return multiply_fixed<SE3d, 3>(a, other, "SE3.__mul__");
          },
          py::arg("other"), py::is_operator(),
          "Composition self * other (X_AC = X_AB * X_BC; other: an SE3), or the moved point "
          "R p + t (other: shape (3,)).")
      .def("__repr__", [](const SE3d& X) {
        return "SE3(quaternion wxyz=" + rigid::to_string(X.rotation().quaternion().transpose()) +
               ", translation=" + rigid::to_string(X.translation().transpose()) + ")";
      });

  py::class_<rigid::OrthogonalityReport>(m, "OrthogonalityReport",
                                              "How far a matrix M is from O(n) and SO(n): check_orthogonal(M, tol).")
      .def_readonly("defect", &rigid::OrthogonalityReport::defect, "max |MᵀM − I| (entrywise).")
      .def_readonly("determinant", &rigid::OrthogonalityReport::determinant, "det M.")
      .def_readonly("orthogonal", &rigid::OrthogonalityReport::orthogonal,
                    "True if the defect is within tol (M in O(n)).")
      .def_readonly("rotation", &rigid::OrthogonalityReport::rotation,
                    "True if also det M > 0 (M in SO(n)).")
      .def("__repr__", [](const rigid::OrthogonalityReport& r) {
        return fmt::format("OrthogonalityReport(defect={}, determinant={}, orthogonal={}, rotation={})", r.defect,
                           r.determinant, r.orthogonal ? "True" : "False", r.rotation ? "True" : "False");
      });
  m.def("check_orthogonal",
        on_square_tol("rigid.check_orthogonal", "M", "n", &rigid::check_orthogonal), py::arg("M"),
        py::arg("tol") = 1e-9, "O(n) membership: max|MᵀM − I| and det M");
  m.def(
      "nearest_rotation",
      [](const py::object& M) {
        return rigid::nearest_rotation(cv::square_matrix(M, {"rigid.nearest_rotation", "M"}));
      },
      py::arg("M"), "closest SO(n) matrix (SVD)");
  bind_so3_batch(m);
}
