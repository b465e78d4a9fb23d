// Python bindings of the Lagrangian engine: rigid.lagrange.System (derive once, simulate with
// numpy arrays out) and the integrator names.
#include <optional>

#include <fmt/format.h>

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "interrupt.hpp"
#include "rigid/lagrange/export.hpp"
#include "rigid/lagrange/system.hpp"

namespace py = pybind11;
namespace cv = rigid::python::convert;

namespace {

using rigid::lagrange::AxisRotation;

// q or q_dot of a system: shape (n,) with n its number of coordinates, finite.
// q (num_coordinates entries) or, for an argument named q_dot or q_dot0, the velocities
// (num_velocities: three per ball coordinate where q has four)
Eigen::VectorXd coordinates_arg(const rigid::lagrange::System& s, const py::handle& value,
                                std::string_view function, std::string_view name) {
  const bool velocity = name == "q_dot" || name == "q_dot0";
  return cv::vector(value, {function, name}, velocity ? s.num_velocities() : s.num_coordinates());
}
using rigid::lagrange::Body;
using rigid::lagrange::NamedExpression;
using rigid::lagrange::System;
using rigid::lagrange::SystemSpec;

std::vector<NamedExpression> named(const std::vector<std::pair<std::string, std::string>>& items) {
  std::vector<NamedExpression> out;
  for (const auto& [name, text] : items) out.push_back({name, text});
  return out;
}

Body body_from_dict(const py::dict& d, std::size_t index) {
  for (auto item : d) {
    const auto key = item.first.cast<std::string>();
    if (key != "name" && key != "mass" && key != "position" && key != "rotations") {
      throw rigid::Error(
          fmt::format("lagrange.System(): unknown body key '{}'; expected name, "
                      "mass, position, rotations",
                      key));
    }
  }
  if (!d.contains("mass")) {
    throw rigid::Error("lagrange.System(): a body needs 'mass' (a rigid.MassProperties)");
  }
  Body b{d.contains("name") ? d["name"].cast<std::string>() : fmt::format("body{}", index),
         d["mass"].cast<rigid::MassProperties>(),
         {},
         {}};
  if (d.contains("position")) {
    const auto p = d["position"].cast<std::vector<std::string>>();
    if (p.size() != 3) {
      throw rigid::Error(
          fmt::format("lagrange.System(): body '{}' position needs 3 expressions, "
                      "got {}",
                      b.name, p.size()));
    }
    for (int k = 0; k < 3; ++k)
      b.position[static_cast<std::size_t>(k)] = p[static_cast<std::size_t>(k)];
  }
  if (d.contains("rotations")) {
    for (const auto& [axis, angle] :
         d["rotations"].cast<std::vector<std::pair<py::object, std::string>>>()) {
      b.rotations.push_back(AxisRotation{
          cv::vector3(axis, {"rigid.lagrange.System", "bodies[].rotations[].axis"}), angle});
    }
  }
  return b;
}

rigid::lagrange::Spring spring_from_dict(const py::dict& d) {
  rigid::lagrange::Spring sp;
  for (auto item : d) {
    const auto key = item.first.cast<std::string>();
    if (key == "body_a")
      sp.body_a = item.second.cast<std::string>();
    else if (key == "point_a")
      sp.point_a_B = cv::vector3(item.second, {"rigid.lagrange.System", "springs[].point_a"});
    else if (key == "body_b")
      sp.body_b = item.second.cast<std::string>();
    else if (key == "point_b")
      sp.point_b_B = cv::vector3(item.second, {"rigid.lagrange.System", "springs[].point_b"});
    else if (key == "stiffness")
      sp.stiffness = py::str(item.second).cast<std::string>();
    else if (key == "rest_length")
      sp.rest_length = py::str(item.second).cast<std::string>();
    else {
      throw rigid::Error(
          fmt::format("lagrange.System(): unknown spring key '{}'; expected "
                      "body_a, point_a, body_b, point_b, stiffness, rest_length",
                      key));
    }
  }
  return sp;
}

// {'name', 'coefficients': {coordinate: expression}, 'term': expression} (numbers allowed).
rigid::lagrange::VelocityConstraint velocity_constraint_from_dict(const py::dict& d,
                                                                  std::size_t index) {
  rigid::lagrange::VelocityConstraint vc;
  vc.name = fmt::format("velocity_constraint{}", index + 1);
  for (auto item : d) {
    const auto key = item.first.cast<std::string>();
    if (key == "name") {
      vc.name = item.second.cast<std::string>();
    } else if (key == "coefficients") {
      for (auto c : item.second.cast<py::dict>()) {
        vc.coefficients.push_back(
            {c.first.cast<std::string>(), py::str(c.second).cast<std::string>()});
      }
    } else if (key == "term") {
      vc.term = py::str(item.second).cast<std::string>();
    } else {
      throw rigid::Error(
          fmt::format("lagrange.System(): unknown velocity constraint key '{}'; "
                      "expected name, coefficients, term",
                      key));
    }
  }
  return vc;
}

using rigid::lagrange::Equations;

// {name: value} of parameters, in declaration order.
py::dict parameters_dict(const std::vector<rigid::lagrange::Parameter>& parameters) {
  py::dict d;
  for (const auto& p : parameters) d[py::str(p.name)] = p.value;
  return d;
}

// Equations.symbols: [{'name', 'latex', 'role', 'unit'}].
py::list symbols_as_dicts(const Equations& e) {
  py::list out;
  for (const auto& s : e.symbols) {
    py::dict d;
    d["name"] = s.name;
    d["latex"] = s.latex;
    d["role"] = s.role;
    d["unit"] = s.unit;
    out.append(d);
  }
  return out;
}

// Equations[key]: the keys of the dict that Equations replaced.
py::object legacy_equations_item(const Equations& e, const std::string& key) {
  if (key == "lagrangian") return py::cast(e.lagrangian_text);
  if (key == "lagrangian_latex") return py::cast(e.lagrangian_latex);
  if (key == "text") return py::cast(e.text);
  if (key == "latex") return py::cast(e.latex);
  if (key == "constraints") return py::cast(e.constraints_text);
  if (key == "constraints_latex") return py::cast(e.constraints_latex);
  if (key == "jacobi_integral") return py::cast(e.energy_text);
  if (key == "cyclic") return py::cast(e.cyclic);
  throw py::key_error(
      fmt::format("'{}'; keys: lagrangian, lagrangian_latex, text, latex, "
                  "constraints, constraints_latex, jacobi_integral, cyclic "
                  "(or use the attributes)",
                  key));
}

void bind_printed(py::module_& m) {
  py::class_<rigid::lagrange::Printed>(m, "Printed",
                                       "One quantity as text (SymPy-parsable) and LaTeX.")
      .def_readonly("text", &rigid::lagrange::Printed::text, "Plain text that SymPy parses.")
      .def_readonly("latex", &rigid::lagrange::Printed::latex, "LaTeX.")
      .def("__str__", [](const rigid::lagrange::Printed& p) { return p.text; })
      .def("__repr__",
           [](const rigid::lagrange::Printed& p) { return "Printed('" + p.text + "')"; });
}

// rigid.lagrange.Equations: every derived quantity as text and LaTeX.
void bind_equations(py::module_& m) {
  py::class_<Equations>(
      m, "Equations",
      "The derived equations: L, T, V, the mass matrix M(q), the forcing f(q, q_dot) "
      "(inertial + potential + generalized), the constraints and their Jacobian, the "
      "conserved quantities and the symbols, each quantity a Printed (text, latex).")
      .def_readonly("coordinates", &Equations::coordinates,
                    "The generalized coordinates' names, in order.")
      .def_property_readonly(
          "parameters", [](const Equations& e) { return parameters_dict(e.parameters); },
          "{name: value} in declaration order")
      .def_readonly("constraint_names", &Equations::constraint_names,
                    "The holonomic constraints' names, in order.")
      .def_readonly("lagrangian", &Equations::lagrangian, "L = T − V (J).")
      .def_readonly("kinetic_energy", &Equations::kinetic_energy, "T (J).")
      .def_readonly("potential_energy", &Equations::potential_energy, "V (J).")
      .def_readonly("mass_matrix", &Equations::mass_matrix, "n lists of n Printed")
      .def_readonly("forcing", &Equations::forcing,
                    "Forcing f(q, q̇) with M(q) q̈ = f: forcing_inertial + forcing_potential + "
                    "forcing_generalized, one Printed per coordinate.")
      .def_readonly("forcing_inertial", &Equations::forcing_inertial,
                    "∂T/∂q − (∂²T/∂q̇∂q) q̇ − ∂²T/∂q̇∂t (Coriolis, centrifugal, driven), one Printed "
                    "per coordinate.")
      .def_readonly("forcing_potential", &Equations::forcing_potential,
                    "−∂V/∂q, one Printed per coordinate.")
      .def_readonly("forcing_generalized", &Equations::forcing_generalized,
                    "The generalized forces Q (the `forces` given), one Printed per coordinate.")
      .def_readonly("equations", &Equations::equations, "one Printed 'lhs = rhs' per coordinate")
      .def_readonly("constraints", &Equations::constraints,
                    "The holonomic constraints g(q, t) = 0, one Printed each.")
      .def_readonly("constraint_jacobian", &Equations::constraint_jacobian,
                    "∂g/∂q: one list of n Printed per constraint.")
      .def_readonly("jacobi_integral", &Equations::jacobi_integral,
                    "The Jacobi integral h = Σ q̇ ∂L/∂q̇ − L (J; the energy when T is quadratic in "
                    "q̇).")
      .def_readonly("jacobi_conserved", &Equations::jacobi_conserved,
                    "True when h is conserved: L and the constraints do not depend on t, there are "
                    "no forces, and the velocity constraints have no term a.")
      .def_readonly("cyclic", &Equations::cyclic, "The cyclic coordinates (L independent of them).")
      .def_readonly("cyclic_momenta", &Equations::cyclic_momenta,
                    "∂L/∂q̇ of each cyclic coordinate (conserved), one Printed each.")
      .def_property_readonly(
          "intermediates",
          [](const Equations& e) {
            py::list out;
            for (const auto& [name, value] : e.intermediates) out.append(py::make_tuple(name, value));
            return out;
          },
          "The named intermediates of a tree derived by its recursions, in the order they are "
          "defined, each from those before it: [(name, definition)], both Printed. Empty for an "
          "expanded derivation.")
      .def_property_readonly("symbols", &symbols_as_dicts,
                             "Every symbol of the equations: [{'name', 'latex', 'role', 'unit'}] "
                             "(role: coordinate, velocity, parameter, ...; SI unit when known).")
      .def_readonly("text", &Equations::text, "the equations, one text line per coordinate")
      .def_readonly("latex", &Equations::latex, "the equations, one LaTeX line per coordinate")
      .def(
          "format",
          [](const Equations& e, const std::string& format) {
            return rigid::lagrange::format_equations(
                e, rigid::lagrange::parse_equation_format(format));
          },
          py::arg("format") = "text",
          "The document `rigid eom --format` prints: 'text', 'latex' or 'json'.")
      // the keys of the dict this method returned before
      .def("__getitem__", &legacy_equations_item)
      .def("__repr__", [](const Equations& e) {
        std::string out = "Equations(\n";
        for (const auto& line : e.text) out += "  " + line + "\n";
        return out + ")";
      });
}

// The System that rigid.lagrange.System(...) describes: coordinates, parameters, bodies and the
// dicts of springs and velocity constraints read into a SystemSpec.
System system_from_python(const std::vector<std::tuple<std::string, double, double>>& coordinates,
                          const py::dict& parameters, const std::string& lagrangian,
                          const std::vector<py::dict>& bodies, const py::object& gravity,
                          const std::vector<std::pair<std::string, std::string>>& potentials,
                          const std::vector<std::pair<std::string, std::string>>& forces,
                          const std::vector<std::pair<std::string, std::string>>& constraints,
                          const std::vector<py::dict>& springs,
                          const std::vector<py::dict>& velocity_constraints) {
  SystemSpec spec;
  // in the dict's order: the equations print parameters in declaration order
  for (const auto& [name, value] : parameters) {
    spec.parameters.push_back({name.cast<std::string>(), value.cast<double>()});
  }
  for (const auto& [name, q0, v0] : coordinates) spec.coordinates.push_back({name, q0, v0});
  spec.lagrangian = lagrangian;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    spec.bodies.push_back(body_from_dict(bodies[i], i));
  }
  spec.gravity_W = rigid::lagrange::Vector3Expression(
      cv::vector3(gravity, {"rigid.lagrange.System", "gravity"}));
  spec.potentials = named(potentials);
  spec.forces = named(forces);
  spec.constraints = named(constraints);
  for (const py::dict& sp : springs) spec.springs.push_back(spring_from_dict(sp));
  for (std::size_t i = 0; i < velocity_constraints.size(); ++i) {
    spec.velocity_constraints.push_back(velocity_constraint_from_dict(velocity_constraints[i], i));
  }
  return System(spec);
}

