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
#include "pickle.hpp"
#include "rigid/common/format.hpp"
#include "rigid/common/wording.hpp"
#include "rigid/lie.hpp"
#include "rotation_vector.hpp"

namespace py = pybind11;
namespace cv = rigid::python::convert;

void bind_so3_batch(py::module_& m);  // so3_batch_py.cpp: rigid.so3

// The private state of SO2 (c, s) and SOn (R), written back exactly when unpickled
// (python/pickle.hpp says why).
namespace rigid::python::pickle {
struct SO2Real {
  using type = double rigid::SO2d::*;
};
struct SO2Imag {
  using type = double rigid::SO2d::*;
};
struct SOnMatrix {
  using type = Eigen::MatrixXd rigid::SOn::*;
};
SO2Real::type member(SO2Real);
SO2Imag::type member(SO2Imag);
SOnMatrix::type member(SOnMatrix);
template struct Grant<SO2Real, &rigid::SO2d::c_>;
template struct Grant<SO2Imag, &rigid::SO2d::s_>;
template struct Grant<SOnMatrix, &rigid::SOn::R_>;
}  // namespace rigid::python::pickle

namespace {

// An angle (rad) from Python, refused when it is NaN or infinite (the rotation would be NaN).
double finite_angle(double theta, const rigid::python::convert::Arg& arg) {
  if (!std::isfinite(theta))
    rigid::python::convert::refuse(arg, fmt::format("must be finite; got {}", theta));
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

// The helpers below keep `function` and `name` (for the refusals) by value: the bindings build
// them from the group's name ("rigid.SE2" + ".exp").

// f(x) for the argument x read as a vector of length N.
template <int N, class F>
auto on_vector(std::string function, std::string name, F f) {
  return [=](const py::object& x) { return f(cv::fixed_vector<N>(x, {function, name})); };
}

// f(x) for the argument x read as an R × C matrix.
template <int R, int C, class F>
auto on_matrix(std::string function, std::string name, F f) {
  return [=](const py::object& x) { return f(cv::fixed_matrix<R, C>(x, {function, name})); };
}

// f(x, tol) for the argument x read as an R × C matrix (from_matrix).
template <int R, int C, class F>
auto on_matrix_tol(std::string function, std::string name, F f) {
  return [=](const py::object& x, double tol) {
    return f(cv::fixed_matrix<R, C>(x, {function, name}), tol);
  };
}

// f(x) for the argument x read as a vector of any length (`dim` names it: "n(n-1)/2"); the
// library checks that the length belongs to a group.
template <class F>
auto on_tangent(std::string function, std::string name, std::string dim, F f) {
  return [=](const py::object& x) {
    return f(cv::vector(x, {function, name}, -1, cv::Finite::kRequired, dim));
  };
}

// f(x, tol) for the argument x read as a square matrix of any size (`size` names it).
template <class F>
auto on_square_tol(std::string function, std::string name, std::string size, F f) {
  return [=](const py::object& x, double tol) {
    return f(cv::square_matrix(x, {function, name}, cv::Finite::kRequired, size), tol);
  };
}

// How a group of fixed size reads its arguments: tangent coordinates of D entries (named
// `tangent`: "omega" or "xi"), matrices M × M (SO2, SE2, SO3, SE3).
template <int D, int M>
struct FixedSize {
  const char* tangent;

  template <class F>
  auto tangent_arg(std::string function, F f) const {
    return on_vector<D>(std::move(function), tangent, f);
  }
  template <class F>
  auto matrix_tol_arg(std::string function, std::string name, F f) const {
    return on_matrix_tol<M, M>(std::move(function), std::move(name), f);
  }
  // vee(matrix) of an M × M matrix
  template <class G>
  void def_vee(py::class_<G>& cls, const std::string& prefix, const std::string& doc) const {
    cls.def_static("vee", on_matrix<M, M>(prefix + ".vee", "matrix", &G::vee), py::arg("matrix"),
                   doc.c_str());
  }
};

// How a group of any n reads its arguments (SOn, SEn): tangent coordinates of any length
// (`dim` names it: "n(n-1)/2"), square matrices of any size (`size` names it: "n", "n+1"); the
// library checks that the sizes belong to a group.
struct AnySize {
  const char* tangent;
  const char* dim;
  const char* size;

  template <class F>
  auto tangent_arg(std::string function, F f) const {
    return on_tangent(std::move(function), tangent, dim, f);
  }
  template <class F>
  auto matrix_tol_arg(std::string function, std::string name, F f) const {
    return on_square_tol(std::move(function), std::move(name), size, f);
  }
  // vee(matrix, tol): the matrix is checked to be in the algebra within tol
  template <class G>
  void def_vee(py::class_<G>& cls, const std::string& prefix, const std::string& doc) const {
    cls.def_static("vee", on_square_tol(prefix + ".vee", "matrix", size, &G::vee),
                   py::arg("matrix"), py::arg("tol") = 1e-9, doc.c_str());
  }
};

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

// __mul__ of a group of fixed size: composition, or the action on a vector of length N.
// `function` is a string literal ("SO3.__mul__"), kept by view.
template <class G, int N>
void def_mul_fixed(py::class_<G>& cls, std::string_view function, const char* doc) {
  cls.def(
      "__mul__",
      [function](const G& a, const py::object& other) {
        return multiply_fixed<G, N>(a, other, function);
      },
      py::arg("other"), py::is_operator(), doc);
}

// `count` elements drawn by draw(rng) from a std::mt19937_64 seeded with `seed` (sample).
template <class G, class Draw>
std::vector<G> draw_samples(std::uint64_t seed, int count, Draw draw) {
  std::mt19937_64 rng(seed);
  std::vector<G> out;
  for (int i = 0; i < count; ++i) out.push_back(draw(rng));
  return out;
}

// The methods every group binds alike, on its elements: the matrix, the adjoint, the inverse
// and the geodesic interpolation.
// `prefix` is the group as Python users call it ("rigid.SE3"): interpolate's refusals name it
// and the argument (a non-finite s, or s so large that the turn is meaningless).
template <class G>
void bind_element_methods(py::class_<G>& cls, const std::string& prefix, const GroupDocs& d) {
  cls.def("matrix", &G::matrix, d.matrix.c_str())
      .def("adjoint", &G::adjoint, d.adjoint.c_str())
      .def("inverse", &G::inverse, d.inverse.c_str())
      .def(
          "interpolate",
          [function = prefix + ".interpolate"](const G& a, const G& b, const py::object& s) {
            const cv::Arg arg{function, "s"};
            const double fraction = cv::number(s, arg);
            if (!std::isfinite(fraction))
              cv::refuse(arg, fmt::format("must be finite; got {}", fraction));
            try {
              return a.interpolate(b, fraction);
            } catch (const rigid::Error& e) {
              throw rigid::Error(fmt::format("{}(): argument 's': {}", function,
                                             rigid::strip_function_names(e.what())));
            }
          },
          py::arg("other"), py::arg("s"), d.interpolate.c_str());
}

// from_matrix(M, tol) of every group; `name` is the matrix argument ("R" or "T").
template <class G, class Size>
void bind_from_matrix(py::class_<G>& cls, const std::string& prefix, const Size& size,
                      const char* name, const GroupDocs& d) {
  cls.def_static("from_matrix", size.matrix_tol_arg(prefix + ".from_matrix", name, &G::from_matrix),
                 py::arg(name), py::arg("tol") = 1e-9, d.from_matrix.c_str());
}

// The maps on tangent coordinates every group but SO2 (whose tangent is one float) binds alike:
// hat, vee and the four Jacobians of exp ([Sola2018]).
template <class G, class Size>
void bind_tangent_maps(py::class_<G>& cls, const std::string& prefix, const Size& size,
                       const GroupDocs& d) {
  const py::arg xi(size.tangent);
  cls.def_static("hat", size.tangent_arg(prefix + ".hat", &G::hat), xi, d.hat.c_str());
  size.def_vee(cls, prefix, d.vee);
  cls.def_static("right_jacobian", size.tangent_arg(prefix + ".right_jacobian", &G::right_jacobian),
                 xi, d.right_jacobian.c_str())
      .def_static("left_jacobian", size.tangent_arg(prefix + ".left_jacobian", &G::left_jacobian),
                  xi, d.left_jacobian.c_str())
      .def_static("right_jacobian_inverse",
                  size.tangent_arg(prefix + ".right_jacobian_inverse", &G::right_jacobian_inverse),
                  xi, d.right_jacobian_inverse.c_str())
      .def_static("left_jacobian_inverse",
                  size.tangent_arg(prefix + ".left_jacobian_inverse", &G::left_jacobian_inverse),
                  xi, d.left_jacobian_inverse.c_str());
}

// What the groups of any n (SOn, SEn) add: identity(n), the small adjoint ad, dimension_of(n),
// and the properties n and dimension of an element.
template <class G>
void bind_any_dimension(py::class_<G>& cls, const std::string& prefix, const AnySize& size,
                        const GroupDocs& d) {
  cls.def_static("identity", &G::identity, py::arg("n"), d.identity.c_str())
      .def_static("ad", size.tangent_arg(prefix + ".ad", &G::ad), py::arg(size.tangent),
                  d.ad.c_str())
      .def_static("dimension_of", &G::dimension_of, py::arg("n"), d.dimension_of.c_str())
      .def_property_readonly("n", &G::n, d.n.c_str())
      .def_property_readonly("dimension", &G::dimension, d.dimension.c_str());
}

// The parts of a rigid motion (SE2, SEn, SE3): p -> R p + t.
template <class G>
void bind_motion_parts(py::class_<G>& cls, const GroupDocs& d) {
  cls.def("rotation", &G::rotation, d.rotation.c_str())
      .def("translation", &G::translation, d.translation.c_str());
}

// Pickling: each group's state is its stored numbers (SO2: c, s; SO3: the quaternion; SOn: the
// matrix; a motion: its rotation's state and t), restored bit for bit after the checks a
// factory makes (a damaged state is refused with rigid.Error). `type` names the function in
// messages: "rigid.SO3.__setstate__".
namespace pk = rigid::python::pickle;

rigid::SO2d so2_of_state(double c, double s, std::string_view type) {
  const double norm2 = c * c + s * s;
  if (!(std::abs(norm2 - 1.0) <= 1e-12)) {
    throw rigid::Error(fmt::format("{}(): (c, s) = ({}, {}) is not a unit complex "
                                   "number (c² + s² = {}; expected 1 within 1e-12)",
                                   type, c, s, norm2));
  }
  rigid::SO2d R = rigid::SO2d::from_complex(c, s);  // checks finiteness
  R.*member(pk::SO2Real{}) = c;
  R.*member(pk::SO2Imag{}) = s;
  return R;
}

rigid::SO3d so3_of_state(const py::handle& q_state, std::string_view type) {
  const Eigen::Vector4d q = cv::vector4(q_state, {type, "state[0] (quaternion wxyz)"});
  const double norm2 = q(0) * q(0) + q(1) * q(1) + q(2) * q(2) + q(3) * q(3);
  if (!(std::abs(norm2 - 1.0) <= 1e-12)) {
    throw rigid::Error(fmt::format("{}(): quaternion {} is not a unit quaternion "
                                   "(norm² = {}; expected 1 within 1e-12)",
                                   type, rigid::to_string(q.transpose()), norm2));
  }
  return rigid::SO3d::from_unit_quaternion(q(0), q(1), q(2), q(3));  // exactly these numbers
}

rigid::SOn son_of_state(const py::handle& R_state, std::string_view type) {
  const Eigen::MatrixXd R = cv::square_matrix(R_state, {type, "state[0] (matrix)"});
  rigid::SOn out = rigid::SOn::from_matrix(R, 1e-9);  // a rotation within 1e-9 (may project)
  out.*member(pk::SOnMatrix{}) = R;                    // the pickled bits
  return out;
}

template <class F>
auto setting_state(std::string_view type, F f) -> decltype(f()) {
  try {
    return f();
  } catch (const rigid::Error& e) {
    const std::string what = e.what();
    if (what.rfind(type, 0) == 0) throw;  // already names rigid.X.__setstate__
    throw rigid::Error(fmt::format("{}(): {}", type, rigid::strip_function_names(what)));
  }
}

void def_pickle_so2(py::class_<rigid::SO2d>& cls) {
  cls.def(py::pickle(
      [](const rigid::SO2d& R) { return py::make_tuple(R.real(), R.imag()); },
      [](const py::tuple& state) {
        constexpr std::string_view type = "rigid.SO2.__setstate__";
        return setting_state(type, [&] {
          const py::tuple t = pk::state_tuple(state, type, 2);
          return so2_of_state(pk::state_float(t, 0, type), pk::state_float(t, 1, type), type);
        });
      }));
}

void def_pickle_se2(py::class_<rigid::SE2d>& cls) {
  cls.def(py::pickle(
      [](const rigid::SE2d& X) {
        return py::make_tuple(X.rotation().real(), X.rotation().imag(),
                              Eigen::Vector2d(X.translation()));
      },
      [](const py::tuple& state) {
        constexpr std::string_view type = "rigid.SE2.__setstate__";
        return setting_state(type, [&] {
          const py::tuple t = pk::state_tuple(state, type, 3);
          const rigid::SO2d R =
              so2_of_state(pk::state_float(t, 0, type), pk::state_float(t, 1, type), type);
          return rigid::SE2d(R, cv::fixed_vector<2>(t[2], {type, "state[2] (translation)"}));
        });
      }));
}

void def_pickle_so3(py::class_<rigid::SO3d>& cls) {
  cls.def(py::pickle(
      [](const rigid::SO3d& R) { return py::make_tuple(Eigen::Vector4d(R.quaternion())); },
      [](const py::tuple& state) {
        constexpr std::string_view type = "rigid.SO3.__setstate__";
        return setting_state(type, [&] {
          const py::tuple t = pk::state_tuple(state, type, 1);
          return so3_of_state(t[0], type);
        });
      }));
}

void def_pickle_se3(py::class_<rigid::SE3d>& cls) {
  cls.def(py::pickle(
      [](const rigid::SE3d& X) {
        return py::make_tuple(Eigen::Vector4d(X.rotation().quaternion()),
                              Eigen::Vector3d(X.translation()));
      },
      [](const py::tuple& state) {
        constexpr std::string_view type = "rigid.SE3.__setstate__";
        return setting_state(type, [&] {
          const py::tuple t = pk::state_tuple(state, type, 2);
          return rigid::SE3d(so3_of_state(t[0], type),
                             cv::vector3(t[1], {type, "state[1] (translation)"}));
        });
      }));
}

void def_pickle_son(py::class_<rigid::SOn>& cls) {
  cls.def(py::pickle([](const rigid::SOn& R) { return py::make_tuple(Eigen::MatrixXd(R.matrix())); },
                     [](const py::tuple& state) {
                       constexpr std::string_view type = "rigid.SOn.__setstate__";
                       return setting_state(type, [&] {
                         const py::tuple t = pk::state_tuple(state, type, 1);
                         return son_of_state(t[0], type);
                       });
                     }));
}

void def_pickle_sen(py::class_<rigid::SEn>& cls) {
  cls.def(py::pickle(
      [](const rigid::SEn& X) {
        return py::make_tuple(Eigen::MatrixXd(X.rotation().matrix()),
                              Eigen::VectorXd(X.translation()));
      },
      [](const py::tuple& state) {
        constexpr std::string_view type = "rigid.SEn.__setstate__";
        return setting_state(type, [&] {
          const py::tuple t = pk::state_tuple(state, type, 2);
          const rigid::SOn R = son_of_state(t[0], type);
          return rigid::SEn(R, cv::vector(t[1], {type, "state[1] (translation)"}, R.n()));
        });
      }));
}

void bind_so2(py::module_& m) {
  using rigid::SO2d;
  using T1 = SO2d::Tangent;
  const GroupDocs d =
      group_docs("SO(2)", "theta (rad, counter-clockwise)", "2×2 rotation matrix R", false);
  py::class_<SO2d> cls(
      m, "SO2",
      "Rotation in 2-D, stored as a unit complex number c + i s; tangent: the angle (float, rad)");
  cls.def_static("identity", &SO2d::identity, d.identity.c_str())
      .def_static(
          "exp",
          [](double theta) {
            return SO2d::exp(T1(finite_angle(theta, {"rigid.SO2.exp", "theta"})));
          },
          py::arg("theta"),
          "angle (rad, counter-clockwise) -> rotation; refuses a non-finite angle")
      .def_static(
          "from_angle",
          [](double theta) {
            return SO2d::from_angle(finite_angle(theta, {"rigid.SO2.from_angle", "theta"}));
          },
          py::arg("theta"), d.from_angle.c_str())
      .def_static("from_complex", &SO2d::from_complex, py::arg("c"), py::arg("s"),
                  d.from_complex.c_str());
  bind_from_matrix(cls, "rigid.SO2", FixedSize<1, 2>{"theta"}, "R", d);
  cls.def_static(
         "hat",
         [](double theta) {
           return SO2d::hat(T1(finite_angle(theta, {"rigid.SO2.hat", "theta"})));
         },
         py::arg("theta"), d.hat.c_str())
      .def_static("vee",
                  on_matrix<2, 2>("rigid.SO2.vee", "matrix",
                                  [](const Eigen::Matrix2d& W) { return SO2d::vee(W)(0); }),
                  py::arg("matrix"), d.vee.c_str())
      .def_static(
          "sample",
          [](std::uint64_t seed, int n) {
            return draw_samples<SO2d>(seed, n,
                                      [](std::mt19937_64& rng) { return SO2d::sample(rng); });
          },
          py::arg("seed"), py::arg("n"), "n Haar-uniform rotations from a seeded std::mt19937_64")
      .def_readonly_static("dimension", &SO2d::kDim, d.dimension.c_str())
      .def(
          "log", [](const SO2d& R) { return R.log()(0); }, "angle in (-pi, pi]")
      .def("angle", &SO2d::angle, d.angle.c_str())
      .def("homogeneous", &SO2d::homogeneous, d.homogeneous.c_str())
      .def(
          "complex", [](const SO2d& R) { return Eigen::Vector2d(R.real(), R.imag()); }, "(c, s)")
      .def("is_approx", &SO2d::is_approx, py::arg("other"), py::arg("tol") = 1e-12,
           d.is_approx.c_str());
  bind_element_methods(cls, "rigid.SO2", d);
  def_mul_fixed<SO2d, 2>(cls, "SO2.__mul__",
                         "Composition self * other (other: an SO2), or the rotated vector R v "
                         "(other: shape (2,)).");
  def_pickle_so2(cls);
  cls.def("__repr__", [](const SO2d& R) { return fmt::format("SO2(angle={})", R.angle()); });
}

void bind_se2(py::module_& m) {
  using rigid::SE2d;
  const GroupDocs d = group_docs("SE(2)", "(rho_x, rho_y, theta) (m, m, rad)",
                                 "3×3 homogeneous matrix [[R, t], [0, 1]]", true);
  const FixedSize<3, 3> size{"xi"};
  py::class_<SE2d> cls(
      m, "SE2", "Rigid motion of the plane (R, t): p -> R p + t; tangent (rho_x, rho_y, theta)");
  cls.def(py::init([](const rigid::SO2d& R, const py::object& t) {
            return SE2d(R, cv::fixed_vector<2>(t, {"rigid.SE2", "t"}));
          }),
          py::arg("R"), py::arg("t"), d.init.c_str())
      .def_static("identity", &SE2d::identity, d.identity.c_str())
      .def_static("exp", size.tangent_arg("rigid.SE2.exp", &SE2d::exp), py::arg("xi"),
                  d.exp.c_str());
  bind_tangent_maps(cls, "rigid.SE2", size, d);
  bind_from_matrix(cls, "rigid.SE2", size, "T", d);
  cls.def_static(
         "sample",
         [](std::uint64_t seed, int n, double half_extent) {
           return draw_samples<SE2d>(
               seed, n, [&](std::mt19937_64& rng) { return SE2d::sample(rng, half_extent); });
         },
         py::arg("seed"), py::arg("n"), py::arg("half_extent") = 1.0, d.sample.c_str())
      .def_readonly_static("dimension", &SE2d::kDim, d.dimension.c_str())
      .def("log", &SE2d::log, d.log.c_str())
      .def("homogeneous", &SE2d::homogeneous, d.homogeneous.c_str())
      .def(
          "act_vector",
          [](const SE2d& X, const py::object& v) -> Eigen::Vector2d {
            return X.act_vector(cv::fixed_vector<2>(v, {"SE2.act_vector", "v"}));
          },
          py::arg("v"), d.act_vector.c_str());
  bind_motion_parts(cls, d);
  bind_element_methods(cls, "rigid.SE2", d);
  def_mul_fixed<SE2d, 2>(cls, "SE2.__mul__",
                         "Composition self * other (other: an SE2), or the moved point R p + t "
                         "(other: shape (2,)).");
  def_pickle_se2(cls);
  cls.def("__repr__", [](const SE2d& X) {
    return fmt::format("SE2(angle={}, translation={})", X.rotation().angle(),
                       rigid::to_string(X.translation().transpose()));
  });
}

void bind_son(py::module_& m) {
  using rigid::SOn;
  const GroupDocs d = group_docs("SO(n)", "omega in R^(n(n-1)/2) (rad; basis as in hat)",
                                 "n×n rotation matrix R", false);
  const AnySize size{"omega", "n(n-1)/2", "n"};
  py::class_<SOn> cls(
      m, "SOn",
      "Rotation of R^n for any n >= 2 (n x n matrix); tangent in R^(n(n-1)/2), basis "
      "as in SOn::hat");
  bind_any_dimension(cls, "rigid.SOn", size, d);
  cls.def_static("exp", size.tangent_arg("rigid.SOn.exp", &SOn::exp), py::arg("omega"),
                 "so(n) coordinates -> rotation (n from the size)");
  bind_tangent_maps(cls, "rigid.SOn", size, d);
  bind_from_matrix(cls, "rigid.SOn", size, "R", d);
  cls.def_static(
         "sample",
         [](int dim, std::uint64_t seed, int count) {
           return draw_samples<SOn>(seed, count,
                                    [&](std::mt19937_64& rng) { return SOn::sample(dim, rng); });
         },
         py::arg("n"), py::arg("seed"), py::arg("count"),
         "count Haar-uniform rotations of R^n (seeded)")
      .def("log", &SOn::log, d.log.c_str())
      .def("angles", &SOn::angles, "rotation angles of the planes, descending, in [0, pi]")
      .def("homogeneous", &SOn::homogeneous, d.homogeneous.c_str())
      .def("is_approx", &SOn::is_approx, py::arg("other"), py::arg("tol") = 1e-12,
           d.is_approx.c_str());
  bind_element_methods(cls, "rigid.SOn", d);
  def_pickle_son(cls);
  cls.def(
         "__mul__",
         [](const SOn& a, const py::object& other) {
           return multiply(a, other, "SOn.__mul__", a.n(),
                           [&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return a * v; });
         },
         py::arg("other"), py::is_operator(),
         "Composition self * other (other: an SOn of the same n), or the rotated vector R v "
         "(other: shape (n,)).")
      .def("__repr__", [](const SOn& R) {
        return fmt::format("SOn(n={}, matrix={})", R.n(), rigid::to_string(R.matrix()));
      });
}

void bind_sen(py::module_& m) {
  using rigid::SEn;
  using VX = Eigen::VectorXd;
  const GroupDocs d = group_docs("SE(n)", "(rho, omega) in R^(n(n+1)/2) (m, rad)",
                                 "(n+1)×(n+1) homogeneous matrix [[R, t], [0, 1]]", true);
  const AnySize size{"xi", "n(n+1)/2", "n+1"};
  py::class_<SEn> cls(
      m, "SEn", "Rigid motion of R^n (R, t) for any n >= 2; tangent (rho, omega) in R^(n(n+1)/2)");
  cls.def(py::init([](const rigid::SOn& R, const py::object& t) {
            return SEn(R, cv::vector(t, {"rigid.SEn", "t"}, R.n()));
          }),
          py::arg("R"), py::arg("t"), d.init.c_str());
  bind_any_dimension(cls, "rigid.SEn", size, d);
  cls.def_static("exp", size.tangent_arg("rigid.SEn.exp", &SEn::exp), py::arg("xi"), d.exp.c_str());
  bind_tangent_maps(cls, "rigid.SEn", size, d);
  bind_from_matrix(cls, "rigid.SEn", size, "T", d);
  cls.def_static(
         "sample",
         [](int dim, std::uint64_t seed, int count, double half_extent) {
           return draw_samples<SEn>(seed, count, [&](std::mt19937_64& rng) {
             return SEn::sample(dim, rng, half_extent);
           });
         },
         py::arg("n"), py::arg("seed"), py::arg("count"), py::arg("half_extent") = 1.0,
         d.sample.c_str())
      .def("log", &SEn::log, d.log.c_str())
      .def("homogeneous", &SEn::homogeneous, d.homogeneous.c_str())
      .def(
          "act_vector",
          [](const SEn& X, const py::object& v) -> VX {
            return X.act_vector(cv::vector(v, {"SEn.act_vector", "v"}, X.n()));
          },
          py::arg("v"), d.act_vector.c_str());
  bind_motion_parts(cls, d);
  bind_element_methods(cls, "rigid.SEn", d);
  def_pickle_sen(cls);
  cls.def(
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
}

// SO3's Euler-angle conversions (any of the 12 sequences, intrinsic or extrinsic).
void bind_so3_euler(py::class_<rigid::SO3d>& cls) {
  using rigid::SO3d;
  cls.def_static(
         "from_euler",
         [](const py::object& angles, const std::string& seq, bool intrinsic) {
           // NaN passes here: the library refuses it in the words of rigid.so3.from_euler and
           // the CLI (tests/cli/test_rotation_seam.py)
           const Eigen::Vector3d a = cv::fixed_vector<3>(angles, {"rigid.SO3.from_euler", "angles"},
                                                         cv::Finite::kAllowed);
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
          "from_euler takes them.");
}

void bind_so3(py::module_& m) {
  using rigid::SO3d;
  const GroupDocs d = group_docs("SO(3)", "omega (rotation vector: axis · angle, rad)",
                                 "3×3 rotation matrix R_AB (v_A = R_AB v_B)", false);
  const FixedSize<3, 3> size{"omega"};
  py::class_<SO3d> cls(m, "SO3", "Rotation in 3-D, stored as a unit quaternion (w, x, y, z)");
  cls.def_static("identity", &SO3d::identity, d.identity.c_str())
      .def_static(
          "exp",
          [](const py::object& omega) {
            constexpr cv::Arg arg{"rigid.SO3.exp", "omega"};
            const Eigen::Vector3d w = cv::fixed_vector<3>(omega, arg, cv::Finite::kAllowed);
            try {
              return rigid::python::exp_of_rotation_vector(w);
            } catch (const rigid::Error& e) {  // as rigid.so3.exp words it
              throw rigid::Error(
                  fmt::format("{}(): argument '{}': {}", arg.function, arg.name, e.what()));
            }
          },
          py::arg("omega"), "rotation vector (rad) -> rotation; refuses a non-finite omega");
  bind_tangent_maps(cls, "rigid.SO3", size, d);
  bind_from_matrix(cls, "rigid.SO3", size, "R", d);
  cls.def_static(
         "from_quaternion",
         [](const py::object& w, const py::object& x, const py::object& y, const py::object& z) {
           // numbers (a TypeError naming the argument otherwise); the library refuses NaN
           constexpr std::string_view f = "rigid.SO3.from_quaternion";
           return SO3d::from_quaternion(cv::number(w, {f, "w"}), cv::number(x, {f, "x"}),
                                        cv::number(y, {f, "y"}), cv::number(z, {f, "z"}));
         },
         py::arg("w"), py::arg("x"), py::arg("y"), py::arg("z"),
         "The rotation of the quaternion (w, x, y, z), normalised; raises rigid.Error if it is "
         "not finite or its norm is below 1e-12.")
      .def_static(
          "from_axis_angle",
          [](const py::object& axis, const py::object& angle) {
            constexpr std::string_view f = "rigid.SO3.from_axis_angle";
            return SO3d::from_axis_angle(cv::fixed_vector<3>(axis, {f, "axis"}),
                                         cv::number(angle, {f, "angle"}));
          },
          py::arg("axis"), py::arg("angle"), d.from_axis_angle.c_str())
      .def_static(
          "sample",
          [](std::uint64_t seed, int n) {
            return draw_samples<SO3d>(seed, n,
                                      [](std::mt19937_64& rng) { return SO3d::sample(rng); });
          },
          py::arg("seed"), py::arg("n"), "n Haar-uniform rotations from a seeded std::mt19937_64");
  bind_so3_euler(cls);
  cls.def("log", &SO3d::log, d.log.c_str())
      .def("angle", &SO3d::angle, d.angle.c_str())
      .def("homogeneous", &SO3d::homogeneous, d.homogeneous.c_str())
      .def("quaternion", &SO3d::quaternion, "(w, x, y, z)")
      .def("is_approx", &SO3d::is_approx, py::arg("other"), py::arg("tol") = 1e-12,
           d.is_approx.c_str());
  bind_element_methods(cls, "rigid.SO3", d);
  def_mul_fixed<SO3d, 3>(cls, "SO3.__mul__",
                         "Composition self * other (R_AC = R_AB * R_BC; other: an SO3), or the "
                         "rotated vector R v (v_A = R_AB v_B; other: shape (3,)).");
  def_pickle_so3(cls);
  cls.def("__repr__", [](const SO3d& R) {
    return "SO3(quaternion wxyz=" + rigid::to_string(R.quaternion().transpose()) + ")";
  });
}

// SE3 binds no homogeneous (its matrix is the homogeneous one), no sample and no act_vector.
void bind_se3(py::module_& m) {
  using rigid::SE3d;
  const GroupDocs d = group_docs("SE(3)", "(rho, omega) (m, rad; translation part first)",
                                 "4×4 homogeneous matrix [[R, t], [0, 1]]", true);
  const FixedSize<6, 4> size{"xi"};
  py::class_<SE3d> cls(m, "SE3", "Rigid motion (R, t): p -> R p + t; tangent (rho, omega)");
  cls.def(py::init([](const rigid::SO3d& R, const py::object& t) {
            return SE3d(R, cv::fixed_vector<3>(t, {"rigid.SE3", "t"}));
          }),
          py::arg("R"), py::arg("t"), d.init.c_str())
      .def_static("identity", &SE3d::identity, d.identity.c_str())
      .def_static("exp", size.tangent_arg("rigid.SE3.exp", &SE3d::exp), py::arg("xi"),
                  d.exp.c_str());
  bind_tangent_maps(cls, "rigid.SE3", size, d);
  bind_from_matrix(cls, "rigid.SE3", size, "T", d);
  cls.def("log", &SE3d::log, d.log.c_str());
  bind_motion_parts(cls, d);
  bind_element_methods(cls, "rigid.SE3", d);
  def_mul_fixed<SE3d, 3>(cls, "SE3.__mul__",
                         "Composition self * other (X_AC = X_AB * X_BC; other: an SE3), or the "
                         "moved point R p + t (other: shape (3,)).");
  def_pickle_se3(cls);
  cls.def("__repr__", [](const SE3d& X) {
    return "SE3(quaternion wxyz=" + rigid::to_string(X.rotation().quaternion().transpose()) +
           ", translation=" + rigid::to_string(X.translation().transpose()) + ")";
  });
}

// check_orthogonal with its report, and nearest_rotation: matrices that may not be rotations.
void bind_orthogonality(py::module_& m) {
  py::class_<rigid::OrthogonalityReport>(
      m, "OrthogonalityReport",
      "How far a matrix M is from O(n) and SO(n): check_orthogonal(M, tol).")
      .def_readonly("defect", &rigid::OrthogonalityReport::defect, "max |MᵀM − I| (entrywise).")
      .def_readonly("determinant", &rigid::OrthogonalityReport::determinant, "det M.")
      .def_readonly("orthogonal", &rigid::OrthogonalityReport::orthogonal,
                    "True if the defect is within tol (M in O(n)).")
      .def_readonly("rotation", &rigid::OrthogonalityReport::rotation,
                    "True if also det M > 0 (M in SO(n)).")
      .def("__repr__", [](const rigid::OrthogonalityReport& r) {
        return fmt::format(
            "OrthogonalityReport(defect={}, determinant={}, orthogonal={}, rotation={})", r.defect,
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
}

}  // namespace

// The classes in the order their signatures need them: SE2 takes an SO2, SEn an SOn, SE3 an SO3.
void bind_lie(py::module_& m) {
  bind_so2(m);
  bind_se2(m);
  bind_son(m);
  bind_sen(m);
  bind_so3(m);
  bind_se3(m);
  bind_orthogonality(m);
  bind_so3_batch(m);
}
