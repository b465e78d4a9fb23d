// rigid.robot: a robot model file (URDF, MJCF, SDF) as a kinematic tree with its dynamics in
// numbers: M(q), the bias and passive forces, inverse and forward dynamics (rigid::robot::
// TreeDynamics, MuJoCo's conventions, docs/robots.md). q is a numpy vector of length nq
// (MuJoCo's qpos), velocities, accelerations and forces of length nv (qvel).
#include <fmt/format.h>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "convert.hpp"
#include "rigid/common/error.hpp"
#include "rigid/io/robot_model.hpp"
#include "rigid/robot/tree_dynamics.hpp"

namespace py = pybind11;
namespace cv = rigid::python::convert;

namespace {

using rigid::robot::TreeDynamics;

// q: nq entries (qpos)
Eigen::VectorXd coordinates_arg(const TreeDynamics& t, const py::handle& value,
                                std::string_view function, std::string_view name) {
  return cv::vector(value, {function, name}, static_cast<Eigen::Index>(t.nq()),
                    cv::Finite::kRequired, t.nq() == t.nv() ? "dof" : "nq");
}

// a velocity, acceleration or force: nv entries (qvel)
Eigen::VectorXd velocities_arg(const TreeDynamics& t, const py::handle& value,
                               std::string_view function, std::string_view name) {
  return cv::vector(value, {function, name}, static_cast<Eigen::Index>(t.nv()),
                    cv::Finite::kRequired, t.nq() == t.nv() ? "dof" : "nv");
}

}  // namespace