// The samples of a run as a dict of numpy arrays (rows are samples) and name lists.
py::dict trajectory_dict(const rigid::lagrange::Trajectory& tr) {
  py::dict d;
  d["t"] = tr.t;
  d["q"] = tr.q;
  d["q_dot"] = tr.q_dot;
  d["lambda"] = tr.lambda;
  d["energy"] = tr.energy;
  d["jacobi"] = tr.jacobi;
  d["cyclic_momenta"] = tr.cyclic_momenta;
  d["residual"] = tr.residual;
  d["velocity_residual"] = tr.velocity_residual;
  d["coordinate_names"] = tr.coordinate_names;
  d["velocity_names"] = tr.velocity_names;
  d["constraint_names"] = tr.constraint_names;
  d["cyclic_names"] = tr.cyclic_names;
  d["steps"] = tr.steps;
  d["mu"] = tr.mu;
  d["velocity_constraint_residual"] = tr.velocity_constraint_residual;
  d["velocity_constraint_names"] = tr.velocity_constraint_names;
  return d;
}

// System.simulate: integrates from (q0, q_dot0), the declared initial state where None.
py::dict simulate_to_dict(const System& s, double t_end, const std::string& method, double dt,
                          double tolerance, double output_dt, double stabilization,
                          bool project_initial, const py::object& q0, const py::object& q_dot0) {
  rigid::python::Interruptible interrupt;
  rigid::lagrange::SimulationOptions o{.t_end = t_end,
                                       .method = rigid::integrate::parse_method(method),
                                       .dt = dt,
                                       .tolerance = tolerance,
                                       .output_dt = output_dt,
                                       .stabilization = stabilization,
                                       .project_initial = project_initial,
                                       .parameters = {},
                                       .control = interrupt.control()};
  const Eigen::VectorXd q_start =
      q0.is_none() ? s.initial_q() : coordinates_arg(s, q0, "System.simulate", "q0");
  const Eigen::VectorXd qd_start = q_dot0.is_none()
                                       ? s.initial_q_dot()
                                       : coordinates_arg(s, q_dot0, "System.simulate", "q_dot0");
  // a System is immutable and each run has its own workspace: other Python threads
  // may run while this one integrates
  rigid::lagrange::Trajectory tr;
  {
    py::gil_scoped_release release;
    tr = s.simulate(o, q_start, qd_start);
  }
  return trajectory_dict(tr);
}

