// Python bindings of the mass module (rigid.MassProperties, rigid.mass.*) and of the
// inertial XML writers/readers.
#include <optional>
#include <string>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"
#include "rigid/common/wording.hpp"
#include "rigid/io/atomic_file.hpp"
#include "rigid/io/inertial_fix.hpp"
#include "rigid/io/inertial_xml.hpp"
#include "rigid/mass.hpp"
#include "rigid/mass/primitive_table.hpp"

namespace py = pybind11;

namespace {

// a placement's 3-vector (origin=, rpy=, axis=), refused by name when it is not 3 numbers
Eigen::Vector3d vector3_from_python(const py::handle& value, const char* what, const char* expected) {
  Eigen::VectorXd v;
  try {
    v = value.cast<Eigen::VectorXd>();
  } catch (const py::cast_error&) {
    v.resize(0);
  }
  if (v.size() != 3) {
    throw rigid::Error(fmt::format("{}= must be {}, got {}", what, expected, py::repr(value).cast<std::string>()));
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
    throw rigid::Error(fmt::format("axis= must be 'x', 'y', 'z', '-x', '-y', '-z' or a vector (vx, vy, vz), got '{}'", s));
  }
  return vector3_from_python(axis, "axis", "'x', 'y', 'z', '-x', '-y', '-z' or a vector (vx, vy, vz)");
}

}  // namespace

