// rigid.robot.Robot's inverse-dynamics regressor and base parameters (rigid/robot/regressor.hpp,
// docs/robots.md#regressor-and-base-parameters): methods added to the class bind_robot defines,
// and the class rigid.robot.BaseParameters. Arrays are numpy; Y's columns are in
// standard_parameters()'s order.
#include <fmt/format.h>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "convert.hpp"
#include "rigid/robot/regressor.hpp"
#include "rigid/robot/tree_dynamics.hpp"

namespace py = pybind11;
namespace cv = rigid::python::convert;

namespace {

using rigid::robot::BaseParameters;
using rigid::robot::TreeDynamics;

std::vector<std::string> names_of(const BaseParameters& b, const std::vector<std::size_t>& idx) {
  std::vector<std::string> out;
  for (std::size_t i : idx) out.push_back(b.standard.names[i]);
  return out;
}

}  // namespace

void bind_robot_regressor(py::module_& m) {
  py::module_ robot = m.attr("robot");
  py::class_<BaseParameters>(
      robot, "BaseParameters",
      "The base (identifiable) parameters of a robot's inverse dynamics: beta = C pi, "
      "tau = Y_b beta with Y_b = Y[:, independent_columns] (Robot.base_parameters).")
      .def_property_readonly(
          "rank", [](const BaseParameters& b) { return b.rank; },
          "r: the number of base parameters.")
      .def_property_readonly(
          "names",
          [](const BaseParameters& b) {
            std::vector<std::string> out;
            for (std::size_t i = 0; i < b.rank; ++i) out.push_back(b.name(i));
            return out;
          },
          "beta_1 … beta_r.")
      .def_property_readonly(
          "expressions",
          [](const BaseParameters& b) {
            std::vector<std::string> out;
            for (std::size_t i = 0; i < b.rank; ++i) out.push_back(b.expression(i));
            return out;
          },
          "Each base parameter as a combination of the named standard parameters.")
      .def_property_readonly(
          "values", [](const BaseParameters& b) { return b.values; },
          "beta of the model (r,), SI units of each one's independent parameter.")
      .def_property_readonly(
          "combination", [](const BaseParameters& b) { return b.combination; },
          "C (r, p): beta = C pi, pi in standard_names' order.")
      .def_property_readonly(
          "standard_names", [](const BaseParameters& b) { return b.standard.names; },
          "The p standard parameters' names (pi's order).")
      .def_property_readonly(
          "standard_values", [](const BaseParameters& b) { return b.standard.values; },
          "pi of the model (p,).")
      .def_property_readonly(
          "independent_columns",
          [](const BaseParameters& b) {
            return std::vector<std::size_t>(b.independent.begin(), b.independent.end());
          },
          "The r columns of Y that form Y_b (indices into pi).")
      .def_property_readonly(
          "independent", [](const BaseParameters& b) { return names_of(b, b.independent); },
          "The standard parameters each base parameter is led by (coefficient 1).")
      .def_property_readonly(
          "dependent", [](const BaseParameters& b) { return names_of(b, b.dependent); },
          "The standard parameters grouped into the base parameters (their columns are "
          "combinations of the independent ones).")
      .def_property_readonly(
          "unidentifiable", [](const BaseParameters& b) { return names_of(b, b.unidentifiable); },
          "The standard parameters that do not move tau at all.")
      .def("__repr__", [](const BaseParameters& b) {
        return fmt::format("rigid.robot.BaseParameters(rank={}, standard={})", b.rank,
                           b.standard.values.size());
      });

  auto cls = py::reinterpret_borrow<py::class_<TreeDynamics, std::shared_ptr<TreeDynamics>>>(
      robot.attr("Robot"));
  cls.def(
         "standard_parameters",
         [](const TreeDynamics& t) {
           const rigid::robot::StandardParameters s = rigid::robot::standard_parameters(t.model());
           return py::make_tuple(s.names, s.values);
         },
         "(names, values): the standard parameters pi, per link m, mx, my, mz, Ixx, Ixy, Ixz, "
         "Iyy, Iyz, Izz in the link frame about its origin, per joint Ia, fv, k (SI units).")
      .def(
          "regressor",
          [](const TreeDynamics& t, const py::object& q, const py::object& q_dot,
             const py::object& q_ddot) {
            const char* f = "rigid.robot.Robot.regressor";
            const auto nq = static_cast<Eigen::Index>(t.nq()), nv = static_cast<Eigen::Index>(t.nv());
            // the sizes named as the other methods name them: dof where nq = nv
            const char* q_size = nq == nv ? "dof" : "nq";
            const char* v_size = nq == nv ? "dof" : "nv";
            return rigid::robot::regressor(
                t.model(), cv::vector(q, {f, "q"}, nq, cv::Finite::kRequired, q_size),
                cv::vector(q_dot, {f, "q_dot"}, nv, cv::Finite::kRequired, v_size),
                cv::vector(q_ddot, {f, "q_ddot"}, nv, cv::Finite::kRequired, v_size));
          },
          py::arg("q"), py::arg("q_dot"), py::arg("q_ddot"),
          "Y (nv, p): tau = Y pi for the standard parameters pi (gravity and the joints' "
          "passive forces included). q has nq entries (a ball's or free joint's unit quaternion "
          "among them), q_dot and q_ddot nv (MuJoCo's qpos and qvel, as inverse_dynamics).")
      .def(
          "base_parameters",
          [](const TreeDynamics& t, std::size_t samples, std::uint64_t seed,
             double rank_tolerance) {
            return rigid::robot::base_parameters(
                t.model(), {.samples = samples, .seed = seed, .rank_tolerance = rank_tolerance});
          },
          py::kw_only(), py::arg("samples") = 0,
          py::arg("seed") = rigid::robot::BaseParameterOptions{}.seed,
          py::arg("rank_tolerance") = rigid::robot::BaseParameterOptions{}.rank_tolerance,
          "The base parameters (BaseParameters) by a QR of Y stacked at `samples` random states "
          "(0: automatic) drawn from `seed`; a column is independent when its distance to the "
          "others exceeds rank_tolerance of the largest column norm.");
}