// What a System is made of: its coordinates, constraints, bodies, initial state and
// parameters, the compiled tape, the printed equations and the exported source.
void bind_system_description(py::class_<System>& cls) {
  cls.def_property_readonly("coordinate_names", &System::coordinate_names,
                            "The entries of q, in order (a ball coordinate b: b_qw b_qx b_qy b_qz).")
      .def_property_readonly("velocity_names", &System::velocity_names,
                             "The entries of q_dot, M's rows and f: c_dot per coordinate c, a ball's "
                             "body-frame angular velocity b_wx b_wy b_wz.")
      .def(
          "coordinate_rates",
          [](const System& s, const py::object& q, const py::object& q_dot) {
            return s.coordinate_rates(coordinates_arg(s, q, "System.coordinate_rates", "q"),
                                      coordinates_arg(s, q_dot, "System.coordinate_rates", "q_dot"));
          },
          py::arg("q"), py::arg("q_dot"),
          "dq/dt at (q, q_dot): q_dot's entries, and 1/2 q * (0, w) for a ball's quaternion.")
      .def_property_readonly("constraint_names", &System::constraint_names,
                             "The holonomic constraints, in order.")
      .def_property_readonly("cyclic_coordinates", &System::cyclic_coordinates,
                             "Coordinates L does not depend on (their momenta are conserved).")
      .def_property_readonly("velocity_constraint_names", &System::velocity_constraint_names,
                             "The velocity (non-holonomic) constraints, in order.")
      .def_property_readonly("body_names", &System::body_names, "Names of the bodies, in order.")
      .def_property_readonly("initial_q", &System::initial_q,
                             "q(0) from the coordinates' declarations, shape (n,).")
      .def_property_readonly("initial_q_dot", &System::initial_q_dot,
                             "q̇(0), shape (nv,) (the velocities: a ball's ω in its body's frame).")
      .def_property_readonly(
          "parameters", [](const System& s) { return parameters_dict(s.parameters()); },
          "{name: value} of the parameters, in declaration order.")
      .def_property_readonly(
          "tape_size", &System::tape_size,
          "Instructions in the compiled tape that evaluates M, f and the constraints.")
      .def("set_parameter", &System::set_parameter, py::arg("name"), py::arg("value"),
           "Sets a parameter's value (SI units) for later evaluations and runs; the equations keep "
           "its name.")
      .def("equations", &System::equations,
           "The equations, printed canonically (the same on every run) and simplified: a "
           "rigid.lagrange.Equations with each quantity as text and LaTeX.")
      .def(
          "emit",
          [](const System& s, const std::string& language, const std::string& name, bool flat,
             std::optional<std::size_t> max_stack_bytes, const std::string& namespace_) {
            rigid::lagrange::ExportOptions o;
            o.name = name;
            o.flat = flat;
            o.flat_namespace = namespace_;
            const auto lang = rigid::lagrange::parse_language(language);
            if (flat && lang != rigid::lagrange::Language::kCpp) {
              throw rigid::Error("flat=True is a layout of the C++ export (global functions "
                                 "without t); the Python module has one layout");
            }
            if (max_stack_bytes && !flat) {
              throw rigid::Error("rigid.lagrange.System.emit(): max_stack_bytes bounds the stack of "
                                 "the flat layout's derivatives; give flat=True with it");
            }
            if (!namespace_.empty() && !flat) {
              throw rigid::Error("rigid.lagrange.System.emit(): namespace is the flat layout's "
                                 "(the other C++ layout's namespace is `name`); give flat=True "
                                 "with it");
            }
            if (max_stack_bytes) o.max_stack_bytes = *max_stack_bytes;
            return rigid::lagrange::emit(s, lang, o);
          },
          py::arg("language"), py::arg("name") = "model", py::arg("flat") = false,
          py::kw_only(), py::arg("max_stack_bytes") = py::none(), py::arg("namespace") = std::string{},
          "The equations of motion (M, f, G, γ) as one dependency-free source file: language "
          "'c++' (a header, <cmath> only, namespace `name`) or 'python' (a module, math only); "
          "parameters are named arguments with the current values as defaults. flat=True (C++): "
          "the dynamics at global scope without t (mass_matrix, inverse_dynamics, "
          "forward_dynamics and their derivatives), as `rigid eom --emit c++ --flat`; "
          "max_stack_bytes (with flat=True): the stack bound of the derivatives (16 n² + 8 n "
          "bytes for the products; default 66048), as Scene.emit; namespace (with flat=True): "
          "the C++ namespace of its declarations, as Scene.emit.");
}

