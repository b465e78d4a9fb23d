// rigid.body: exact free rigid body and free-body steppers.
#include <string>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "rigid/body.hpp"

namespace py = pybind11;

void bind_body(py::module_& m) {
  auto body = m.def_submodule("body", "Rigid-body dynamics on SO(3): exact free body, integrators, SO(n).");
  py::class_<rigid::body::FreeBodyExact>(body, "FreeBodyExact",
                                         "Exact torque-free body angular velocity (Jacobi elliptic functions).")
      .def(py::init<const Eigen::Vector3d&, const Eigen::Vector3d&>(), py::arg("principal_moments"),
           py::arg("omega_body"))
      .def("omega_body", &rigid::body::FreeBodyExact::omega_body, py::arg("t"), "Body angular velocity at t (s).")
      .def_property_readonly("period", &rigid::body::FreeBodyExact::period)
      .def_property_readonly("modulus", &rigid::body::FreeBodyExact::modulus)
      .def_property_readonly("energy", &rigid::body::FreeBodyExact::energy)
      .def_property_readonly("angular_momentum_norm", &rigid::body::FreeBodyExact::angular_momentum_norm);
  py::class_<rigid::body::FreeBodyMotion>(
      body, "FreeBodyMotion",
      "Exact torque-free motion: orientation q_WB(t) and body angular velocity in closed form.")
      .def(py::init([](const Eigen::Vector3d& I_B, const Eigen::Vector4d& q_wxyz, const Eigen::Vector3d& w_B) {
             return rigid::body::FreeBodyMotion(I_B, Eigen::Quaterniond(q_wxyz(0), q_wxyz(1), q_wxyz(2), q_wxyz(3)),
                                                w_B);
           }),
           py::arg("principal_moments"), py::arg("q_wxyz"), py::arg("omega_body"))
      .def(
          "orientation",
          [](const rigid::body::FreeBodyMotion& motion, double t) {
            const Eigen::Quaterniond q = motion.orientation(t);
            return Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
          },
          py::arg("t"), "Orientation q_WB(t) as (w, x, y, z).")
      .def("omega_body", &rigid::body::FreeBodyMotion::omega_body, py::arg("t"), "Body angular velocity at t (s).")
      .def_property_readonly("angular_momentum_world", &rigid::body::FreeBodyMotion::angular_momentum_world)
      .def_property_readonly("period", [](const rigid::body::FreeBodyMotion& motion) { return motion.omega_solution().period(); })
      .def_property_readonly("modulus", [](const rigid::body::FreeBodyMotion& motion) { return motion.omega_solution().modulus(); });
  body.def(
      "simulate_free_body",
      [](const std::string& method, const Eigen::Vector3d& I_B, const Eigen::Vector4d& q_wxyz,
         const Eigen::Vector3d& w_B, double h_max, const std::vector<double>& times) {
        rigid::body::FreeBodyState s;
        s.q_WB = Eigen::Quaterniond(q_wxyz(0), q_wxyz(1), q_wxyz(2), q_wxyz(3));
        s.w_B = w_B;
        const auto traj = rigid::body::simulate_free_body(rigid::body::free_body_method_from_name(method), I_B,
                                                          s, h_max, times);
        const auto n = static_cast<Eigen::Index>(traj.t.size());
        Eigen::MatrixXd q(n, 4), w(n, 3), L(n, 3);
        Eigen::VectorXd E(n), ortho(n);
        for (Eigen::Index i = 0; i < n; ++i) {
          const auto& st = traj.states[static_cast<std::size_t>(i)];
          const auto& d = traj.diagnostics[static_cast<std::size_t>(i)];
          q.row(i) << st.q_WB.w(), st.q_WB.x(), st.q_WB.y(), st.q_WB.z();
          w.row(i) = st.w_B.transpose();
          L.row(i) = d.L_W.transpose();
          E(i) = d.energy;
          ortho(i) = d.orthonormality_error;
        }
        py::dict out;
        out["t"] = traj.t;
        out["q_wxyz"] = q;
        out["omega_body"] = w;
        out["L_world"] = L;
        out["energy"] = E;
        out["orthonormality_error"] = ortho;
        return out;
      },
      py::arg("method"), py::arg("principal_moments"), py::arg("q_wxyz"), py::arg("omega_body"),
      py::arg("h_max"), py::arg("times"),
      "Integrate a free body (method: rk4, splitting2, splitting4, splitting6, midpoint, rkmk4, moser_veselov); "
      "returns a dict of "
      "arrays sampled at `times`.");
}
