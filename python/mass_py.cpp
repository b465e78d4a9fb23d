// Python bindings of the mass module (rigid.MassProperties, rigid.mass.*) and of the
// inertial XML writers/readers.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "pickle.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"
#include "rigid/common/wording.hpp"
#include "rigid/io/atomic_file.hpp"
#include "rigid/io/inertial_fix.hpp"
#include "rigid/io/inertial_xml.hpp"
#include "rigid/mass.hpp"
#include "rigid/mass/primitive_table.hpp"

namespace py = pybind11;
namespace cv = rigid::python::convert;

namespace {

// a placement's 3-vector (origin=, rpy=, axis=), refused by name when it is not 3 numbers
Eigen::Vector3d vector3_from_python(const py::handle& value, const char* what,
                                    const char* expected) {
  Eigen::VectorXd v;
  try {
    v = value.cast<Eigen::VectorXd>();
  } catch (const py::cast_error&) {
    v.resize(0);
  }
  if (v.size() != 3) {
    throw rigid::Error(
        fmt::format("{}= must be {}, got {}", what, expected, py::repr(value).cast<std::string>()));
  }
  return v;
}

// axis= of a placement: 'x', 'y', 'z', '-x', '-y', '-z' or a 3-vector
Eigen::Vector3d axis_from_python(const py::handle& axis) {
  if (py::isinstance<py::str>(axis)) {
    const auto s = axis.cast<std::string>();
    const bool neg = !s.empty() && s[0] == '-';
    const std::string letter = neg ? s.substr(1) : s;
    if (letter == "x" || letter == "y" || letter == "z") {
      Eigen::Vector3d v = Eigen::Vector3d::Unit(letter[0] - 'x');
      return neg ? (-v).eval() : v;
    }
    throw rigid::Error(fmt::format(
        "axis= must be 'x', 'y', 'z', '-x', '-y', '-z' or a vector (vx, vy, vz), got '{}'", s));
  }
  return vector3_from_python(axis, "axis",
                             "'x', 'y', 'z', '-x', '-y', '-z' or a vector (vx, vy, vz)");
}

namespace rm = rigid::mass;
using rigid::MassProperties;
using rigid::MassProperties2;
using rigid::SecondMoments;

// rigid.MassProperties: a 3D body's mass, COM and inertia about the COM, checked when built.
void bind_mass_properties(py::module_& m) {
  py::class_<MassProperties>(m, "MassProperties",
                             "Mass (kg), center of mass p_OC_B (m) and inertia about the COM "
                             "I_C_B (kg·m²) of a 3D body, validated when built.")
      .def(py::init([](double mass, const py::object& p_OC_B, const py::object& I_C_B) {
             const cv::Arg f{"rigid.MassProperties", ""};
             return MassProperties(mass, cv::vector3(p_OC_B, {f.function, "p_OC_B"}),
                                   cv::matrix3(I_C_B, {f.function, "I_C_B"}));
           }),
           py::arg("mass"), py::arg("p_OC_B"), py::arg("I_C_B"),
           "Validated mass properties: mass (kg), COM p_OC_B from the frame origin O in B (shape "
           "(3,), m), inertia about the COM I_C_B in B (shape (3, 3), kg·m², the physical tensor: "
           "off-diagonal −∫ρxy dV). Raises rigid.Error naming the failed condition and its margin.")
      .def_property_readonly("mass", &MassProperties::mass, "Mass (kg).")
      .def_property_readonly("com", &MassProperties::com, "Centre of mass p_OC_B (m), shape (3,).")
      .def_property_readonly("inertia_com", &MassProperties::inertia_com,
                             "Inertia about the COM expressed in B (kg·m²), shape (3, 3).")
      .def(
          "inertia_about",
          [](const MassProperties& mp, const py::object& p) {
            return mp.inertia_about(cv::vector3(p, {"MassProperties.inertia_about", "p_OQ_B"}));
          },
          py::arg("p_OQ_B"),
          "Inertia (kg·m²) about the point Q at p_OQ_B (m, in B), expressed in B: the "
          "parallel-axis theorem I_Q = I_C + m (|d|² 1 − d dᵀ), d = p_OC − p_OQ.")
      .def(
          "inertia_about_axis",
          [](const MassProperties& mp, const py::object& p, const py::object& u) {
            const char* f = "MassProperties.inertia_about_axis";
            return mp.inertia_about_axis(cv::vector3(p, {f, "p_OQ_B"}),
                                         cv::vector3(u, {f, "unit_B"}));
          },
          py::arg("p_OQ_B"), py::arg("unit_B"),
          "Moment of inertia uᵀ I_Q u (kg·m²) about the line through Q (p_OQ_B, m, in B) along "
          "the unit vector unit_B (in B; |u| within 1e-12 of 1).")
      .def(
          "shifted",
          [](const MassProperties& mp, const py::object& d) {
            return mp.shifted(cv::vector3(d, {"MassProperties.shifted", "d_B"}));
          },
          py::arg("d_B"), "The same body moved by d_B (m, in B): COM + d_B, inertia unchanged.")
      .def(
          "rotated",
          [](const MassProperties& mp, const py::object& R) {
            return mp.rotated(cv::matrix3(R, {"MassProperties.rotated", "R_AB"}));
          },
          py::arg("R_AB"),
          "The same body re-expressed in frame A (common origin): p_OC_A = R_AB p_OC_B, "
          "I_C_A = R_AB I_C_B R_ABᵀ; R_AB (3, 3) must be a rotation within 1e-9.")
      .def(
          "transformed",
          [](const MassProperties& mp, const py::object& R, const py::object& p) {
            const char* f = "MassProperties.transformed";
            return mp.transformed(cv::matrix3(R, {f, "R_AB"}), cv::vector3(p, {f, "p_AB_A"}));
          },
          py::arg("R_AB"), py::arg("p_AB_A"),
          "The same body expressed in frame A, given the pose of B in A: rotation R_AB (3, 3) "
          "and position p_AB_A (m) of B's origin in A.")
      .def(
          "principal_axes",
          [](const MassProperties& mp) {
            const auto pa = mp.principal_axes();
            return py::make_tuple(pa.moments, pa.R_BP);
          },
          "(ascending principal moments, R_BP with the principal axes as columns, det +1).")
      .def("invalidity_report", &MassProperties::invalidity_report,
           "Why these mass properties are not physical, or None (always None once built; see "
           "check).")
      .def_static(
          "check",
          [](double mass, const py::object& p, const py::object& I) {
            const char* f = "rigid.MassProperties.check";
            // NaN is reported by check itself, as a reason, not refused here
            return MassProperties::check(mass, cv::vector3(p, {f, "p_OC_B"}, cv::Finite::kAllowed),
                                         cv::matrix3(I, {f, "I_C_B"}, cv::Finite::kAllowed));
          },
          py::arg("mass"), py::arg("p_OC_B"), py::arg("I_C_B"),
          "Why (mass kg, COM p_OC_B m, inertia about the COM I_C_B kg·m²) is not a "
          "physical body, or None when it is.")
      .def(py::pickle(
          // (mass, p_OC_B, I_C_B): the constructor keeps them as they are (I_C_B is stored
          // symmetric, and the symmetric part of a symmetric matrix is itself, bit for bit)
          [](const MassProperties& mp) {
            return py::make_tuple(mp.mass(), Eigen::Vector3d(mp.com()),
                                  Eigen::Matrix3d(mp.inertia_com()));
          },
          [](const py::tuple& state) {
            constexpr std::string_view type = "rigid.MassProperties.__setstate__";
            const py::tuple t = rigid::python::pickle::state_tuple(state, type, 3);
            return MassProperties(rigid::python::pickle::state_float(t, 0, type),
                                  cv::vector3(t[1], {type, "state[1] (p_OC_B)"}),
                                  cv::matrix3(t[2], {type, "state[2] (I_C_B)"}));
          }))
      .def("__repr__", [](const MassProperties& mp) { return fmt::format("{}", mp); });
}

// rigid.combine and rigid.subtract: bodies added and removed in one frame.
void bind_combination(py::module_& m) {
  m.def(
      "combine", [](const std::vector<MassProperties>& parts) { return rigid::combine(parts); },
      py::arg("parts"), "Mass properties of the union of bodies in one frame.");
  m.def("subtract", &rigid::subtract, py::arg("whole"), py::arg("hole"),
        "The body with a hole removed; refuses non-physical results.");
}

// rigid.MassProperties2: a lamina's mass, COM and moment about the COM.
void bind_mass_properties2(py::module_& m) {
  py::class_<MassProperties2>(m, "MassProperties2", "Planar mass, COM and moment about the COM.")
      .def(py::init([](double mass, const py::object& p, double moment_com) {
             return MassProperties2(mass, cv::vector(p, {"rigid.MassProperties2", "p_OC_B"}, 2),
                                    moment_com);
           }),
           py::arg("mass"), py::arg("p_OC_B"), py::arg("moment_com"),
           "Mass (kg), COM p_OC_B (shape (2,), m) and moment about the COM (kg·m²) of a lamina.")
      .def_property_readonly("mass", &MassProperties2::mass, "Mass (kg).")
      .def_property_readonly("com", &MassProperties2::com,
                             "Center of mass p_OC_B in the plane frame B (m).")
      .def_property_readonly("moment_com", &MassProperties2::moment_com,
                             "Polar moment of inertia about the normal through the COM (kg·m²).")
      .def(
          "moment_about",
          [](const MassProperties2& mp, const py::object& p) {
            return mp.moment_about(cv::vector(p, {"MassProperties2.moment_about", "p_OQ_B"}, 2));
          },
          py::arg("p_OQ_B"), "Polar moment (kg·m²) about the point Q at p_OQ_B (shape (2,), m).")
      .def(
          "shifted",
          [](const MassProperties2& mp, const py::object& d) {
            return mp.shifted(cv::vector(d, {"MassProperties2.shifted", "d_B"}, 2));
          },
          py::arg("d_B"),
          "The same lamina moved by d_B (shape (2,), m): COM + d_B, moment unchanged.")
      .def("rotated", &MassProperties2::rotated, py::arg("angle"),
           "The same lamina with its coordinates rotated by angle (rad, counter-clockwise); the "
           "moment about the COM is unchanged.")
      .def_static(
          "combine",
          [](const MassProperties2& a, const MassProperties2& b) { return rigid::combine(a, b); },
          py::arg("a"), py::arg("b"),
          "The union of two laminae in one frame: masses add, moments are shifted to the common "
          "COM and added.")
      .def(py::pickle(
          [](const MassProperties2& mp) {
            return py::make_tuple(mp.mass(), Eigen::Vector2d(mp.com()), mp.moment_com());
          },
          [](const py::tuple& state) {
            constexpr std::string_view type = "rigid.MassProperties2.__setstate__";
            const py::tuple t = rigid::python::pickle::state_tuple(state, type, 3);
            return MassProperties2(rigid::python::pickle::state_float(t, 0, type),
                                   cv::vector(t[1], {type, "state[1] (p_OC_B)"}, 2),
                                   rigid::python::pickle::state_float(t, 2, type));
          }))
      .def("__repr__", [](const MassProperties2& mp) { return fmt::format("{}", mp); });
}

// rigid.SecondMoments: an n-D body's mass, COM and second-moment matrix.
void bind_second_moments(py::module_& m) {
  py::class_<SecondMoments>(m, "SecondMoments",
                            "n-D mass, COM and second-moment matrix J about the COM.")
      .def(py::init([](double mass, const py::object& com, const py::object& J) {
             const char* f = "rigid.SecondMoments";
             const Eigen::VectorXd c = cv::vector(com, {f, "com"});
             return rigid::SecondMoments(mass, c, cv::matrix(J, {f, "J_com"}, c.size(), c.size()));
           }),
           py::arg("mass"), py::arg("com"), py::arg("J_com"),
           "Mass (kg), COM (shape (n,), m) and second-moment matrix J = ∫ρ r rᵀ about the COM "
           "(shape (n, n), kg·m²) of an n-dimensional body.")
      .def_property_readonly("mass", &SecondMoments::mass, "Mass (kg).")
      .def_property_readonly("com", &SecondMoments::com, "Center of mass in the body frame (m).")
      .def_property_readonly("J_com", &SecondMoments::J_com,
                             "Second-moment matrix ∫ρ r rᵀ dV about the COM (kg·m²).")
      .def_property_readonly("dimension", &SecondMoments::dimension,
                             "n, the dimension of the space.")
      .def(
          "J_about",
          [](const SecondMoments& J, const py::object& q) {
            return J.J_about(cv::vector(q, {"SecondMoments.J_about", "q"}, J.dimension()));
          },
          py::arg("q"),
          "Second moments about the point q (shape (n,), m): J_C + m d dᵀ, d = c − q.")
      .def(
          "apply",
          [](const SecondMoments& J, const py::object& Omega) {
            return J.apply(
                cv::matrix(Omega, {"SecondMoments.apply", "Omega"}, J.dimension(), J.dimension()));
          },
          py::arg("Omega"),
          "Body angular momentum M = J Ω + Ω J (kg·m²/s) of the angular velocity Ω ∈ so(n) "
          "(n × n skew, rad/s).")
      .def("to_mass_properties", &SecondMoments::to_mass_properties,
           "The 3D MassProperties (I = tr(J) 1 − J); raises rigid.Error unless n = 3.")
      .def_static("from_mass_properties", &SecondMoments::from_mass_properties, py::arg("mp"),
                  "The second moments of 3D mass properties: J = ½ tr(I) 1 − I.")
      .def(py::pickle(
          // (mass, com, J_com): J_com is stored symmetric, which the constructor keeps exactly
          [](const SecondMoments& J) {
            return py::make_tuple(J.mass(), Eigen::VectorXd(J.com()), Eigen::MatrixXd(J.J_com()));
          },
          [](const py::tuple& state) {
            constexpr std::string_view type = "rigid.SecondMoments.__setstate__";
            const py::tuple t = rigid::python::pickle::state_tuple(state, type, 3);
            const Eigen::VectorXd c = cv::vector(t[1], {type, "state[1] (com)"});
            return SecondMoments(rigid::python::pickle::state_float(t, 0, type), c,
                                 cv::matrix(t[2], {type, "state[2] (J_com)"}, c.size(), c.size()));
          }))
      .def("__repr__", [](const SecondMoments& s) {
        return fmt::format("SecondMoments(n={}, mass={} kg, com={} m, J_com={} kg·m²)",
                           s.dimension(), s.mass(), rigid::to_string(s.com().transpose()),
                           rigid::to_string(s.J_com()));
      });
}

// rigid.mass.<shape>_with_mass(m, sizes...) and rigid.mass.<shape>_with_density(rho, sizes...)
// of a closed-form primitive; the sizes are named by `sizes` (m). The docstrings are short: the
// frames and formulas of every primitive are in docs/mass.md.
template <class WithMass, class WithDensity, class... Sizes>
void def_with_mass_and_density(py::module_& mass, const std::string& shape, WithMass with_mass,
                               WithDensity with_density, const Sizes&... sizes) {
  mass.def(
      (shape + "_with_mass").c_str(), with_mass, py::arg("m"), py::arg(sizes)...,
      fmt::format("Uniform {} of mass m (kg); sizes in m (frame and formula: docs/mass.md).", shape)
          .c_str());
  mass.def((shape + "_with_density").c_str(), with_density, py::arg("rho"), py::arg(sizes)...,
           fmt::format("Uniform {} of density rho (kg/m³, kg/m² for shells/plates/laminae, kg/m "
                       "for the rod); sizes in m.",
                       shape)
               .c_str());
}

// The closed-form primitives given by their sizes, each by mass and by density.
void bind_sized_primitives(py::module_& mass) {
  def_with_mass_and_density(mass, "solid_sphere", &rm::solid_sphere_with_mass,
                            &rm::solid_sphere_with_density, "r");
  def_with_mass_and_density(mass, "thick_spherical_shell", &rm::thick_spherical_shell_with_mass,
                            &rm::thick_spherical_shell_with_density, "r_inner", "r_outer");
  def_with_mass_and_density(mass, "thin_spherical_shell", &rm::thin_spherical_shell_with_mass,
                            &rm::thin_spherical_shell_with_density, "r");
  def_with_mass_and_density(mass, "solid_ellipsoid", &rm::solid_ellipsoid_with_mass,
                            &rm::solid_ellipsoid_with_density, "a", "b", "c");
  def_with_mass_and_density(mass, "solid_box", &rm::solid_box_with_mass,
                            &rm::solid_box_with_density, "lx", "ly", "lz");
  def_with_mass_and_density(mass, "solid_cylinder", &rm::solid_cylinder_with_mass,
                            &rm::solid_cylinder_with_density, "r", "h");
  def_with_mass_and_density(mass, "thick_tube", &rm::thick_tube_with_mass,
                            &rm::thick_tube_with_density, "r_inner", "r_outer", "h");
  def_with_mass_and_density(mass, "thin_cylindrical_shell", &rm::thin_cylindrical_shell_with_mass,
                            &rm::thin_cylindrical_shell_with_density, "r", "h");
  def_with_mass_and_density(mass, "capped_cylindrical_shell",
                            &rm::capped_cylindrical_shell_with_mass,
                            &rm::capped_cylindrical_shell_with_density, "r", "h");
  def_with_mass_and_density(mass, "solid_cone", &rm::solid_cone_with_mass,
                            &rm::solid_cone_with_density, "r", "h");
  def_with_mass_and_density(mass, "solid_frustum", &rm::solid_frustum_with_mass,
                            &rm::solid_frustum_with_density, "r_bottom", "r_top", "h");
  def_with_mass_and_density(mass, "solid_capsule", &rm::solid_capsule_with_mass,
                            &rm::solid_capsule_with_density, "r", "l");
  def_with_mass_and_density(mass, "solid_torus", &rm::solid_torus_with_mass,
                            &rm::solid_torus_with_density, "R", "a");
  def_with_mass_and_density(mass, "thin_rod", &rm::thin_rod_with_mass, &rm::thin_rod_with_density,
                            "l");
  def_with_mass_and_density(mass, "thin_rectangular_plate", &rm::thin_rectangular_plate_with_mass,
                            &rm::thin_rectangular_plate_with_density, "lx", "ly");
  def_with_mass_and_density(mass, "thin_disk", &rm::thin_disk_with_mass,
                            &rm::thin_disk_with_density, "r");
  def_with_mass_and_density(mass, "thin_ring", &rm::thin_ring_with_mass,
                            &rm::thin_ring_with_density, "r");
  def_with_mass_and_density(mass, "disk_lamina", &rm::disk_lamina_with_mass,
                            &rm::disk_lamina_with_density, "r");
  def_with_mass_and_density(mass, "annulus_lamina", &rm::annulus_lamina_with_mass,
                            &rm::annulus_lamina_with_density, "r_inner", "r_outer");
  def_with_mass_and_density(mass, "rectangle_lamina", &rm::rectangle_lamina_with_mass,
                            &rm::rectangle_lamina_with_density, "lx", "ly");
}

// The primitives given by their vertices (solid tetrahedron, polygonal lamina), each by mass
// and by density.
void bind_vertex_primitives(py::module_& mass) {
  for (const bool with_mass : {true, false}) {
    const std::string name =
        with_mass ? "solid_tetrahedron_with_mass" : "solid_tetrahedron_with_density";
    mass.def(
        name.c_str(),
        [with_mass, name](double amount, const py::object& v0, const py::object& v1,
                          const py::object& v2, const py::object& v3) {
          const std::string f = "rigid.mass." + name;
          const Eigen::Vector3d a = cv::vector3(v0, {f, "v0"}), b = cv::vector3(v1, {f, "v1"}),
                                c = cv::vector3(v2, {f, "v2"}), d = cv::vector3(v3, {f, "v3"});
          return with_mass ? rm::solid_tetrahedron_with_mass(amount, a, b, c, d)
                           : rm::solid_tetrahedron_with_density(amount, a, b, c, d);
        },
        py::arg(with_mass ? "m" : "rho"), py::arg("v0"), py::arg("v1"), py::arg("v2"),
        py::arg("v3"),
        with_mass
            ? "Uniform solid tetrahedron of mass m (kg) with vertices v0..v3 (each shape (3,), m), "
              "in the vertices' frame (frame and formula: docs/mass.md)."
            : "Uniform solid tetrahedron of density rho (kg/m³) with vertices v0..v3 (each shape "
              "(3,), m), in the vertices' frame.");
    const std::string polygon =
        with_mass ? "polygon_lamina_with_mass" : "polygon_lamina_with_density";
    mass.def(
        polygon.c_str(),
        [with_mass, polygon](double amount, const py::object& vertices) {
          const Eigen::Matrix2Xd v = cv::points(vertices, {"rigid.mass." + polygon, "vertices"}, 2);
          return with_mass ? rm::polygon_lamina_with_mass(amount, v)
                           : rm::polygon_lamina_with_density(amount, v);
        },
        py::arg(with_mass ? "m" : "sigma"), py::arg("vertices"),
        with_mass
            ? "Uniform polygonal lamina of mass m (kg); vertices shape (n, 2) in m, one per row, "
              "in order around a simple polygon; in the vertices' plane frame."
            : "Uniform polygonal lamina of areal density sigma (kg/m²); vertices shape (n, 2) in "
              "m, "
              "one per row, in order around a simple polygon.");
  }
}

// The keyword arguments of a catalogue factory: mass= or density=, the sizes and points by
// name, and the placement axis=, origin=, rpy=.
struct PrimitiveCall {
  rm::Amount amount;
  double value;
  rm::PrimitiveArguments args;
  rm::Placement placement;
};

PrimitiveCall parse_primitive_call(const std::string& name, const py::kwargs& kwargs) {
  const rm::PrimitiveEntry& e = rm::find_primitive(name);
  std::optional<double> amount_mass, amount_density;
  PrimitiveCall call{rm::Amount::kMass, 0.0, {}, {}};
  for (auto item : kwargs) {
    const auto key = item.first.cast<std::string>();
    if (key == "axis") {
      call.placement.axis = axis_from_python(item.second);
    } else if (key == "origin") {
      call.placement.origin = vector3_from_python(item.second, "origin", "a point (x, y, z) in m");
    } else if (key == "rpy") {
      call.placement.rpy = vector3_from_python(item.second, "rpy", "(roll, pitch, yaw) in rad");
    } else if (key == "mass") {
      amount_mass = cv::number(item.second, {"rigid.mass." + name, key});
    } else if (key == "density") {
      amount_density = cv::number(item.second, {"rigid.mass." + name, key});
    } else if (e.point_index(key)) {
      call.args.points.emplace_back(key, cv::vector3(item.second, {"rigid.mass." + name, key}));
    } else {
      call.args.sizes.emplace_back(key, cv::number(item.second, {"rigid.mass." + name, key}));
    }
  }
  if (amount_mass.has_value() == amount_density.has_value()) {
    throw rigid::Error(
        fmt::format("rigid.mass.{}(): give exactly one of mass= (kg) and density= ({}), got {}",
                    name, e.density_unit, amount_mass ? "both" : "neither"));
  }
  call.amount = amount_mass ? rm::Amount::kMass : rm::Amount::kDensity;
  call.value = amount_mass ? *amount_mass : *amount_density;
  return call;
}

// The catalogue's primitive `name` from the keyword arguments, placed.
MassProperties make_primitive_from_kwargs(const std::string& name, const py::kwargs& kwargs) {
  const PrimitiveCall c = parse_primitive_call(name, kwargs);
  return rm::place(rm::make_primitive(name, c.amount, c.value, c.args), c.placement);
}

// The inertia tensor (kg·m²) of the 10 values (m, c, I) an uncertainty propagation carries:
// I_xx, I_yy, I_zz at 4..6, then I_xy, I_xz, I_yz at 7..9.
Eigen::Matrix3d inertia_of(const Eigen::Matrix<double, 10, 1>& y) {
  Eigen::Matrix3d I;
  I << y(4), y(7), y(8), y(7), y(5), y(9), y(8), y(9), y(6);
  return I;
}

// rigid.mass.primitive_uncertainty: the values and their 1σ as dicts, and the inputs.
py::dict primitive_uncertainty_dict(const std::string& name, const std::string& tolerance,
                                    const py::object& about, const py::kwargs& kwargs) {
  const PrimitiveCall c = parse_primitive_call(name, kwargs);
  std::optional<Eigen::Vector3d> point;
  if (!about.is_none())
    point = vector3_from_python(about, "about", "a point (x, y, z) in m, or None for the COM");
  const auto u = rm::primitive_uncertainty(name, c.amount, c.value, c.args, c.placement,
                                           rm::parse_tolerances(tolerance), point);
  py::dict d;
  d["mass"] = u.value(0);
  d["com"] = Eigen::Vector3d(u.value.segment<3>(1));
  d["inertia"] = inertia_of(u.value);
  py::dict sigma;
  sigma["mass"] = u.sigma(0);
  sigma["com"] = Eigen::Vector3d(u.sigma.segment<3>(1));
  sigma["inertia"] = inertia_of(u.sigma);
  d["sigma"] = sigma;
  d["inputs"] = u.inputs;
  return d;
}

void bind_primitive_uncertainty(py::module_& mass) {
  mass.def(
      "primitive_uncertainty", &primitive_uncertainty_dict, py::arg("name"), py::arg("tolerance"),
      py::arg("about") = py::none(),
      "Mass, COM and inertia (about `about`, the COM when None) of a catalogue primitive with "
      "their 1σ, first-order propagation of independent inputs: primitive_uncertainty('cylinder', "
      "'dims=±0.1mm,density=±2%', density=2700, radius=0.05, height=0.4). Takes the factories' "
      "keywords (axis=, origin=, rpy= too); ± is one standard deviation.");
}

// rigid.mass.place and rigid.mass.placement_rotation: a shape's own frame placed in a link.
void bind_placement(py::module_& mass) {
  mass.def(
      "place",
      [](const MassProperties& body, const py::object& axis, const py::object& origin,
         const py::object& rpy) {
        return rm::place(
            body, rm::Placement{.axis = axis_from_python(axis),
                                .rpy = cv::vector3(rpy, {"rigid.mass.place", "rpy"}),
                                .origin = cv::vector3(origin, {"rigid.mass.place", "origin"})});
      },
      py::arg("body"), py::arg("axis") = "z", py::arg("origin") = py::make_tuple(0.0, 0.0, 0.0),
      py::arg("rpy") = py::make_tuple(0.0, 0.0, 0.0),
      "The body (given in a shape's own frame) placed in the link frame: its z axis turned along "
      "axis ('x', 'y', 'z', '-x', '-y', '-z' or a vector), then rotated by rpy (rad, URDF: "
      "Rz(yaw) Ry(pitch) Rx(roll)), then its origin moved to origin (m). Every catalogue "
      "factory takes the same axis=, origin=, rpy=.");
  mass.def(
      "placement_rotation",
      [](const py::object& axis, const py::object& rpy) {
        return rm::placement_rotation(
            rm::Placement{.axis = axis_from_python(axis),
                          .rpy = cv::vector3(rpy, {"rigid.mass.placement_rotation", "rpy"}),
                          .origin = Eigen::Vector3d::Zero()});
      },
      py::arg("axis") = "z", py::arg("rpy") = py::make_tuple(0.0, 0.0, 0.0),
      "R_LS of a placement: Rz(yaw) Ry(pitch) Rx(roll) · (shortest rotation from z to axis).");
}

// The docstring of a catalogue factory: its sizes and vertices with their units, its aliases.
std::string catalogue_doc(const rm::PrimitiveEntry& e) {
  std::string doc =
      fmt::format("{} in its own frame: {}(mass= or density=, ", e.description, e.name);
  std::vector<std::string> args;
  for (const auto& sz : e.sizes)
    args.push_back(fmt::format("{}= ({}, {})", sz.name, sz.help, sz.unit));
  for (const auto& pt : e.points)
    args.push_back(fmt::format("{}= ({} as (x, y, z), m)", pt.name, pt.help));
  doc += fmt::format("{}). Density in {}.", fmt::join(args, ", "), e.density_unit);
  if (!e.aliases.empty()) doc += fmt::format(" Also called: {}.", fmt::join(e.aliases, ", "));
  return doc;
}

// The primitive catalogue as Python data: a dict per shape.
py::list primitive_catalogue() {
  py::list out;
  for (const rm::PrimitiveEntry& e : rm::primitive_table()) {
    py::dict d;
    d["name"] = e.name;
    d["aliases"] = e.aliases;
    d["description"] = e.description;
    py::list sizes;
    for (const auto& sz : e.sizes) {
      py::dict z;
      z["name"] = sz.name;
      z["help"] = sz.help;
      z["unit"] = sz.unit;
      z["aliases"] = sz.aliases;
      sizes.append(z);
    }
    d["sizes"] = sizes;
    py::list points;
    for (const auto& pt : e.points) points.append(pt.name);
    d["points"] = points;
    d["density_unit"] = e.density_unit;
    out.append(d);
  }
  return out;
}

// The primitive catalogue: rigid.mass.primitive(name, ...), one factory per name and alias
// (rigid.mass.solid_cylinder, rigid.mass.cylinder, ...) taking mass= or density= and the sizes
// by name, and rigid.mass.primitives() listing them.
void bind_primitive_catalogue(py::module_& mass) {
  mass.def("primitive", &make_primitive_from_kwargs, py::arg("name"),
           "Mass properties of the catalogue's primitive `name` (any name or alias, as in scene "
           "files and "
           "`rigid inertia`): primitive('cylinder', mass=2.0, radius=0.1, height=0.5). Sizes in m, "
           "mass in kg or density in kg/m³ (kg/m² shells and plates, kg/m rods); vertices as (x, "
           "y, z).");
  for (const rm::PrimitiveEntry& e : rm::primitive_table()) {
    const std::string doc = catalogue_doc(e);
    for (const std::string& n : e.names()) {
      mass.def(
          n.c_str(),
          [n](const py::kwargs& kwargs) { return make_primitive_from_kwargs(n, kwargs); },
          doc.c_str());
    }
  }
  mass.def("primitives", &primitive_catalogue,
           "The primitive catalogue: every shape with its name, aliases, sizes (name, help, unit, "
           "aliases), vertices and density unit.");
}

// rigid.mass.n_ball_* and rigid.mass.n_box_*: uniform bodies in n dimensions.
void bind_n_dimensional_bodies(py::module_& mass) {
  mass.def("n_ball_with_mass", &rm::n_ball_with_mass, py::arg("m"), py::arg("r"), py::arg("n"),
           "Uniform n-ball of mass m (kg) and radius r (m) in n ≥ 1 dimensions, centred: "
           "J = m r²/(n + 2) · 1 (kg·m²).");
  mass.def("n_ball_with_density", &rm::n_ball_with_density, py::arg("rho"), py::arg("r"),
           py::arg("n"),
           "Uniform n-ball of density rho (kg/mⁿ) and radius r (m) in n ≥ 1 dimensions, centred; "
           "volume π^{n/2} rⁿ / Γ(n/2 + 1).");
  mass.def(
      "n_box_with_mass",
      [](double m_kg, const py::object& sizes) {
        return rm::n_box_with_mass(m_kg,
                                   cv::vector(sizes, {"rigid.mass.n_box_with_mass", "sizes"}));
      },
      py::arg("m"), py::arg("sizes"),
      "Uniform n-box of mass m (kg) with edge lengths `sizes` (shape (n,), m), centred: "
      "J = m diag(l_i²/12).");
  mass.def(
      "n_box_with_density",
      [](double rho, const py::object& sizes) {
        return rm::n_box_with_density(
            rho, cv::vector(sizes, {"rigid.mass.n_box_with_density", "sizes"}));
      },
      py::arg("rho"), py::arg("sizes"),
      "Uniform n-box of density rho (kg/mⁿ) with edge lengths `sizes` (shape (n,), m), centred.");
}

// Refuses masses and points whose counts differ: one mass per point (row).
void require_one_mass_per_point(const char* function, std::size_t masses, Eigen::Index points) {
  if (static_cast<Eigen::Index>(masses) != points) {
    throw rigid::Error(
        fmt::format("{}(): {} masses and {} points; expected one mass per point (row)", function,
                    masses, points));
  }
}

// Point masses (3D and n-D) and the moments of a polygon.
void bind_point_masses(py::module_& mass) {
  mass.def(
      "point_mass",
      [](double m_kg, const py::object& p) {
        return rm::point_mass(m_kg, cv::vector3(p, {"rigid.mass.point_mass", "p"}));
      },
      py::arg("m"), py::arg("p"),
      "A point mass m (kg) at p (shape (3,), m): COM p, zero inertia about it.");
  mass.def(
      "point_masses",
      [](const py::object& masses, const py::object& points) {
        const char* f = "rigid.mass.point_masses";
        const std::vector<double> mk = cv::values(masses, {f, "masses"});
        const Eigen::Matrix3Xd p = cv::points(points, {f, "points"});
        require_one_mass_per_point(f, mk.size(), p.cols());
        return rm::point_masses(mk, p);
      },
      py::arg("masses"), py::arg("points"),
      "Point masses masses[i] (kg, shape (n,)) at points[i] (shape (n, 3), m, one point per row), "
      "combined into one body in the points' frame.");

  mass.def(
      "point_set_second_moments",
      [](const py::object& masses, const py::object& points) {
        const char* f = "rigid.mass.point_set_second_moments";
        const std::vector<double> mk = cv::values(masses, {f, "masses"});
        const py::array shape_of = py::module_::import("numpy").attr("asarray")(points);
        const Eigen::Index d = shape_of.ndim() == 2 ? shape_of.shape(1) : 3;
        const Eigen::MatrixXd p = cv::points(points, {f, "points"}, d);
        require_one_mass_per_point(f, mk.size(), p.cols());
        return rm::point_set_second_moments(mk, p);
      },
      py::arg("masses"), py::arg("points"),
      "n-D second moments (rigid.SecondMoments) of point masses masses[i] (kg, shape (k,)) at "
      "points[i] (shape (k, n), m, one point per row): J_C = Σ m (p − c)(p − c)ᵀ about the COM c.");
  mass.def(
      "polygon_moments",
      [](const py::object& vertices) {
        const auto pm = rm::polygon_moments(
            cv::points(vertices, {"rigid.mass.polygon_moments", "vertices"}, 2));
        return py::make_tuple(pm.area, pm.centroid, pm.J_C);
      },
      py::arg("vertices"),
      "(area m², centroid (2,) m, J_C (2, 2) m⁴ per unit areal density) of a simple polygon, "
      "vertices shape (n, 2) in order (either direction).");
}

// rigid.mass.check_rotational_moments: the dynamics' check of principal moments.
void bind_moment_check(py::module_& mass) {
  mass.def(
      "check_rotational_moments",
      [](const py::object& moments) {
        return rigid::check_rotational_moments(cv::vector3(
            moments, {"rigid.mass.check_rotational_moments", "moments"}, cv::Finite::kAllowed));
      },
      py::arg("moments"),
      "Why principal moments (kg·m², shape (3,), any order) cannot be those of a body that "
      "turns (not finite, negative, I_i > I_j + I_k, or a zero moment), or None: the check the "
      "dynamics (rigid.body, rigid.spring) make.");
}

// rigid.mass.DensityIntegration and rigid.mass.integrate_density_over_*: a variable density
// integrated by adaptive cubature.
void bind_density_cubature(py::module_& mass) {
  py::class_<rm::DensityIntegration>(
      mass, "DensityIntegration",
      "Mass properties of a variable density by adaptive cubature, with error bounds.")
      .def_readonly("mass_properties", &rm::DensityIntegration::mass_properties,
                    "The integrated rigid.MassProperties (in the shape's frame, centred).")
      .def_readonly("mass_error", &rm::DensityIntegration::mass_error,
                    "Error bound on the mass (kg).")
      .def_readonly("com_error", &rm::DensityIntegration::com_error,
                    "Error bound on every COM component (m).")
      .def_readonly("inertia_error", &rm::DensityIntegration::inertia_error,
                    "Error bound on every element of the inertia about the COM (kg·m²).")
      .def_readonly("cells", &rm::DensityIntegration::cells, "Cells used.")
      .def_readonly("converged", &rm::DensityIntegration::converged,
                    "False if max_cells was reached before the relative tolerance.")
      .def("__repr__", [](const rm::DensityIntegration& d) {
        return fmt::format(
            "DensityIntegration(mass_properties={}, mass_error={} kg, com_error={} m, "
            "inertia_error={} kg·m², cells={}, converged={})",
            d.mass_properties, d.mass_error, d.com_error, d.inertia_error, d.cells,
            d.converged ? "True" : "False");
      });
  auto opts = [](double tol, int cells) {
    return rm::CubatureOptions{.relative_tolerance = tol, .max_cells = cells};
  };
  mass.def(
      "integrate_density_over_box",
      [opts](const rm::DensityFunction& rho, double lx, double ly, double lz, double tol,
             int cells) {
        return rm::integrate_density_over_box(rho, lx, ly, lz, opts(tol, cells));
      },
      py::arg("rho"), py::arg("lx"), py::arg("ly"), py::arg("lz"),
      py::arg("relative_tolerance") = 1e-10, py::arg("max_cells") = 2000,
      "Mass properties of the density rho(p) (kg/m³; p a point in m, the box's frame) over the box "
      "[-lx/2, lx/2] × [-ly/2, ly/2] × [-lz/2, lz/2] (m), by adaptive cubature: a "
      "DensityIntegration.");
  mass.def(
      "integrate_density_over_cylinder",
      [opts](const rm::DensityFunction& rho, double r, double h, double tol, int cells) {
        return rm::integrate_density_over_cylinder(rho, r, h, opts(tol, cells));
      },
      py::arg("rho"), py::arg("r"), py::arg("h"), py::arg("relative_tolerance") = 1e-10,
      py::arg("max_cells") = 2000,
      "Mass properties of the density rho(p) (kg/m³) over the cylinder of radius r and height h "
      "(m), "
      "axis z, centred at the origin, by adaptive cubature: a DensityIntegration.");
  mass.def(
      "integrate_density_over_sphere",
      [opts](const rm::DensityFunction& rho, double r, double tol, int cells) {
        return rm::integrate_density_over_sphere(rho, r, opts(tol, cells));
      },
      py::arg("rho"), py::arg("r"), py::arg("relative_tolerance") = 1e-10,
      py::arg("max_cells") = 2000,
      "Mass properties of the density rho(p) (kg/m³) over the ball of radius r (m) centred at the "
      "origin, by adaptive cubature: a DensityIntegration.");
}

// The format= of an inertial document: 'urdf', 'mjcf' or 'sdf'.
rigid::io::InertialFormat parse_inertial_format(const std::string& f) {
  for (auto k : {rigid::io::InertialFormat::urdf, rigid::io::InertialFormat::mjcf,
                 rigid::io::InertialFormat::sdf}) {
    if (f == rigid::io::to_string(k)) return k;
  }
  throw rigid::Error(fmt::format("format must be 'urdf', 'mjcf' or 'sdf', got '{}'", f));
}

// rigid.mass.write_inertial_document: one inertial as a URDF/MJCF/SDF document.
void bind_inertial_writer(py::module_& mass) {
  mass.def(
      "write_inertial_document",
      [](const MassProperties& mp, const std::string& format, const std::string& name,
         bool principal, const py::object& inertial_frame) {
        std::optional<Eigen::Matrix3d> frame;
        if (!inertial_frame.is_none()) {
          frame =
              cv::matrix3(inertial_frame, {"rigid.mass.write_inertial_document", "inertial_frame"});
        }
        return rigid::io::write_inertial_document(mp, parse_inertial_format(format),
                                                  {.name = name, .principal = principal}, frame);
      },
      py::arg("mp"), py::arg("format"), py::arg("name") = "body", py::arg("principal") = false,
      py::arg("inertial_frame") = py::none(),
      "A minimal URDF/MJCF/SDF document holding one inertial; with principal=True, "
      "inertial_frame=R_LI (e.g. placement_rotation(axis, rpy)) writes that frame exactly.");
}

// The pseudo-inertia and log-Cholesky parameters of a body ([Wensing2017], [Rucker2022]).
void bind_inertial_parameters(py::module_& mass) {
  mass.def(
      "pseudo_inertia", &rm::pseudo_inertia, py::arg("mp"),
      "The 4×4 pseudo-inertia J = [[Σ, h], [hᵀ, m]] about the frame origin: Σ = ½ tr(I_O) 1 − I_O, "
      "h = m c [Wensing2017].");
  mass.def(
      "from_pseudo_inertia",
      [](const py::object& J) {
        return rm::from_pseudo_inertia(
            cv::matrix(J, {"rigid.mass.from_pseudo_inertia", "J"}, 4, 4));
      },
      py::arg("J"),
      "The body of a pseudo-inertia J; raises rigid.Error naming the failed condition (mass, "
      "triangle inequality) when J is not positive semidefinite.");
  mass.def(
      "log_cholesky", &rm::log_cholesky, py::arg("mp"),
      "The 10 log-Cholesky parameters (alpha, d1, d2, d3, s12, s23, s13, t1, t2, t3) of the body "
      "about the frame origin [Rucker2022]; J = U Uᵀ, m = exp(2 alpha).");
  mass.def(
      "from_log_cholesky",
      [](const py::object& theta) {
        return rm::from_log_cholesky(
            cv::vector(theta, {"rigid.mass.from_log_cholesky", "theta"}, 10));
      },
      py::arg("theta"),
      "The body of 10 log-Cholesky parameters (any finite vector is a physical body).");
  mass.def(
      "pseudo_inertia_from_log_cholesky",
      [](const py::object& theta) {
        return rm::pseudo_inertia_from_log_cholesky(
            cv::vector(theta, {"rigid.mass.pseudo_inertia_from_log_cholesky", "theta"}, 10));
      },
      py::arg("theta"), "J = U Uᵀ of 10 log-Cholesky parameters.");
}

// rigid.mass.read_inertials: every inertial of a document (a file, or text=) as dicts.
py::list read_inertials_as_dicts(const py::object& path, const py::object& text,
                                 const std::optional<std::string>& source) {
  const char* f = "rigid.mass.read_inertials";
  std::vector<rigid::io::InertialEntry> entries;
  if (path.is_none() == text.is_none()) {
    throw rigid::Error(
        fmt::format("{}(): give exactly one of path (a file) and text= (the XML "
                    "itself), got {}",
                    f, path.is_none() ? "neither" : "both"));
  }
  if (!path.is_none()) {
    const std::string file = cv::path(path, {f, "path"});
    // a str is a file name, never XML: a document passed as the path is refused with the remedy
    if (!cv::is_file(file)) {
      const bool looks_like_xml = file.find('<') != std::string::npos;
      std::error_code ec;
      throw rigid::Error(fmt::format(
          "{}(): {}", f,
          looks_like_xml
              ? std::string("the path looks like XML text: pass a document as "
                            "read_inertials(text=...)")
              : fmt::format("'{}' is not a file{}", cv::shown(file),
                            std::filesystem::exists(file, ec) ? "" : " (no such file)")));
    }
    if (source) {
      throw rigid::Error(
          fmt::format("{}(): source= names a document given as text=; a file's "
                      "messages name the file",
                      f));
    }
    entries = rigid::io::read_inertials_file(file);
  } else {
    entries = rigid::io::read_inertials(text.cast<std::string>(), source.value_or("<string>"));
  }
  py::list out;
  for (const auto& e : entries) {
    py::dict d;
    d["name"] = e.name;
    d["line"] = e.line;
    d["mass"] = e.mass;
    d["com"] = e.com;
    d["inertia_com"] = e.inertia_com;
    d["problem"] = e.problem;
    out.append(d);
  }
  return out;
}

// rigid.mass.fix_inertials: the report of the inertials recomputed from the geometry, as a dict
// with the rewritten document as 'text'; written to `output_arg` when given.
py::dict fix_inertials_report(const py::object& path_arg, const py::object& output_arg,
                              std::optional<double> density, bool keep_mass,
                              const std::string& geometry, const std::vector<std::string>& only,
                              const py::object& package_path) {
  const std::string path = cv::path(path_arg, {"rigid.mass.fix_inertials", "path"});
  std::optional<std::string> output;
  if (!output_arg.is_none()) output = cv::path(output_arg, {"rigid.mass.fix_inertials", "output"});
  rigid::io::InertialFixOptions options;
  options.density = density;
  options.keep_mass = keep_mass;
  if (geometry != "collision" && geometry != "visual") {
    throw rigid::Error(fmt::format("geometry must be 'collision' or 'visual', got '{}'", geometry));
  }
  options.from = geometry == "visual" ? rigid::io::GeometrySource::kVisual
                                      : rigid::io::GeometrySource::kCollision;
  options.only = only;
  // "NAME=DIR" or a list of them, as the command line's --package-path
  if (py::isinstance<py::str>(package_path)) {
    options.package_paths.push_back(
        rigid::io::parse_package_path(package_path.cast<std::string>()));
  } else if (!package_path.is_none()) {
    for (const auto& p : package_path) {
      options.package_paths.push_back(rigid::io::parse_package_path(p.cast<std::string>()));
    }
  }
  const auto result = cv::reading("rigid.mass.fix_inertials", path,
                                  [&] { return rigid::io::fix_inertials_file(path, options); });
  // the report is the command line's JSON table, as a dict
  py::dict report = py::module_::import("json").attr("loads")(
      rigid::word_for(rigid::Surface::kPython, rigid::io::fix_table_json(result)));
  result.require_ok();
  if (output) rigid::io::write_file_atomically(*output, result.text);
  report["text"] = result.text;
  return report;
}

// Inertials of URDF/MJCF/SDF documents read, and recomputed from the geometry.
void bind_inertial_readers(py::module_& mass) {
  mass.def(
      "read_inertials", &read_inertials_as_dicts, py::arg("path") = py::none(), py::kw_only(),
      py::arg("text") = py::none(), py::arg("source") = py::none(),
      "Every inertial of a URDF/MJCF/SDF document, in document order, as dicts: name, line, mass "
      "(kg), com (m), inertia_com (kg·m², about the COM), all in the link/body frame (the "
      "inertial's own rotation applied), and problem (why it is not physical, or None). "
      "read_inertials(path) reads a file (a str or pathlib.Path; messages start with its name); "
      "read_inertials(text=xml) parses a document in memory (messages name `source`, default "
      "'<string>'). A str is always a path, never XML.");
  mass.def("fix_inertials", &fix_inertials_report, py::arg("path"), py::arg("output") = py::none(),
           py::arg("density") = std::nullopt, py::arg("keep_mass") = false,
           py::arg("geometry") = "collision", py::arg("only") = std::vector<std::string>{},
           py::arg("package_path") = py::none(),
           "Recompute the inertials of a URDF/SDF/MJCF model from its geometry (as `rigid inertia "
           "fix`): the report of old vs new per link, with the rewritten document as 'text'; "
           "writes it to `output` when given. Raises rigid.Error (and writes nothing) if a link "
           "cannot be fixed.");
}

}  // namespace

// The order of registration is kept: the catalogue's factories (any name or alias) come after
// the named primitives and before the n-D bodies, so a shared name would overload the same way.
void bind_mass(py::module_& m) {
  bind_mass_properties(m);
  bind_combination(m);
  bind_mass_properties2(m);
  bind_second_moments(m);

  auto mass = m.def_submodule("mass", "Primitive bodies, laminae, n-D bodies, density cubature.");
  bind_sized_primitives(mass);
  bind_vertex_primitives(mass);
  bind_primitive_uncertainty(mass);
  bind_placement(mass);
  bind_primitive_catalogue(mass);
  bind_n_dimensional_bodies(mass);
  bind_point_masses(mass);
  bind_moment_check(mass);
  bind_density_cubature(mass);
  bind_inertial_writer(mass);
  bind_inertial_parameters(mass);
  bind_inertial_readers(mass);
}