// A System evaluated at (t, q) or (t, q, q̇): constraint residuals, energies and body poses.
void bind_system_evaluations(py::class_<System>& cls) {
  cls.def(
         "velocity_constraint_residual",
         [](const System& s, double t, const py::object& q, const py::object& q_dot) {
           const char* f = "System.velocity_constraint_residual";
           return s.velocity_constraint_residual(t, coordinates_arg(s, q, f, "q"),
                                                 coordinates_arg(s, q_dot, f, "q_dot"));
         },
         py::arg("t"), py::arg("q"), py::arg("q_dot"),
         "A(q, t) q̇ + a(q, t) at time t (s), q and q̇ of shape (n,): one entry per velocity "
         "constraint.")
      .def(
          "energy",
          [](const System& s, double t, const py::object& q, const py::object& q_dot) {
            const char* f = "System.energy";
            return s.energy(t, coordinates_arg(s, q, f, "q"),
                            coordinates_arg(s, q_dot, f, "q_dot"));
          },
          py::arg("t"), py::arg("q"), py::arg("q_dot"),
          "T + V (J) at time t (s) and (q, q̇), each shape (n,).")
      .def(
          "jacobi_integral",
          [](const System& s, double t, const py::object& q, const py::object& q_dot) {
            const char* f = "System.jacobi_integral";
            return s.jacobi_integral(t, coordinates_arg(s, q, f, "q"),
                                     coordinates_arg(s, q_dot, f, "q_dot"));
          },
          py::arg("t"), py::arg("q"), py::arg("q_dot"),
          "The Jacobi integral h = Σ q̇ ∂L/∂q̇ − L (J) at (t, q, q̇); conserved when L does not "
          "depend on t.")
      .def(
          "constraint_residual",
          [](const System& s, double t, const py::object& q) {
            return s.constraint_residual(t,
                                         coordinates_arg(s, q, "System.constraint_residual", "q"));
          },
          py::arg("t"), py::arg("q"), "g(q, t) of the holonomic constraints (one entry each).")
      .def(
          "body_poses",
          [](const System& s, double t, const py::object& q) {
            py::dict out;
            const auto poses = s.body_poses(t, coordinates_arg(s, q, "System.body_poses", "q"));
            for (std::size_t i = 0; i < poses.size(); ++i) {
              py::dict d;
              d["p_world"] = poses[i].p_WB;
              d["q_wxyz"] = Eigen::Vector4d(poses[i].R_WB.quaternion());
              d["R_WB"] = Eigen::Matrix3d(poses[i].R_WB.matrix());
              out[py::str(s.body_names()[i])] = d;
            }
            return out;
          },
          py::arg("t"), py::arg("q"),
          "{body: {'p_world': origin of B in W (m), 'q_wxyz': R_WB, 'R_WB': (3, 3)}} at (t, q).");
}

