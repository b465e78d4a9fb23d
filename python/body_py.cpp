// rigid.body: exact free rigid body, free-body steppers, the general rigid body and the heavy
// top. Long runs without Python callbacks release the GIL and stop on Ctrl-C
// (KeyboardInterrupt).
#include <string>
#include <vector>

#include <fmt/format.h>

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "interrupt.hpp"
#include "rigid/body.hpp"
#include "rigid/body/rigid_body.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"

namespace py = pybind11;

namespace {

using rigid::SO3d;

// q_wxyz arguments must be unit quaternions (within 1e-9, as a scene's initial_quaternion)
SO3d rotation_of(const Eigen::Vector4d& q_wxyz) {
  return SO3d::from_unit_quaternion(q_wxyz(0), q_wxyz(1), q_wxyz(2), q_wxyz(3), 1e-9);
}

// The trajectory of a free body or a heavy top as numpy arrays.
py::dict free_trajectory(const rigid::body::FreeBodyTrajectory& traj) {
  const auto n = static_cast<Eigen::Index>(traj.t.size());
  Eigen::MatrixXd q(n, 4), w(n, 3), L(n, 3);
  Eigen::VectorXd E(n), ortho(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto& st = traj.states[static_cast<std::size_t>(i)];
    const auto& d = traj.diagnostics[static_cast<std::size_t>(i)];
    q.row(i) = st.R_WB.quaternion().transpose();
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
}

// rigid.body.RigidBody: mass properties, gravity and Python loads; simulate() returns the
// sampled trajectory as numpy arrays. With Python loads the GIL stays held (the loads run
// Python); without, it is released.
void bind_rigid_body(py::module_& body) {
  using rigid::body::RigidBody;
  using rigid::body::RigidBodyState;
  py::class_<RigidBody>(body, "RigidBody",
                        "A rigid body: mass properties (a rigid.MassProperties in the body frame B, "
                        "or mass in kg and the inertia about the COM in kg·m², any symmetric "
                        "tensor), uniform gravity (m/s²) and applied loads. The state follows the COM.")
      .def(py::init<const rigid::MassProperties&, const Eigen::Vector3d&>(), py::arg("mass_properties"),
           py::arg("gravity") = Eigen::Vector3d::Zero(),
           "From mass properties in the body frame B (any origin; the state follows the COM) and "
           "uniform gravity in the world frame (m/s²).")
      .def(py::init<double, const Eigen::Matrix3d&, const Eigen::Vector3d&>(), py::arg("mass"),
           py::arg("inertia"), py::arg("gravity") = Eigen::Vector3d::Zero(),
           "From the mass (kg) and the inertia about the COM in the body frame (kg·m², any symmetric "
           "physical tensor), and uniform gravity in the world frame (m/s²).")
      .def(
          "add_load",
          [](RigidBody& b, py::function fn, const std::string& frame, const Eigen::Vector3d& point) {
            if (frame != "world" && frame != "body") {
              throw rigid::Error(fmt::format("RigidBody.add_load(): frame must be 'world' or 'body', got '{}'", frame));
            }
            rigid::body::AppliedLoad load;
            load.frame = frame == "world" ? rigid::body::LoadFrame::kWorld : rigid::body::LoadFrame::kBody;
            load.p_CQ_B = point;
            load.wrench = [fn](double t, const RigidBodyState& st) {
              py::gil_scoped_acquire gil;  // a no-op when it is held already
              const Eigen::Vector4d q = st.R_WB.quaternion();
              py::dict state;
              state["q_wxyz"] = q;
              state["omega_body"] = st.w_B;
              state["p_world"] = st.p_WC;
              state["v_world"] = st.v_WC;
              const auto fw = fn(t, state).cast<std::pair<Eigen::Vector3d, Eigen::Vector3d>>();
              return rigid::body::Wrench{fw.first, fw.second};
            };
            b.add_load(std::move(load));
          },
          py::arg("wrench"), py::arg("frame") = "world", py::arg("point") = Eigen::Vector3d::Zero(),
          "Adds a load: wrench(t, state) -> (force N, torque N·m) in `frame` ('world' or 'body'); "
          "the force acts at the body point `point` (from the COM, body frame, m). `state` is a "
          "dict with q_wxyz, omega_body, p_world, v_world.")
      .def_property_readonly("mass", &RigidBody::mass, "Mass (kg).")
      .def_property_readonly("com", &RigidBody::com, "COM in the body frame (m).")
      .def_property_readonly("principal_moments", &RigidBody::principal_moments,
                             "Principal moments of inertia about the COM, ascending (kg·m²).")
      .def(
          "simulate",
          [](const RigidBody& b, const std::string& method, const Eigen::Vector4d& q_wxyz,
             const Eigen::Vector3d& w_B, const Eigen::Vector3d& p, const Eigen::Vector3d& v, double h_max,
             const std::vector<double>& times, const std::string& free_method) {
            RigidBodyState s;
            s.R_WB = rotation_of(q_wxyz);
            s.w_B = w_B;
            s.p_WC = p;
            s.v_WC = v;
            const auto m = rigid::body::rigid_body_method_from_name(method);
            const auto fm = rigid::body::free_body_method_from_name(free_method);
            rigid::python::Interruptible interrupt;
            rigid::body::RigidBodyTrajectory tr;
            if (b.load_count() > 0) {  // the loads are Python: keep the GIL
              tr = rigid::body::simulate_rigid_body(b, m, s, h_max, times, fm, interrupt.control());
            } else {
              py::gil_scoped_release release;
              tr = rigid::body::simulate_rigid_body(b, m, s, h_max, times, fm, interrupt.control());
            }
            const auto n = static_cast<Eigen::Index>(tr.t.size());
            Eigen::MatrixXd q(n, 4), w(n, 3), pw(n, 3), vw(n, 3), P(n, 3), L(n, 3);
            Eigen::VectorXd E(n);
            for (Eigen::Index i = 0; i < n; ++i) {
              const auto& st = tr.states[static_cast<std::size_t>(i)];
              const auto& d = tr.diagnostics[static_cast<std::size_t>(i)];
              q.row(i) = st.R_WB.quaternion().transpose();
              w.row(i) = st.w_B.transpose();
              pw.row(i) = st.p_WC.transpose();
              vw.row(i) = st.v_WC.transpose();
              P.row(i) = d.P_W.transpose();
              L.row(i) = d.L_W.transpose();
              E(i) = d.energy;
            }
            py::dict out;
            out["t"] = tr.t;
            out["q_wxyz"] = q;
            out["omega_body"] = w;
            out["p_world"] = pw;
            out["v_world"] = vw;
            out["momentum_world"] = P;
            out["angular_momentum_world"] = L;
            out["energy"] = E;
            return out;
          },
          py::arg("method"), py::arg("q_wxyz"), py::arg("omega_body"), py::arg("p_world"),
          py::arg("v_world"), py::arg("h_max"), py::arg("times"), py::arg("free_method") = "splitting2",
          "Integrates from t = 0 (method: splitting2 or rk4) and samples at `times` (s): initial "
          "orientation R_WB as a unit quaternion (w, x, y, z), body angular velocity omega_body (rad/s, "
          "body frame), COM position p_world (m) and velocity v_world (m/s) in the world frame, largest "
          "step h_max (s). Returns a dict of arrays, one row per sample: t, q_wxyz, omega_body, p_world, "
          "v_world, momentum_world (kg·m/s), angular_momentum_world (about the world origin, kg·m²/s), "
          "energy (J).")
      .def("__repr__", [](const RigidBody& b) {
        return fmt::format("RigidBody(mass={} kg, principal_moments={} kg·m², loads={})", b.mass(),
                           rigid::to_string(b.principal_moments().transpose()), b.load_count());
      });
}

void bind_heavy_top(py::module_& body) {
  using rigid::body::HeavyTop;
  py::class_<HeavyTop>(body, "HeavyTop",
                       "A rigid body on a fixed frictionless pivot in uniform gravity: its mass "
                       "properties in the body frame B, the pivot in B (m), gravity (m/s²).")
      .def(py::init<const rigid::MassProperties&, const Eigen::Vector3d&, const Eigen::Vector3d&>(),
           py::arg("mass_properties"), py::arg("pivot"), py::arg("gravity") = Eigen::Vector3d(0, 0, -9.81),
           "From mass properties in the body frame B, the pivot point in B (m, from B's origin) and "
           "uniform gravity in the world frame (m/s²).")
      .def_property_readonly("mass", &HeavyTop::mass, "Mass (kg).")
      .def_property_readonly("inertia_about_pivot", &HeavyTop::inertia_about_pivot,
                             "Inertia about the pivot, in the body frame (kg·m²).")
      .def_property_readonly("com_from_pivot", &HeavyTop::com_from_pivot,
                             "COM position from the pivot, in the body frame (m).")
      .def(
          "energy",
          [](const HeavyTop& top, const Eigen::Vector4d& q_wxyz, const Eigen::Vector3d& w_B) {
            return top.energy({rotation_of(q_wxyz), w_B});
          },
          py::arg("q_wxyz"), py::arg("omega_body"),
          "Kinetic + gravitational energy (J) at orientation R_WB (unit quaternion w, x, y, z) and body "
          "angular velocity omega_body (rad/s, body frame): ½ ωᵀ I_pivot ω − m g · (R_WB p_pivot→COM).")
      .def(
          "simulate",
          [](const HeavyTop& top, const Eigen::Vector4d& q_wxyz, const Eigen::Vector3d& w_B, double h_max,
             const std::vector<double>& times, const std::string& free_method) {
            const auto fm = rigid::body::free_body_method_from_name(free_method);
            rigid::python::Interruptible interrupt;
            rigid::body::FreeBodyTrajectory traj;
            {
              py::gil_scoped_release release;
              traj = top.simulate({rotation_of(q_wxyz), w_B}, h_max, times, fm, interrupt.control());
            }
            return free_trajectory(traj);
          },
          py::arg("q_wxyz"), py::arg("omega_body"), py::arg("h_max"), py::arg("times"),
          py::arg("free_method") = "splitting2",
          "Integrates by the gravity-kick splitting around the free flow (free_method splitting2/4/6) "
          "from orientation R_WB (unit quaternion w, x, y, z) and body angular velocity omega_body "
          "(rad/s, body frame), largest step h_max (s); returns a dict of arrays sampled at `times` "
          "(s): t, q_wxyz, omega_body, L_world (about the pivot, kg·m²/s), energy (J), "
          "orthonormality_error.")
      .def("__repr__", [](const HeavyTop& top) {
        return fmt::format("HeavyTop(mass={} kg, com_from_pivot={} m, inertia_about_pivot={} kg·m²)", top.mass(),
                           rigid::to_string(top.com_from_pivot().transpose()),
                           rigid::to_string(top.inertia_about_pivot()));
      });
}

}  // namespace

void bind_body(py::module_& m) {
  auto body = m.def_submodule("body", "Rigid-body dynamics on SO(3): exact free body, integrators, SO(n).");
  py::class_<rigid::body::FreeBodyExact>(body, "FreeBodyExact",
                                         "Exact torque-free body angular velocity (Jacobi elliptic functions).")
      .def(py::init<const Eigen::Vector3d&, const Eigen::Vector3d&>(), py::arg("principal_moments"),
           py::arg("omega_body"),
           "From the principal moments (kg·m²) and the initial angular velocity in the principal "
           "body frame (rad/s).")
      .def("omega_body", &rigid::body::FreeBodyExact::omega_body, py::arg("t"), "Body angular velocity at t (s).")
      .def_property_readonly("period", &rigid::body::FreeBodyExact::period,
                             "Period of ω(t) (s; inf when ω is constant or on the separatrix).")
      .def_property_readonly("modulus", &rigid::body::FreeBodyExact::modulus,
                             "Elliptic modulus k (0 for a symmetric body, 1 on the separatrix).")
      .def_property_readonly("energy", &rigid::body::FreeBodyExact::energy,
                             "Kinetic energy ½ ωᵀIω (J), constant.")
      .def_property_readonly("angular_momentum_norm", &rigid::body::FreeBodyExact::angular_momentum_norm,
                             "|L| (kg·m²/s), constant.")
      .def("__repr__", [](const rigid::body::FreeBodyExact& e) {
        return fmt::format("FreeBodyExact(energy={} J, angular_momentum_norm={} kg·m²/s, modulus={}, period={} s)",
                           e.energy(), e.angular_momentum_norm(), e.modulus(), e.period());
      });
  py::class_<rigid::body::FreeBodyMotion>(
      body, "FreeBodyMotion",
      "Exact torque-free motion: orientation R_WB(t) and body angular velocity in closed form.")
      .def(py::init([](const Eigen::Vector3d& I_B, const Eigen::Vector4d& q_wxyz, const Eigen::Vector3d& w_B) {
             return rigid::body::FreeBodyMotion(I_B, rotation_of(q_wxyz), w_B);
           }),
           py::arg("principal_moments"), py::arg("q_wxyz"), py::arg("omega_body"),
           "The motion of a body in its principal frame B: principal moments (kg·m²), initial "
           "orientation R_WB as a unit quaternion (w, x, y, z), initial body angular velocity (rad/s).")
      .def(py::init([](const rigid::MassProperties& mp, const Eigen::Vector4d& q_wxyz, const Eigen::Vector3d& w_B) {
             return rigid::body::FreeBodyMotion(mp, rotation_of(q_wxyz), w_B);
           }),
           py::arg("mass_properties"), py::arg("q_wxyz"), py::arg("omega_body"),
           "The motion of a body with these mass properties in any body frame.")
      .def(
          "orientation",
          [](const rigid::body::FreeBodyMotion& motion, double t) {
            return Eigen::Vector4d(motion.orientation(t).quaternion());
          },
          py::arg("t"), "Orientation R_WB(t) as a quaternion (w, x, y, z).")
      .def("omega_body", &rigid::body::FreeBodyMotion::omega_body, py::arg("t"), "Body angular velocity at t (s).")
      .def_property_readonly("angular_momentum_world", &rigid::body::FreeBodyMotion::angular_momentum_world,
                             "Angular momentum about the COM in the world frame (kg·m²/s), constant.")
      .def_property_readonly("period", [](const rigid::body::FreeBodyMotion& motion) { return motion.omega_solution().period(); },
                             "Period of the body angular velocity (s).")
      .def_property_readonly("modulus", [](const rigid::body::FreeBodyMotion& motion) { return motion.omega_solution().modulus(); },
                             "Elliptic modulus k of the body angular velocity's solution.")
      .def("__repr__", [](const rigid::body::FreeBodyMotion& motion) {
        return fmt::format("FreeBodyMotion(angular_momentum_world={} kg·m²/s, period={} s, modulus={})",
                           rigid::to_string(motion.angular_momentum_world().transpose()),
                           motion.omega_solution().period(), motion.omega_solution().modulus());
      });
  body.def(
      "simulate_free_body",
      [](const std::string& method, const Eigen::Vector3d& I_B, const Eigen::Vector4d& q_wxyz,
         const Eigen::Vector3d& w_B, double h_max, const std::vector<double>& times) {
        const rigid::body::FreeBodyState s{rotation_of(q_wxyz), w_B};
        const auto stepper = rigid::body::free_body_method_from_name(method);
        rigid::python::Interruptible interrupt;
        rigid::body::FreeBodyTrajectory traj;
        {
          py::gil_scoped_release release;
          traj = rigid::body::simulate_free_body(stepper, I_B, s, h_max, times, interrupt.control());
        }
        return free_trajectory(traj);
      },
      py::arg("method"), py::arg("principal_moments"), py::arg("q_wxyz"), py::arg("omega_body"),
      py::arg("h_max"), py::arg("times"),
      "Integrate a torque-free body in its principal frame (method: rk4, splitting2, splitting4, "
      "splitting6, midpoint, rkmk4, moser_veselov): principal moments (kg·m²), initial orientation "
      "R_WB (unit quaternion w, x, y, z), body angular velocity omega_body (rad/s), largest step h_max "
      "(s); returns a dict of arrays sampled at `times` (s): t, q_wxyz, omega_body, L_world "
      "(kg·m²/s), energy (J), orthonormality_error.");

  bind_rigid_body(body);
  bind_heavy_top(body);
}
