// rigid.spring: the stiff body, point masses joined by linear springs (the physical model of a
// rigid body as the stiffness grows), stepped by the implicit midpoint rule. Positions and
// velocities are (n, 3) arrays, one particle per row, in the world frame W.
#include <fmt/format.h>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include "convert.hpp"
#include "interrupt.hpp"
#include "rigid/common/error.hpp"
#include "rigid/spring.hpp"

namespace py = pybind11;
namespace cv = rigid::python::convert;

namespace {

using rigid::spring::Network;
using rigid::spring::Spring;

// (n, 3) rows of a 3 × n matrix of columns (the library's layout)
Eigen::MatrixXd rows_of(const Eigen::Matrix3Xd& columns) { return columns.transpose(); }

rigid::spring::MidpointOptions midpoint_options(int max_iterations, double tolerance) {
  if (max_iterations < 1) {
    throw rigid::Error(
        fmt::format("rigid.spring: max_iterations must be at least 1, got {}", max_iterations));
  }
  if (!(std::isfinite(tolerance) && tolerance > 0)) {
    throw rigid::Error(
        fmt::format("rigid.spring: tolerance must be positive and finite, got {}", tolerance));
  }
  return {.max_iterations = max_iterations, .tolerance = tolerance};
}

}  // namespace

void bind_spring(py::module_& m) {
  auto spring =
      m.def_submodule("spring",
                      "The stiff body: point masses joined by linear springs, the physical model "
                      "of a rigid body as the stiffness k → ∞ (docs/body.md).");

  py::class_<Network>(spring, "Network",
                      "Particles (mass kg, position m and velocity m/s in the world frame, one per "
                      "row) joined by springs (i, j, stiffness N/m, rest length m).")
      .def(py::init([](const py::object& mass, const py::object& position,
                       const py::object& velocity,
                       const std::vector<std::tuple<int, int, double, double>>& springs) {
             const char* f = "rigid.spring.Network";
             Network net;
             net.mass = cv::vector(mass, {f, "mass"});
             const Eigen::Index n = net.mass.size();
             net.position = cv::points(position, {f, "position"});
             net.velocity = cv::points(velocity, {f, "velocity"});
             if (net.position.cols() != n || net.velocity.cols() != n) {
               throw rigid::Error(
                   fmt::format("{}(): {} masses, {} positions and {} velocities; expected one "
                               "of each per particle",
                               f, n, net.position.cols(), net.velocity.cols()));
             }
             for (Eigen::Index i = 0; i < n; ++i) {
               if (!(net.mass(i) > 0)) {
                 throw rigid::Error(fmt::format("{}(): mass[{}] = {} kg; expected a positive mass",
                                                f, i, net.mass(i)));
               }
             }
             for (std::size_t k = 0; k < springs.size(); ++k) {
               const auto& [i, j, stiffness, rest] = springs[k];
               if (i < 0 || j < 0 || i >= n || j >= n || i == j) {
                 throw rigid::Error(
                     fmt::format("{}(): spring {} joins particles {} and {}; expected two "
                                 "different particles from 0 to {}",
                                 f, k, i, j, n - 1));
               }
               if (!(std::isfinite(stiffness) && stiffness > 0) ||
                   !(std::isfinite(rest) && rest >= 0)) {
                 throw rigid::Error(
                     fmt::format("{}(): spring {} has stiffness {} N/m and rest length {} m; "
                                 "expected a positive stiffness and a rest length ≥ 0",
                                 f, k, stiffness, rest));
               }
               net.springs.push_back(
                   Spring{.i = i, .j = j, .stiffness = stiffness, .rest_length = rest});
             }
             return net;
           }),
           py::arg("mass"), py::arg("position"), py::arg("velocity"), py::arg("springs"),
           "mass (n,) kg; position, velocity (n, 3) in m and m/s, one particle per row, world "
           "frame; springs: [(i, j, stiffness N/m, rest_length m)].")
      .def_property_readonly(
          "mass", [](const Network& net) { return net.mass; }, "Masses (kg), shape (n,).")
      .def_property_readonly(
          "position", [](const Network& net) { return rows_of(net.position); },
          "Positions (m, world), shape (n, 3).")
      .def_property_readonly(
          "velocity", [](const Network& net) { return rows_of(net.velocity); },
          "Velocities (m/s, world), shape (n, 3).")
      .def_property_readonly(
          "springs",
          [](const Network& net) {
            std::vector<std::tuple<int, int, double, double>> out;
            for (const Spring& s : net.springs)
              out.emplace_back(s.i, s.j, s.stiffness, s.rest_length);
            return out;
          },
          "[(i, j, stiffness N/m, rest_length m)].")
      .def(
          "forces", [](const Network& net) { return rows_of(rigid::spring::spring_forces(net)); },
          "Spring forces on every particle (N, world), shape (n, 3).")
      .def("energy", &rigid::spring::network_energy,
           "Total energy (J): kinetic + spring potential.")
      .def(
          "step",
          [](Network& net, double h, int max_iterations, double tolerance) {
            if (!(std::isfinite(h) && h > 0)) {
              throw rigid::Error(
                  fmt::format("Network.step(): step h must be positive and finite, got {} s", h));
            }
            rigid::spring::step_implicit_midpoint(net, h,
                                                  midpoint_options(max_iterations, tolerance));
          },
          py::arg("h"), py::arg("max_iterations") = 50, py::arg("tolerance") = 1e-15,
          "Advances the network in place by one implicit-midpoint step of size h (s): Newton on "
          "the stage positions with the exact stiffness matrix, A-stable (h is not limited by "
          "√(m/k)); keeps linear and angular momentum up to the Newton tolerance (a correction at "
          "most tolerance·(1 + max|p|), m). Raises rigid.Error, leaving the network unchanged, if "
          "Newton does not converge.")
      .def(
          "simulate",
          [](const Network& net, double h_max, const py::object& times, int max_iterations,
             double tolerance) {
            const std::vector<double> out_times = cv::values(times, {"Network.simulate", "times"});
            const auto options = midpoint_options(max_iterations, tolerance);
            rigid::python::Interruptible interrupt;
            rigid::spring::NetworkTrajectory tr;
            {
              py::gil_scoped_release release;
              tr = rigid::spring::simulate_network(net, h_max, out_times, interrupt.control(),
                                                   options);
            }
            const auto rows = static_cast<py::ssize_t>(tr.t.size());
            const auto n = static_cast<py::ssize_t>(net.mass.size());
            py::array_t<double> p({rows, n, py::ssize_t{3}}), v({rows, n, py::ssize_t{3}});
            auto pw = p.mutable_unchecked<3>();
            auto vw = v.mutable_unchecked<3>();
            for (py::ssize_t k = 0; k < rows; ++k) {
              const auto& P = tr.position[static_cast<std::size_t>(k)];
              const auto& V = tr.velocity[static_cast<std::size_t>(k)];
              for (py::ssize_t i = 0; i < n; ++i) {
                for (py::ssize_t d = 0; d < 3; ++d) {
                  pw(k, i, d) = P(d, i);
                  vw(k, i, d) = V(d, i);
                }
              }
            }
            py::dict out;
            out["t"] = cv::array(tr.t);
            out["position"] = p;
            out["velocity"] = v;
            out["energy"] = cv::array(tr.energy);
            return out;
          },
          py::arg("h_max"), py::arg("times"), py::arg("max_iterations") = 50,
          py::arg("tolerance") = 1e-15,
          "Integrates from t = 0 by implicit-midpoint steps (the fewest equal steps ≤ h_max, s, "
          "between output times) and samples at `times` (s, ascending): a dict with t, position "
          "and velocity (shape (len(times), n, 3), m and m/s, world) and energy (J). Releases the "
          "GIL; Ctrl-C raises KeyboardInterrupt.")
      .def("__repr__", [](const Network& net) {
        return fmt::format("Network(particles={}, springs={}, mass={:.6g} kg)",
                           net.mass.size(), net.springs.size(), net.mass.sum());
      });

  spring.def(
      "network_with_inertia", &rigid::spring::network_with_inertia, py::arg("mass_properties"),
      py::arg("stiffness"),
      "Six particles of mass m/6 at C ± a_i e_i along the principal axes of the body (its frame "
      "B taken as the world at t = 0), at rest, with the body's mass, COM and inertia about "
      "the COM, joined by all 15 springs of stiffness (N/m) at their rest lengths. Needs "
      "I_i < I_j + I_k strictly (a flat body cannot be spanned by six particles).");
}