// The terms of the equations of motion at (t, q, q̇): M and f, the constraint terms G and γ,
// and the accelerations with the multipliers.
void bind_system_dynamics(py::class_<System>& cls) {
  cls.def(
         "mass_matrix_and_forces",
         [](const System& s, double t, const py::object& q_arg, const py::object& q_dot_arg) {
           const Eigen::VectorXd q =
               coordinates_arg(s, q_arg, "System.mass_matrix_and_forces", "q");
           const Eigen::VectorXd q_dot =
               coordinates_arg(s, q_dot_arg, "System.mass_matrix_and_forces", "q_dot");
           Eigen::MatrixXd M;
           Eigen::VectorXd f;
           s.mass_matrix_and_forces(t, q, q_dot, M, f);
           return py::make_tuple(M, f);
         },
         py::arg("t"), py::arg("q"), py::arg("q_dot"), "(M, f) at (t, q, q̇).")
      .def(
          "constraint_terms",
          [](const System& s, double t, const py::object& q_arg, const py::object& q_dot_arg) {
            const Eigen::VectorXd q = coordinates_arg(s, q_arg, "System.constraint_terms", "q");
            const Eigen::VectorXd q_dot =
                coordinates_arg(s, q_dot_arg, "System.constraint_terms", "q_dot");
            Eigen::MatrixXd G;
            Eigen::VectorXd gamma;
            rigid::lagrange::Workspace w = s.make_workspace();
            rigid::lagrange::constraint_terms(s, w, t, q, q_dot, G, gamma);
            return py::make_tuple(G, gamma);
          },
          py::arg("t"), py::arg("q"), py::arg("q_dot"),
          "(G, γ) at (t, q, q̇): the constraint Jacobian ∂g/∂q (m × n) and γ with G q̈ = γ.")
      .def(
          "accelerations",
          [](const System& s, double t, const py::object& q_arg, const py::object& q_dot_arg) {
            const Eigen::VectorXd q = coordinates_arg(s, q_arg, "System.accelerations", "q");
            const Eigen::VectorXd q_dot =
                coordinates_arg(s, q_dot_arg, "System.accelerations", "q_dot");
            Eigen::VectorXd qdd, lambda;
            s.accelerations(t, q, q_dot, qdd, lambda);
            return py::make_tuple(qdd, lambda);
          },
          py::arg("t"), py::arg("q"), py::arg("q_dot"),
          "(q̈, λ) at (t, q, q̇); λ holds the holonomic multipliers, then the velocity "
          "constraints' μ.");
}