void bind_mass(py::module_& m) {
  using rigid::MassProperties;
  using rigid::MassProperties2;
  using rigid::SecondMoments;

  py::class_<MassProperties>(m, "MassProperties",
                             "Mass (kg), center of mass p_OC_B (m) and inertia about the COM "
                             "I_C_B (kg·m²) of a 3D body, validated when built.")
      .def(py::init<double, const Eigen::Vector3d&, const Eigen::Matrix3d&>(), py::arg("mass"),
           py::arg("p_OC_B"), py::arg("I_C_B"),
           "Builds and validates: mass (kg), COM position p_OC_B from the frame origin O in the body "
           "frame B (m), inertia I_C_B about the COM in B (kg·m², the physical tensor with off-diagonal "
           "−∫ρxy dV); raises rigid.Error naming the failed condition and its margin.")
      .def_property_readonly("mass", &MassProperties::mass, "Mass (kg).")
      .def_property_readonly("com", &MassProperties::com,
                             "Center of mass p_OC_B: from the origin O, in frame B (m).")
      .def_property_readonly("inertia_com", &MassProperties::inertia_com,
                             "Inertia tensor about the COM, in frame B (kg·m²).")
      .def("inertia_about", &MassProperties::inertia_about, py::arg("p_OQ_B"),
           "Inertia about the point Q, expressed in B (parallel-axis theorem).")
      .def("inertia_about_axis", &MassProperties::inertia_about_axis, py::arg("p_OQ_B"),
           py::arg("unit_B"), "Moment of inertia about the line through Q along unit_B.")
      .def("shifted", &MassProperties::shifted, py::arg("d_B"), "The same body moved by d_B.")
      .def("rotated",
           py::overload_cast<const Eigen::Matrix3d&>(&MassProperties::rotated, py::const_),
           py::arg("R_AB"),
           "The same body re-expressed in frame A.")
      .def("transformed",
           py::overload_cast<const Eigen::Matrix3d&, const Eigen::Vector3d&>(
               &MassProperties::transformed, py::const_),
           py::arg("R_AB"), py::arg("p_AB_A"),
           "The same body expressed in frame A, given the pose of B in A.")
      .def(
          "principal_axes",
          [](const MassProperties& mp) {
            const auto pa = mp.principal_axes();
            return py::make_tuple(pa.moments, pa.R_BP);
          },
          "(ascending principal moments, R_BP with the principal axes as columns, det +1).")
      .def("invalidity_report", &MassProperties::invalidity_report,
           "Why these mass properties are not physical, or None (always None once built; see check).")
      .def_static("check", &MassProperties::check, py::arg("mass"), py::arg("p_OC_B"),
                  py::arg("I_C_B"), "Why (mass, com, inertia) is not physical, or None.")
      .def("__repr__", [](const MassProperties& mp) { return fmt::format("{}", mp); });

  m.def(
      "combine",
      [](const std::vector<MassProperties>& parts) { return rigid::combine(parts); },
      py::arg("parts"), "Mass properties of the union of bodies in one frame.");
  m.def("subtract", &rigid::subtract, py::arg("whole"), py::arg("hole"),
        "The body with a hole removed; refuses non-physical results.");

  py::class_<MassProperties2>(m, "MassProperties2", "Planar mass, COM and moment about the COM.")
      .def(py::init<double, const Eigen::Vector2d&, double>(), py::arg("mass"), py::arg("p_OC_B"),
           py::arg("moment_com"),
           "Builds and validates: mass (kg), COM p_OC_B in the plane frame B (m), polar moment about "
           "the COM (kg·m², about the normal through C).")
      .def_property_readonly("mass", &MassProperties2::mass, "Mass (kg).")
      .def_property_readonly("com", &MassProperties2::com,
                             "Center of mass p_OC_B in the plane frame B (m).")
      .def_property_readonly("moment_com", &MassProperties2::moment_com,
                             "Polar moment of inertia about the normal through the COM (kg·m²).")
      .def("moment_about", &MassProperties2::moment_about, py::arg("p_OQ_B"),
           "Polar moment about the normal through Q (p_OQ_B in B, m): moment_com + m |p_QC|² (kg·m²).")
      .def("__repr__", [](const MassProperties2& mp) { return fmt::format("{}", mp); });

  py::class_<SecondMoments>(m, "SecondMoments",
                            "n-D mass, COM and second-moment matrix J about the COM.")
      .def(py::init<double, const Eigen::VectorXd&, const Eigen::MatrixXd&>(), py::arg("mass"),
           py::arg("com"), py::arg("J_com"),
           "Builds and validates: mass (kg), COM in the body frame (m, n entries), second-moment "
           "matrix J = ∫ρ r rᵀ dV about the COM (kg·m², n × n, symmetric positive semidefinite).")
      .def_property_readonly("mass", &SecondMoments::mass, "Mass (kg).")
      .def_property_readonly("com", &SecondMoments::com, "Center of mass in the body frame (m).")
      .def_property_readonly("J_com", &SecondMoments::J_com,
                             "Second-moment matrix ∫ρ r rᵀ dV about the COM (kg·m²).")
      .def_property_readonly("dimension", &SecondMoments::dimension,
                             "n, the dimension of the space.")
      .def("J_about", &SecondMoments::J_about, py::arg("q"),
           "J about the point q (m): J_C + m (c − q)(c − q)ᵀ (kg·m²).")
      .def("apply", &SecondMoments::apply, py::arg("Omega"), "M = J Ω + Ω J for Ω in so(n).")
      .def("to_mass_properties", &SecondMoments::to_mass_properties,
           "The 3D MassProperties (I = tr(J) 1 − J); raises rigid.Error unless n = 3.")
      .def_static("from_mass_properties", &SecondMoments::from_mass_properties, py::arg("mp"),
                  "The second moments of 3D mass properties: J = ½ tr(I) 1 − I.")
      .def("__repr__", [](const SecondMoments& s) {
        return fmt::format("SecondMoments(n={}, mass={} kg, com={} m, J_com={} kg·m²)", s.dimension(), s.mass(),
                           rigid::to_string(s.com().transpose()), rigid::to_string(s.J_com()));
      });

  auto mass = m.def_submodule("mass", "Primitive bodies, laminae, n-D bodies, density cubature.");
  namespace rm = rigid::mass;
  // docstrings: the frames and formulas of every primitive are in docs/mass.md
#define RIGID_BIND_PRIMITIVE(name, ...)                                                     \
  mass.def(#name "_with_mass", &rm::name##_with_mass, py::arg("m"), __VA_ARGS__,            \
           "Uniform " #name " of mass m (kg); sizes in m (frame and formula: docs/mass.md)."); \
  mass.def(#name "_with_density", &rm::name##_with_density, py::arg("rho"), __VA_ARGS__,    \
           "Uniform " #name " of density rho (kg/m³, kg/m² for shells/plates/laminae, kg/m "  \
           "for the rod); sizes in m.")
  RIGID_BIND_PRIMITIVE(solid_sphere, py::arg("r"));
  RIGID_BIND_PRIMITIVE(thick_spherical_shell, py::arg("r_inner"), py::arg("r_outer"));
  RIGID_BIND_PRIMITIVE(thin_spherical_shell, py::arg("r"));
  RIGID_BIND_PRIMITIVE(solid_ellipsoid, py::arg("a"), py::arg("b"), py::arg("c"));
  RIGID_BIND_PRIMITIVE(solid_box, py::arg("lx"), py::arg("ly"), py::arg("lz"));
  RIGID_BIND_PRIMITIVE(solid_cylinder, py::arg("r"), py::arg("h"));
  RIGID_BIND_PRIMITIVE(thick_tube, py::arg("r_inner"), py::arg("r_outer"), py::arg("h"));
  RIGID_BIND_PRIMITIVE(thin_cylindrical_shell, py::arg("r"), py::arg("h"));
  RIGID_BIND_PRIMITIVE(capped_cylindrical_shell, py::arg("r"), py::arg("h"));
  RIGID_BIND_PRIMITIVE(solid_cone, py::arg("r"), py::arg("h"));
  RIGID_BIND_PRIMITIVE(solid_frustum, py::arg("r_bottom"), py::arg("r_top"), py::arg("h"));
  RIGID_BIND_PRIMITIVE(solid_capsule, py::arg("r"), py::arg("l"));
  RIGID_BIND_PRIMITIVE(solid_torus, py::arg("R"), py::arg("a"));
  RIGID_BIND_PRIMITIVE(thin_rod, py::arg("l"));
  RIGID_BIND_PRIMITIVE(thin_rectangular_plate, py::arg("lx"), py::arg("ly"));
  RIGID_BIND_PRIMITIVE(thin_disk, py::arg("r"));
  RIGID_BIND_PRIMITIVE(thin_ring, py::arg("r"));
  RIGID_BIND_PRIMITIVE(solid_tetrahedron, py::arg("v0"), py::arg("v1"), py::arg("v2"), py::arg("v3"));
  RIGID_BIND_PRIMITIVE(disk_lamina, py::arg("r"));
  RIGID_BIND_PRIMITIVE(annulus_lamina, py::arg("r_inner"), py::arg("r_outer"));
  RIGID_BIND_PRIMITIVE(rectangle_lamina, py::arg("lx"), py::arg("ly"));
  RIGID_BIND_PRIMITIVE(polygon_lamina, py::arg("vertices"));
#undef RIGID_BIND_PRIMITIVE
  // the primitive catalogue: one factory per name and alias (rigid.mass.solid_cylinder,
  // rigid.mass.cylinder, ...), taking mass= or density= and the sizes by name
  // the keyword arguments of a catalogue factory: mass= or density=, the sizes and points by
  // name, and the placement axis=, origin=, rpy=
  struct PrimitiveCall {
    rm::Amount amount;
    double value;
    rm::PrimitiveArguments args;
    rm::Placement placement;
  };
  auto parse_call = [](const std::string& name, const py::kwargs& kwargs) {
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
        amount_mass = item.second.cast<double>();
      } else if (key == "density") {
        amount_density = item.second.cast<double>();
      } else if (e.point_index(key)) {
        call.args.points.emplace_back(key, item.second.cast<Eigen::Vector3d>());
      } else {
        call.args.sizes.emplace_back(key, item.second.cast<double>());
      }
    }
    if (amount_mass.has_value() == amount_density.has_value()) {
      throw rigid::Error(fmt::format("rigid.mass.{}(): give exactly one of mass= (kg) and density= ({}), got {}",
                                     name, e.density_unit, amount_mass ? "both" : "neither"));
    }
    call.amount = amount_mass ? rm::Amount::kMass : rm::Amount::kDensity;
    call.value = amount_mass ? *amount_mass : *amount_density;
    return call;
  };
  auto make = [parse_call](const std::string& name, const py::kwargs& kwargs) {
    const PrimitiveCall c = parse_call(name, kwargs);
    return rm::place(rm::make_primitive(name, c.amount, c.value, c.args), c.placement);
  };
  mass.def(
      "primitive_uncertainty",
      [parse_call](const std::string& name, const std::string& tolerance, const py::object& about,
                   const py::kwargs& kwargs) {
        const PrimitiveCall c = parse_call(name, kwargs);
        std::optional<Eigen::Vector3d> point;
        if (!about.is_none()) point = vector3_from_python(about, "about", "a point (x, y, z) in m, or None for the COM");
        const auto u = rm::primitive_uncertainty(name, c.amount, c.value, c.args, c.placement,
                                                 rm::parse_tolerances(tolerance), point);
        const auto tensor = [](const Eigen::Matrix<double, 10, 1>& y) {
          Eigen::Matrix3d I;
          I << y(4), y(7), y(8), y(7), y(5), y(9), y(8), y(9), y(6);
          return I;
        };
        py::dict d;
        d["mass"] = u.value(0);
        d["com"] = Eigen::Vector3d(u.value.segment<3>(1));
        d["inertia"] = tensor(u.value);
        py::dict sigma;
        sigma["mass"] = u.sigma(0);
        sigma["com"] = Eigen::Vector3d(u.sigma.segment<3>(1));
        sigma["inertia"] = tensor(u.sigma);
        d["sigma"] = sigma;
        d["inputs"] = u.inputs;
        return d;
      },
      py::arg("name"), py::arg("tolerance"), py::arg("about") = py::none(),
      "Mass, COM and inertia (about `about`, the COM when None) of a catalogue primitive with "
      "their 1σ, first-order propagation of independent inputs: primitive_uncertainty('cylinder', "
      "'dims=±0.1mm,density=±2%', density=2700, radius=0.05, height=0.4). Takes the factories' "
      "keywords (axis=, origin=, rpy= too); ± is one standard deviation.");
  mass.def(
      "place",
      [](const MassProperties& body, const py::object& axis, const Eigen::Vector3d& origin,
         const Eigen::Vector3d& rpy) {
        return rm::place(body, rm::Placement{.axis = axis_from_python(axis), .rpy = rpy, .origin = origin});
      },
      py::arg("body"), py::arg("axis") = "z", py::arg("origin") = Eigen::Vector3d::Zero().eval(),
      py::arg("rpy") = Eigen::Vector3d::Zero().eval(),
      "The body (given in a shape's own frame) placed in the link frame: its z axis turned along "
      "axis ('x', 'y', 'z', '-x', '-y', '-z' or a vector), then rotated by rpy (rad, URDF: "
      "Rz(yaw) Ry(pitch) Rx(roll)), then its origin moved to origin (m). Every catalogue "
      "factory takes the same axis=, origin=, rpy=.");
  mass.def("placement_rotation",
           [](const py::object& axis, const Eigen::Vector3d& rpy) {
             return rm::placement_rotation(rm::Placement{.axis = axis_from_python(axis), .rpy = rpy, .origin = Eigen::Vector3d::Zero()});
           },
           py::arg("axis") = "z", py::arg("rpy") = Eigen::Vector3d::Zero().eval(),
           "R_LS of a placement: Rz(yaw) Ry(pitch) Rx(roll) · (shortest rotation from z to axis).");
  mass.def(
      "primitive", [make](const std::string& name, const py::kwargs& kwargs) { return make(name, kwargs); },
      py::arg("name"),
      "Mass properties of the catalogue's primitive `name` (any name or alias, as in scene files and "
      "`rigid inertia`): primitive('cylinder', mass=2.0, radius=0.1, height=0.5). Sizes in m, "
      "mass in kg or density in kg/m³ (kg/m² shells and plates, kg/m rods); vertices as (x, y, z).");
  for (const rm::PrimitiveEntry& e : rm::primitive_table()) {
    std::string doc = fmt::format("{} in its own frame: {}(mass= or density=, ", e.description, e.name);
    std::vector<std::string> args;
    for (const auto& sz : e.sizes) args.push_back(fmt::format("{}= ({}, {})", sz.name, sz.help, sz.unit));
    for (const auto& pt : e.points) args.push_back(fmt::format("{}= ({} as (x, y, z), m)", pt.name, pt.help));
    doc += fmt::format("{}). Density in {}.", fmt::join(args, ", "), e.density_unit);
    if (!e.aliases.empty()) doc += fmt::format(" Also called: {}.", fmt::join(e.aliases, ", "));
    for (const std::string& n : e.names()) {
      mass.def(n.c_str(), [make, n](const py::kwargs& kwargs) { return make(n, kwargs); }, doc.c_str());
    }
  }
  mass.def(
      "primitives",
      [] {
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
      },
      "The primitive catalogue: every shape with its name, aliases, sizes (name, help, unit, "
      "aliases), vertices and density unit.");
  mass.def("n_ball_with_mass", &rm::n_ball_with_mass, py::arg("n"), py::arg("m"), py::arg("r"),
           "Uniform n-ball of mass m (kg) and radius r (m), centred: SecondMoments with J = m r²/(n + 2) · 1.");
  mass.def("n_ball_with_density", &rm::n_ball_with_density, py::arg("n"), py::arg("rho"), py::arg("r"),
           "Uniform n-ball of density rho (kg/mⁿ) and radius r (m), centred; volume π^(n/2) rⁿ / Γ(n/2 + 1).");
  mass.def("n_box_with_mass", &rm::n_box_with_mass, py::arg("m"), py::arg("sizes"),
           "Uniform n-box of mass m (kg) with edge lengths `sizes` (m), centred: J = m diag(l_i²/12).");
  mass.def("n_box_with_density", &rm::n_box_with_density, py::arg("rho"), py::arg("sizes"),
           "Uniform n-box of density rho (kg/mⁿ) with edge lengths `sizes` (m), centred; volume Π l_i.");
  mass.def("point_mass", &rm::point_mass, py::arg("m"), py::arg("p"),
           "A point mass m (kg) at p (m, in the frame of the result): COM p, zero inertia about the COM.");
  mass.def(
      "point_masses",
      [](const std::vector<double>& masses, const Eigen::Matrix3Xd& points) {
        return rm::point_masses(masses, points);
      },
      py::arg("masses"), py::arg("points"), "Point masses at the columns of a 3 × n array.");

  py::class_<rm::DensityIntegration>(mass, "DensityIntegration",
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
        return fmt::format("DensityIntegration(mass_properties={}, mass_error={} kg, com_error={} m, "
                           "inertia_error={} kg·m², cells={}, converged={})", d.mass_properties, d.mass_error,
                           d.com_error, d.inertia_error, d.cells, d.converged ? "True" : "False");
      });
  auto opts = [](double tol, int cells) {
    return rm::CubatureOptions{.relative_tolerance = tol, .max_cells = cells};
  };
  mass.def(
      "integrate_density_over_box",
      [opts](const rm::DensityFunction& rho, double lx, double ly, double lz, double tol, int cells) {
        return rm::integrate_density_over_box(rho, lx, ly, lz, opts(tol, cells));
      },
      py::arg("rho"), py::arg("lx"), py::arg("ly"), py::arg("lz"),
      py::arg("relative_tolerance") = 1e-10, py::arg("max_cells") = 2000,
      "Mass properties of the density rho(p) (kg/m³; p a point in m, the box's frame) over the box "
      "[-lx/2, lx/2] × [-ly/2, ly/2] × [-lz/2, lz/2] (m), by adaptive cubature: a DensityIntegration.");
  mass.def(
      "integrate_density_over_cylinder",
      [opts](const rm::DensityFunction& rho, double r, double h, double tol, int cells) {
        return rm::integrate_density_over_cylinder(rho, r, h, opts(tol, cells));
      },
      py::arg("rho"), py::arg("r"), py::arg("h"), py::arg("relative_tolerance") = 1e-10,
      py::arg("max_cells") = 2000,
      "Mass properties of the density rho(p) (kg/m³) over the cylinder of radius r and height h (m), "
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

  // inertial XML
  auto parse_format = [](const std::string& f) {
    for (auto k : {rigid::io::InertialFormat::urdf, rigid::io::InertialFormat::mjcf,
                   rigid::io::InertialFormat::sdf}) {
      if (f == rigid::io::to_string(k)) return k;
    }
    throw rigid::Error(fmt::format("format must be 'urdf', 'mjcf' or 'sdf', got '{}'", f));
  };
  mass.def(
      "write_inertial_document",
      [parse_format](const MassProperties& mp, const std::string& format, const std::string& name,
                     bool principal, const std::optional<Eigen::Matrix3d>& inertial_frame) {
        return rigid::io::write_inertial_document(mp, parse_format(format),
                                                  {.name = name, .principal = principal}, inertial_frame);
      },
      py::arg("mp"), py::arg("format"), py::arg("name") = "body", py::arg("principal") = false,
      py::arg("inertial_frame") = py::none(),
      "A minimal URDF/MJCF/SDF document holding one inertial; with principal=True, "
      "inertial_frame=R_LI (e.g. placement_rotation(axis, rpy)) writes that frame exactly.");
  mass.def("pseudo_inertia", &rm::pseudo_inertia, py::arg("mp"),
           "The 4×4 pseudo-inertia J = [[Σ, h], [hᵀ, m]] about the frame origin: Σ = ½ tr(I_O) 1 − I_O, "
           "h = m c [Wensing2017].");
  mass.def("from_pseudo_inertia", &rm::from_pseudo_inertia, py::arg("J"),
           "The body of a pseudo-inertia J; raises rigid.Error naming the failed condition (mass, "
           "triangle inequality) when J is not positive semidefinite.");
  mass.def("log_cholesky", &rm::log_cholesky, py::arg("mp"),
           "The 10 log-Cholesky parameters (alpha, d1, d2, d3, s12, s23, s13, t1, t2, t3) of the body "
           "about the frame origin [Rucker2022]; J = U Uᵀ, m = exp(2 alpha).");
  mass.def("from_log_cholesky", &rm::from_log_cholesky, py::arg("theta"),
           "The body of 10 log-Cholesky parameters (any finite vector is a physical body).");
  mass.def("pseudo_inertia_from_log_cholesky", &rm::pseudo_inertia_from_log_cholesky, py::arg("theta"),
           "J = U Uᵀ of 10 log-Cholesky parameters.");
  mass.def(
      "read_inertials",
      [](const std::string& xml, const std::string& source) {
        py::list out;
        for (const auto& e : rigid::io::read_inertials(xml, source)) {
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
      },
      py::arg("xml"), py::arg("source") = "<string>",
      "Every inertial of a URDF/MJCF/SDF document as dicts (link frame, rotation applied).");
  mass.def(
      "fix_inertials",
      [](const std::string& path, const std::optional<std::string>& output,
         std::optional<double> density, bool keep_mass, const std::string& geometry,
         const std::vector<std::string>& only, const py::object& package_path) {
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
          options.package_paths.push_back(rigid::io::parse_package_path(package_path.cast<std::string>()));
        } else if (!package_path.is_none()) {
          for (const auto& p : package_path) {
            options.package_paths.push_back(rigid::io::parse_package_path(p.cast<std::string>()));
          }
        }
        const auto result = rigid::io::fix_inertials_file(path, options);
        // the report is the command line's JSON table, as a dict
        py::dict report = py::module_::import("json").attr("loads")(
            rigid::word_for(rigid::Surface::kPython, rigid::io::fix_table_json(result)));
        result.require_ok();
        if (output) rigid::io::write_file_atomically(*output, result.text);
        report["text"] = result.text;
        return report;
      },
      py::arg("path"), py::arg("output") = std::nullopt, py::arg("density") = std::nullopt,
      py::arg("keep_mass") = false, py::arg("geometry") = "collision",
      py::arg("only") = std::vector<std::string>{},
      py::arg("package_path") = py::none(),
      "Recompute the inertials of a URDF/SDF/MJCF model from its geometry (as `rigid inertia "
      "fix`): the report of old vs new per link, with the rewritten document as 'text'; "
      "writes it to `output` when given. Raises rigid.Error (and writes nothing) if a link "
      "cannot be fixed.");
}