void bind_robot(py::module_& m) {
  auto robot = m.def_submodule(
      "robot",
      "Robot model files (URDF, MJCF, SDF) as kinematic trees with their dynamics in numbers: "
      "M(q) q̈ = τ − b(q, q̇) + p(q, q̇), MuJoCo's conventions (docs/robots.md).");

  py::class_<TreeDynamics, std::shared_ptr<TreeDynamics>>(
      robot, "Robot",
      "A kinematic tree read from a URDF, MJCF or SDF file: links, joints (hinge, slide, ball, "
      "free; depth first from the root, MuJoCo's order), inertials and gravity. q is MuJoCo's "
      "qpos (nq entries: a ball's quaternion w x y z, a free joint's world position and "
      "quaternion), q_dot its qvel (nv entries: angular velocities in the link frame, a free "
      "joint's linear velocity in the world); forces have nv entries. Immutable; every method "
      "may be called from any thread.")
      .def(py::init([](const py::object& file, bool pin_free_root) {
             const std::string path = cv::path(file, {"rigid.robot.Robot", "file"});
             rigid::io::RobotReadOptions options;
             options.pin_free_root = pin_free_root;
             return cv::reading("rigid.robot.Robot", path, [&] {
               return std::make_shared<TreeDynamics>(
                   rigid::io::read_robot_model_file(path, options));
             });
           }),
           py::arg("file"), py::kw_only(), py::arg("pin_free_root") = false,
           "Reads the model. pin_free_root: weld a free-floating root (MJCF <freejoint>, URDF "
           "floating) where it is.")
      .def_property_readonly("dof", &TreeDynamics::dof, "Degrees of freedom (nv).")
      .def_property_readonly("nq", &TreeDynamics::nq, "Entries of q (MuJoCo's qpos).")
      .def_property_readonly("nv", &TreeDynamics::nv, "Entries of q_dot (MuJoCo's qvel).")
      .def_property_readonly(
          "coordinates", [](const TreeDynamics& t) { return t.model().coordinate_names(); },
          "The names of q's entries (a hinge's or slide's: its joint's; a free joint 'j': j_x j_y "
          "j_z j_qw j_qx j_qy j_qz; a ball 'j': j_qw j_qx j_qy j_qz).")
      .def_property_readonly(
          "velocities", [](const TreeDynamics& t) { return t.model().velocity_names(); },
          "The names of q_dot's entries (a free joint 'j': j_vx j_vy j_vz j_wx j_wy j_wz; a ball "
          "'j': j_wx j_wy j_wz).")
      .def_property_readonly(
          "links",
          [](const TreeDynamics& t) {
            std::vector<std::string> names;
            for (const auto& l : t.model().links) names.push_back(l.name);
            return names;
          },
          "The links' names, depth first from the root.")
      .def_property_readonly(
          "gravity", [](const TreeDynamics& t) { return Eigen::Vector3d(t.model().gravity); },
          "m/s², world frame.")
      .def_property_readonly("reference_configuration", &TreeDynamics::reference_configuration,
                             "q at which every link sits at its placement (MuJoCo's qpos0).")
      .def(
          "mass_matrix",
          [](const TreeDynamics& t, const py::object& q) {
            return t.mass_matrix(coordinates_arg(t, q, "rigid.robot.Robot.mass_matrix", "q"));
          },
          py::arg("q"), "M(q), nv × nv, armature on the diagonal.")
      .def(
          "bias_forces",
          [](const TreeDynamics& t, const py::object& q, const py::object& q_dot) {
            const char* f = "rigid.robot.Robot.bias_forces";
            return t.bias_forces(coordinates_arg(t, q, f, "q"),
                                 velocities_arg(t, q_dot, f, "q_dot"));
          },
          py::arg("q"), py::arg("q_dot"),
          "b(q, q̇): Coriolis, centrifugal and gravity forces (MuJoCo's qfrc_bias).")
      .def(
          "passive_forces",
          [](const TreeDynamics& t, const py::object& q, const py::object& q_dot) {
            const char* f = "rigid.robot.Robot.passive_forces";
            return t.passive_forces(coordinates_arg(t, q, f, "q"),
                                    velocities_arg(t, q_dot, f, "q_dot"));
          },
          py::arg("q"), py::arg("q_dot"),
          "p(q, q̇) = −damping q̇ − stiffness (q − springref) (MuJoCo's qfrc_passive).")
      .def(
          "inverse_dynamics",
          [](const TreeDynamics& t, const py::object& q, const py::object& q_dot,
             const py::object& q_ddot) {
            const char* f = "rigid.robot.Robot.inverse_dynamics";
            return t.inverse_dynamics(coordinates_arg(t, q, f, "q"),
                                      velocities_arg(t, q_dot, f, "q_dot"),
                                      velocities_arg(t, q_ddot, f, "q_ddot"));
          },
          py::arg("q"), py::arg("q_dot"), py::arg("q_ddot"), "τ = M q̈ + b − p.")
      .def(
          "forward_dynamics",
          [](const TreeDynamics& t, const py::object& q, const py::object& q_dot,
             const py::object& tau) {
            const char* f = "rigid.robot.Robot.forward_dynamics";
            return t.forward_dynamics(coordinates_arg(t, q, f, "q"),
                                      velocities_arg(t, q_dot, f, "q_dot"),
                                      velocities_arg(t, tau, f, "tau"));
          },
          py::arg("q"), py::arg("q_dot"), py::arg("tau"), "q̈ = M⁻¹ (τ − b + p).")
      .def(
          "energy",
          [](const TreeDynamics& t, const py::object& q, const py::object& q_dot) {
            const char* f = "rigid.robot.Robot.energy";
            const Eigen::VectorXd qv = coordinates_arg(t, q, f, "q");
            return py::make_tuple(t.kinetic_energy(qv, velocities_arg(t, q_dot, f, "q_dot")),
                                  t.potential_energy(qv));
          },
          py::arg("q"), py::arg("q_dot"),
          "(T, V) in J: T = ½ q̇ᵀ M q̇, V = gravity's and the joint springs'.")
      .def(
          "link_poses",
          [](const TreeDynamics& t, const py::object& q) {
            py::list out;
            for (const auto& pose :
                 t.link_poses(coordinates_arg(t, q, "rigid.robot.Robot.link_poses", "q"))) {
              out.append(
                  py::make_tuple(Eigen::Vector3d(pose.position), Eigen::Matrix3d(pose.rotation)));
            }
            return out;
          },
          py::arg("q"), "Each link's world pose (position (3,), rotation (3, 3)), in link order.")
      .def("__repr__", [](const TreeDynamics& t) {
        if (t.nq() != t.nv()) {
          return fmt::format("rigid.robot.Robot('{}', nq={}, nv={})", t.model().source, t.nq(),
                             t.nv());
        }
        return fmt::format("rigid.robot.Robot('{}', dof={})", t.model().source, t.dof());
      });
}