// rigid.lagrange.System: derived once, then evaluated and integrated.
void bind_system(py::module_& m) {
  py::class_<System> cls(m, "System",
                         "A Lagrangian system: L = lagrangian + Σ bodies (T − V_gravity) − Σ "
                         "potentials, with generalized forces and holonomic constraints.");
  cls.def(py::init(&system_from_python), py::arg("coordinates"), py::arg("parameters") = py::dict(),
          py::arg("lagrangian") = "", py::arg("bodies") = std::vector<py::dict>{},
          py::arg("gravity") = py::make_tuple(0.0, 0.0, 0.0),
          py::arg("potentials") = std::vector<std::pair<std::string, std::string>>{},
          py::arg("forces") = std::vector<std::pair<std::string, std::string>>{},
          py::arg("constraints") = std::vector<std::pair<std::string, std::string>>{},
          py::arg("springs") = std::vector<py::dict>{},
          py::arg("velocity_constraints") = std::vector<py::dict>{},
          "coordinates: [(name, q0, q_dot0)]; parameters: {name: value}; bodies: [{'name', "
          "'mass': rigid.MassProperties, 'position': [3 expressions], 'rotations': [(axis, "
          "angle expression)]}]; potentials/forces/constraints: [(name, expression)] (a force's "
          "name is its coordinate); springs: [{'body_a', 'point_a', 'body_b' (omit: world), "
          "'point_b', 'stiffness', 'rest_length'}]; velocity_constraints: [{'name', "
          "'coefficients': {coordinate: A_i(q, t)}, 'term': a(q, t)}] for Σ A_i q̇_i + a = 0.");
  bind_system_description(cls);
  bind_system_evaluations(cls);
  bind_system_dynamics(cls);
  cls.def("simulate", &simulate_to_dict, py::arg("t_end"), py::arg("method") = "dopri5",
          py::arg("dt") = 1e-3, py::arg("tolerance") = 1e-10, py::arg("output_dt") = 0.0,
          py::arg("stabilization") = 10.0, py::arg("project_initial") = false,
          py::arg("q0") = py::none(), py::arg("q_dot0") = py::none(),
          "Integrates; returns a dict of numpy arrays (rows are samples): t, q, q_dot, lambda, "
          "energy, jacobi, cyclic_momenta, residual, velocity_residual, mu, "
          "velocity_constraint_residual, and the name lists (coordinate_names for q's columns, "
          "velocity_names for q_dot's: a ball coordinate has four of the first, three of the "
          "second, its quaternion written normalised).")
      .def("__repr__", [](const System& s) {
        return fmt::format("System(coordinates=[{}], constraints=[{}], velocity_constraints=[{}])",
                           fmt::join(s.coordinate_names(), ", "),
                           fmt::join(s.constraint_names(), ", "),
                           fmt::join(s.velocity_constraint_names(), ", "));
      });
}

}  // namespace

void bind_lagrange(py::module_& root) {
  py::module_ m = root.def_submodule(
      "lagrange", "Euler–Lagrange equations derived symbolically, compiled, and integrated.");

  bind_printed(m);
  bind_equations(m);
  bind_system(m);
}
