// rigid.body: exact free rigid body, free-body steppers, the general rigid body and the heavy
// top. Long runs without Python callbacks release the GIL and stop on Ctrl-C
// (KeyboardInterrupt).
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "interrupt.hpp"
#include "rigid/body.hpp"
#include "rigid/body/euler.hpp"
#include "rigid/body/euler_arnold.hpp"
#include "rigid/body/free_body_batch.hpp"
#include "rigid/body/rigid_body.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"
#include "rigid/common/wording.hpp"

namespace py = pybind11;
namespace cv = rigid::python::convert;

namespace {

using rigid::SO3d;

// q_wxyz arguments must be unit quaternions (within 1e-9, as a scene's initial_quaternion).
// One that is unit to 1e-12 (what a step returned) is taken as it is, not normalised again, so
// that steps chained from Python give the library's trajectory bit for bit.
SO3d rotation_of(const Eigen::Vector4d& q_wxyz) {
  if (std::abs(q_wxyz.norm() - 1.0) <= 1e-12) {
    return SO3d::from_unit_quaternion(q_wxyz(0), q_wxyz(1), q_wxyz(2), q_wxyz(3));
  }
  return SO3d::from_unit_quaternion(q_wxyz(0), q_wxyz(1), q_wxyz(2), q_wxyz(3), 1e-9);
}

// A q_wxyz argument: shape (4,), finite, a unit quaternion within 1e-9; refusals name it.
SO3d rotation_arg(const py::handle& q, const cv::Arg& arg) {
  const Eigen::Vector4d v = cv::vector4(q, arg);
  try {
    return rotation_of(v);
  } catch (const rigid::Error& e) {
    throw rigid::Error(fmt::format("{}(): argument '{}': {}", arg.function, arg.name,
                                   rigid::strip_function_names(e.what())));
  }
}

// Principal moments (kg·m²) of a body that turns: shape (3,), rigid::check_rotational_moments.
Eigen::Vector3d moments_arg(const py::handle& I, const cv::Arg& arg) {
  const Eigen::Vector3d v = cv::vector3(I, arg);
  if (const auto why = rigid::check_rotational_moments(v)) {
    throw rigid::Error(fmt::format("{}(): argument '{}': {}", arg.function, arg.name, *why));
  }
  return v;
}

// A time t (s) from Python: a number (TypeError naming it otherwise), finite (rigid.Error).
double time_arg(const py::object& t, const cv::Arg& arg) {
  const double v = cv::number(t, arg);
  if (!std::isfinite(v)) cv::refuse(arg, fmt::format("must be a finite time (s); got {}", v));
  return v;
}

// f() with a library refusal (a time too far for the closed form) prefixed by the Python
// function and the argument 't'.
template <class F>
auto at_time(const cv::Arg& arg, F f) {
  try {
    return f();
  } catch (const rigid::Error& e) {
    throw rigid::Error(fmt::format("{}(): argument '{}': {}", arg.function, arg.name,
                                   rigid::strip_function_names(e.what())));
  }
}

// A step h (s): positive and finite.
double step_arg(double h, std::string_view function) {
  if (!(std::isfinite(h) && h > 0)) {
    throw rigid::Error(fmt::format("{}(): step h must be positive and finite, got {} s", function, h));
  }
  return h;
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
  out["t"] = cv::array(traj.t);
  out["q_wxyz"] = q;
  out["omega_body"] = w;
  out["L_world"] = L;
  out["energy"] = E;
  out["orthonormality_error"] = ortho;
  return out;
}

// The state dict of a rigid body (what RigidBody.step returns and takes).
py::dict state_dict(const rigid::body::RigidBodyState& st) {
  py::dict d;
  d["q_wxyz"] = Eigen::Vector4d(st.R_WB.quaternion());
  d["omega_body"] = st.w_B;
  d["p_world"] = st.p_WC;
  d["v_world"] = st.v_WC;
  return d;
}

rigid::body::RigidBodyState state_of(std::string_view f, const py::object& q, const py::object& w,
                                     const py::object& p, const py::object& v) {
  rigid::body::RigidBodyState s;
  s.R_WB = rotation_arg(q, {f, "q_wxyz"});
  s.w_B = cv::vector3(w, {f, "omega_body"});
  s.p_WC = cv::vector3(p, {f, "p_world"});
  s.v_WC = cv::vector3(v, {f, "v_world"});
  return s;
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
      .def(py::init([](const rigid::MassProperties& mp, const py::object& gravity) {
             return RigidBody(mp, cv::vector3(gravity, {"rigid.body.RigidBody", "gravity"}));
           }),
           py::arg("mass_properties"), py::arg("gravity") = py::make_tuple(0.0, 0.0, 0.0),
           "A body with these mass properties (frame B, any origin) in uniform gravity g_W (m/s², "
           "world frame). Raises rigid.Error for a principal moment 0 (a point mass, a thin rod).")
      .def(py::init([](double mass, const py::object& inertia, const py::object& gravity) {
             const char* f = "rigid.body.RigidBody";
             return RigidBody(mass, cv::matrix3(inertia, {f, "inertia"}), cv::vector3(gravity, {f, "gravity"}));
           }),
           py::arg("mass"), py::arg("inertia"), py::arg("gravity") = py::make_tuple(0.0, 0.0, 0.0),
           "A body of mass (kg) with inertia I_C_B about its COM (shape (3, 3), kg·m², body frame "
           "with origin at the COM) in uniform gravity (m/s², world frame).")
      .def(
          "add_load",
          [](RigidBody& b, py::function fn, const std::string& frame, const py::object& point) {
            if (frame != "world" && frame != "body") {
              throw rigid::Error(fmt::format("RigidBody.add_load(): frame must be 'world' or 'body', got '{}'", frame));
            }
            rigid::body::AppliedLoad load;
            load.frame = frame == "world" ? rigid::body::LoadFrame::kWorld : rigid::body::LoadFrame::kBody;
            load.p_CQ_B = cv::vector3(point, {"RigidBody.add_load", "point"});
            load.wrench = [fn](double t, const RigidBodyState& st) {
              py::gil_scoped_acquire gil;  // a no-op when it is held already
              const Eigen::Vector4d q = st.R_WB.quaternion();
              py::dict state;
              state["q_wxyz"] = q;
              state["omega_body"] = st.w_B;
              state["p_world"] = st.p_WC;
              state["v_world"] = st.v_WC;
              const py::object out = fn(t, state);
              // (force, torque): two 3-vectors, named when they are not
              if (!py::isinstance<py::sequence>(out) || py::len(out) != 2) {
                throw rigid::Error(fmt::format("RigidBody.add_load(): the wrench function must return "
                                               "(force, torque), two 3-vectors; got {} at t = {} s",
                                               py::repr(out).cast<std::string>(), t));
              }
              const char* f = "RigidBody.add_load";
              return rigid::body::Wrench{cv::vector3(out[py::int_(0)], {f, "force (returned by wrench)"}, cv::Finite::kAllowed),
                                         cv::vector3(out[py::int_(1)], {f, "torque (returned by wrench)"}, cv::Finite::kAllowed)};
            };
            b.add_load(std::move(load));
          },
          py::arg("wrench"), py::arg("frame") = "world", py::arg("point") = py::make_tuple(0.0, 0.0, 0.0),
          "Adds a load: wrench(t, state) -> (force N, torque N·m) in `frame` ('world' or 'body'); "
          "the force acts at the body point `point` (from the COM, body frame, m). `state` is a "
          "dict with q_wxyz, omega_body, p_world, v_world.")
      .def_property_readonly("mass", &RigidBody::mass, "Mass (kg).")
      .def_property_readonly("com", &RigidBody::com, "COM in the body frame (m).")
      .def_property_readonly("inertia", &RigidBody::inertia, "Inertia about the COM in the body frame (kg·m²).")
      .def_property_readonly("gravity", &RigidBody::gravity, "Uniform gravity g_W (m/s², world frame).")
      .def_property_readonly("principal_moments", &RigidBody::principal_moments,
                             "Principal moments about the COM (kg·m²), ascending (or B's own diagonal when "
                             "the inertia is diagonal in B).")
      .def_property_readonly("principal_axes",
                             [](const RigidBody& b) { return Eigen::Matrix3d(b.principal_axes().matrix()); },
                             "R_BP (3, 3): the principal axes as columns, in B (det +1).")
      .def(
          "acceleration",
          [](const RigidBody& b, double t, const py::object& q, const py::object& w, const py::object& p,
             const py::object& v) {
            const auto a = b.acceleration(t, state_of("RigidBody.acceleration", q, w, p, v));
            return py::make_tuple(a.a_WC, a.alpha_B);
          },
          py::arg("t"), py::arg("q_wxyz"), py::arg("omega_body"), py::arg("p_world"), py::arg("v_world"),
          "(a_world, alpha_body) at time t (s): the COM's acceleration in the world (m/s²) and the "
          "body angular acceleration (rad/s², body frame), from Newton's and Euler's equations.")
      .def(
          "diagnose",
          [](const RigidBody& b, const py::object& q, const py::object& w, const py::object& p,
             const py::object& v) {
            const auto d = b.diagnose(state_of("RigidBody.diagnose", q, w, p, v));
            py::dict out;
            out["energy"] = d.energy;
            out["momentum_world"] = d.P_W;
            out["angular_momentum_world"] = d.L_W;
            out["orthonormality_error"] = d.orthonormality_error;
            return out;
          },
          py::arg("q_wxyz"), py::arg("omega_body"), py::arg("p_world"), py::arg("v_world"),
          "Energy (J, gravity included), linear momentum (kg·m/s, world), angular momentum about "
          "the world origin (kg·m²/s, world) and ‖RᵀR − 1‖ of a state.")
      .def(
          "step",
          [](const RigidBody& b, const std::string& method, double t, const py::object& q, const py::object& w,
             const py::object& p, const py::object& v, double h, const std::string& free_method) {
            const auto m = rigid::body::rigid_body_method_from_name(method);
            const auto fm = rigid::body::free_body_method_from_name(free_method);
            return state_dict(rigid::body::step_rigid_body(b, m, t, state_of("RigidBody.step", q, w, p, v), h, fm));
          },
          py::arg("method"), py::arg("t"), py::arg("q_wxyz"), py::arg("omega_body"), py::arg("p_world"),
          py::arg("v_world"), py::arg("h"), py::arg("free_method") = "splitting2",
          "One step of size h (s) from time t (s) (method splitting2 or rk4; free_method is the "
          "free rotation of splitting2's drift): the next state as a dict q_wxyz (R_WB), "
          "omega_body (rad/s, body), p_world (COM, m), v_world (COM velocity, m/s). The step a "
          "scene of free bodies takes (`rigid run`), so repeated calls reproduce its trajectory.")
      .def(
          "simulate",
          [](const RigidBody& b, const std::string& method, const py::object& q_wxyz, const py::object& w_B,
             const py::object& p, const py::object& v, double h_max, const py::object& times,
             const std::string& free_method) {
            const char* f = "RigidBody.simulate";
            const RigidBodyState s = state_of(f, q_wxyz, w_B, p, v);
            const std::vector<double> out_times = cv::values(times, {f, "times"});
            const auto m = rigid::body::rigid_body_method_from_name(method);
            const auto fm = rigid::body::free_body_method_from_name(free_method);
            rigid::python::Interruptible interrupt;
            rigid::body::RigidBodyTrajectory tr;
            if (b.load_count() > 0) {  // the loads are Python: keep the GIL
              tr = rigid::body::simulate_rigid_body(b, m, s, h_max, out_times, fm, interrupt.control());
            } else {
              py::gil_scoped_release release;
              tr = rigid::body::simulate_rigid_body(b, m, s, h_max, out_times, fm, interrupt.control());
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
            out["t"] = cv::array(tr.t);
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
          "Integrates from t = 0 (method: splitting2 or rk4) and samples at `times` (s, ascending); "
          "returns a dict of arrays, one row per time: q_wxyz (R_WB), omega_body (rad/s, body), "
          "p_world, v_world (COM, m and m/s), momentum_world, angular_momentum_world (about the "
          "world origin), energy (J).")
      .def("__repr__", [](const RigidBody& b) {
        return fmt::format("RigidBody(mass={} kg, principal_moments={} kg·m², loads={})", b.mass(),
                           rigid::to_string(b.principal_moments().transpose()), b.load_count());
      });
}

void bind_heavy_top(py::module_& body) {
  using rigid::body::HeavyTop;
  py::class_<HeavyTop>(body, "HeavyTop",
                       "A rigid body on a fixed frictionless pivot in uniform gravity: its mass "
                       "properties in the body frame B, the pivot in B (m), gravity (m/s²). State: "
                       "R_WB as q_wxyz and the body angular velocity omega_body (rad/s).")
      .def(py::init([](const rigid::MassProperties& mp, const py::object& pivot, const py::object& gravity) {
             const char* f = "rigid.body.HeavyTop";
             return HeavyTop(mp, cv::vector3(pivot, {f, "pivot"}), cv::vector3(gravity, {f, "gravity"}));
           }),
           py::arg("mass_properties"), py::arg("pivot"), py::arg("gravity") = py::make_tuple(0.0, 0.0, -9.81),
           "A top with these mass properties (frame B) turning about the pivot p_OP_B (m, in B) in "
           "uniform gravity g_W (m/s², world). Raises rigid.Error if the moments about the pivot "
           "leave a rotation undefined (a thin rod pivoted on its own axis).")
      .def_property_readonly("mass", &HeavyTop::mass, "Mass (kg).")
      .def_property_readonly("gravity", &HeavyTop::gravity, "g_W (m/s², world).")
      .def_property_readonly("pivot", &HeavyTop::pivot, "p_OP_B: the pivot in B (m).")
      .def_property_readonly("inertia_about_pivot", &HeavyTop::inertia_about_pivot,
                             "I_P_B: the inertia about the pivot in B (kg·m²).")
      .def_property_readonly("com_from_pivot", &HeavyTop::com_from_pivot, "p_PC_B: the COM from the pivot, in B (m).")
      .def_property_readonly("principal_moments", &HeavyTop::principal_moments,
                             "Principal moments about the pivot (kg·m²).")
      .def_property_readonly("principal_axes",
                             [](const HeavyTop& top) { return Eigen::Matrix3d(top.principal_axes().matrix()); },
                             "R_BP (3, 3): the principal axes about the pivot as columns, in B.")
      .def(
          "energy",
          [](const HeavyTop& top, const py::object& q, const py::object& w) {
            return top.energy({rotation_arg(q, {"HeavyTop.energy", "q_wxyz"}), cv::vector3(w, {"HeavyTop.energy", "omega_body"})});
          },
          py::arg("q_wxyz"), py::arg("omega_body"),
          "Total energy (J): ½ ω_Bᵀ I_P_B ω_B − m g_W · (R_WB p_PC_B), zero potential at the pivot's height.")
      .def(
          "torque",
          [](const HeavyTop& top, const py::object& q) { return top.torque(rotation_arg(q, {"HeavyTop.torque", "q_wxyz"})); },
          py::arg("q_wxyz"), "Gravity torque about the pivot in B (N·m): p_PC_B × (m R_WBᵀ g_W).")
      .def(
          "angular_momentum_world",
          [](const HeavyTop& top, const py::object& q, const py::object& w) {
            const char* f = "HeavyTop.angular_momentum_world";
            return top.angular_momentum_world({rotation_arg(q, {f, "q_wxyz"}), cv::vector3(w, {f, "omega_body"})});
          },
          py::arg("q_wxyz"), py::arg("omega_body"),
          "Angular momentum about the pivot in the world (kg·m²/s): R_WB I_P_B ω_B.")
      .def(
          "step",
          [](const HeavyTop& top, const py::object& q, const py::object& w, double h, const std::string& free_method) {
            const char* f = "HeavyTop.step";
            const auto fm = rigid::body::free_body_method_from_name(free_method);
            const auto next = top.step({rotation_arg(q, {f, "q_wxyz"}), cv::vector3(w, {f, "omega_body"})},
                                       step_arg(h, f), fm);
            return py::make_tuple(Eigen::Vector4d(next.R_WB.quaternion()), next.w_B);
          },
          py::arg("q_wxyz"), py::arg("omega_body"), py::arg("h"), py::arg("free_method") = "splitting2",
          "One step of size h (s) of the symmetric splitting V(h/2) T(h) V(h/2) (gravity kick around "
          "the free flow by splitting2/4/6): (q_wxyz, omega_body) after it. Symplectic; keeps the "
          "vertical angular momentum g_W · L_W to round-off. The step a scene's top takes.")
      .def(
          "simulate",
          [](const HeavyTop& top, const py::object& q, const py::object& w, double h_max,
             const py::object& times, const std::string& free_method) {
            const char* f = "HeavyTop.simulate";
            const rigid::body::FreeBodyState s{rotation_arg(q, {f, "q_wxyz"}), cv::vector3(w, {f, "omega_body"})};
            const std::vector<double> out_times = cv::values(times, {f, "times"});
            const auto fm = rigid::body::free_body_method_from_name(free_method);
            rigid::python::Interruptible interrupt;
            rigid::body::FreeBodyTrajectory traj;
            {
              py::gil_scoped_release release;
              traj = top.simulate(s, h_max, out_times, fm, interrupt.control());
            }
            return free_trajectory(traj);
          },
          py::arg("q_wxyz"), py::arg("omega_body"), py::arg("h_max"), py::arg("times"),
          py::arg("free_method") = "splitting2",
          "Integrates by the gravity-kick splitting around the free flow (splitting2/4/6); returns a "
          "dict of arrays sampled at `times` (s): t, q_wxyz, omega_body, L_world (about the pivot, "
          "kg·m²/s), energy (J, total), orthonormality_error.")
      .def("__repr__", [](const HeavyTop& top) {
        return fmt::format("HeavyTop(mass={} kg, com_from_pivot={} m, inertia_about_pivot={} kg·m²)", top.mass(),
                           rigid::to_string(top.com_from_pivot().transpose()),
                           rigid::to_string(top.inertia_about_pivot()));
      });
}

// Euler–Arnold equations on SO(n): J (n,) and M (n, n) skew, refused by name when malformed.
void bind_euler_arnold(py::module_& body) {
  auto args = [](std::string_view f, const py::object& J, const py::object& M) {
    const Eigen::VectorXd j = cv::vector(J, {f, "J"});
    if (j.size() < 2) {
      throw rigid::Error(fmt::format("{}(): argument 'J' must have n ≥ 2 entries (the body turns in SO(n)); "
                                     "got {}", f, j.size()));
    }
    return std::make_pair(j, cv::matrix(M, {f, "M"}, j.size(), j.size()));
  };
  body.def(
      "euler_arnold_velocity",
      [args](const py::object& J, const py::object& M) {
        const auto [j, m] = args("rigid.body.euler_arnold_velocity", J, M);
        return rigid::body::euler_arnold_velocity(j, m);
      },
      py::arg("J"), py::arg("M"),
      "Body angular velocity Ω ∈ so(n) (rad/s) of the body angular momentum M ∈ so(n) (n × n "
      "skew, kg·m²/s) of the generalised rigid body with mass matrix J = diag(J_1 … J_n) "
      "(shape (n,), kg·m², J = Σ m x xᵀ in principal axes): Ω_ij = M_ij / (J_i + J_j).");
  body.def(
      "euler_arnold_rhs",
      [args](const py::object& J, const py::object& M) {
        const auto [j, m] = args("rigid.body.euler_arnold_rhs", J, M);
        return rigid::body::euler_arnold_rhs(j, m);
      },
      py::arg("J"), py::arg("M"),
      "Ṁ = [M, Ω] = MΩ − ΩM (kg·m²/s²), the Euler–Arnold equations on SO(n) [Ratiu1980] in the "
      "body frame. For n = 3, M = hat(L) and I_1 = J_2 + J_3 (cyclic): Euler's equations.");
  body.def(
      "euler_arnold_rk4_step",
      [args](const py::object& J, const py::object& M, double h) {
        const auto [j, m] = args("rigid.body.euler_arnold_rk4_step", J, M);
        return rigid::body::euler_arnold_rk4_step(j, m, step_arg(h, "rigid.body.euler_arnold_rk4_step"));
      },
      py::arg("J"), py::arg("M"), py::arg("h"),
      "M after one classical RK4 step of size h (s) of the Euler–Arnold equations; the Casimirs "
      "tr(M^2k) are kept to the method's O(h⁴) error.");
}

}  // namespace

void bind_body(py::module_& m) {
  auto body = m.def_submodule("body", "Rigid-body dynamics on SO(3): exact free body, integrators, SO(n).");
  py::class_<rigid::body::FreeBodyExact>(body, "FreeBodyExact",
                                         "Exact torque-free body angular velocity (Jacobi elliptic functions).")
      .def(py::init([](const py::object& I_B, const py::object& w_B) {
             const char* f = "rigid.body.FreeBodyExact";
             return rigid::body::FreeBodyExact(moments_arg(I_B, {f, "principal_moments"}), cv::vector3(w_B, {f, "omega_body"}));
           }),
           py::arg("principal_moments"), py::arg("omega_body"),
           "The motion of ω_B (rad/s, principal body frame) for principal moments I_B (kg·m²) "
           "from ω_B(0) = omega_body.")
      .def(
          "omega_body",
          [](const rigid::body::FreeBodyExact& e, const py::object& t) {
            const cv::Arg arg{"rigid.body.FreeBodyExact.omega_body", "t"};
            const double time = time_arg(t, arg);
            return at_time(arg, [&] { return Eigen::Vector3d(e.omega_body(time)); });
          },
          py::arg("t"),
          "Body angular velocity at t (s); raises rigid.Error if t is not finite or beyond "
          "max_time.")
      .def_property_readonly("max_time", &rigid::body::FreeBodyExact::max_time,
                             "The largest |t| (s) omega_body accepts: 1e15 rad over the rate of "
                             "the phase of ω (beyond, rounding has lost the fraction of a "
                             "period); inf when ω is constant.")
      .def_property_readonly("period", &rigid::body::FreeBodyExact::period, "Period of ω_B(t) (s; inf on a separatrix).")
      .def_property_readonly("modulus", &rigid::body::FreeBodyExact::modulus, "Elliptic modulus k.")
      .def_property_readonly("energy", &rigid::body::FreeBodyExact::energy, "Kinetic energy ½ ωᵀ I ω (J).")
      .def_property_readonly("angular_momentum_norm", &rigid::body::FreeBodyExact::angular_momentum_norm,
                             "|L| (kg·m²/s), constant.")
      .def("__repr__", [](const rigid::body::FreeBodyExact& e) {
        return fmt::format("FreeBodyExact(energy={} J, angular_momentum_norm={} kg·m²/s, modulus={}, period={} s)",
                           e.energy(), e.angular_momentum_norm(), e.modulus(), e.period());
      });
  py::class_<rigid::body::FreeBodyMotion>(
      body, "FreeBodyMotion",
      "Exact torque-free motion: orientation R_WB(t) and body angular velocity in closed form.")
      .def(py::init([](const py::object& I_B, const py::object& q_wxyz, const py::object& w_B) {
             const char* f = "rigid.body.FreeBodyMotion";
             return rigid::body::FreeBodyMotion(moments_arg(I_B, {f, "principal_moments"}), rotation_arg(q_wxyz, {f, "q_wxyz"}),
                                                cv::vector3(w_B, {f, "omega_body"}));
           }),
           py::arg("principal_moments"), py::arg("q_wxyz"), py::arg("omega_body"),
           "The motion from R_WB(0) (q_wxyz, principal body frame B) and ω_B(0) (rad/s) for "
           "principal moments (kg·m²).")
      .def(py::init([](const rigid::MassProperties& mp, const py::object& q_wxyz, const py::object& w_B) {
             const char* f = "rigid.body.FreeBodyMotion";
             return rigid::body::FreeBodyMotion(mp, rotation_arg(q_wxyz, {f, "q_wxyz"}), cv::vector3(w_B, {f, "omega_body"}));
           }),
           py::arg("mass_properties"), py::arg("q_wxyz"), py::arg("omega_body"),
           "The motion of a body with these mass properties in any body frame.")
      .def(
          "orientation",
          [](const rigid::body::FreeBodyMotion& motion, const py::object& t) {
            const cv::Arg arg{"rigid.body.FreeBodyMotion.orientation", "t"};
            const double time = time_arg(t, arg);
            return at_time(arg, [&] { return Eigen::Vector4d(motion.orientation(time).quaternion()); });
          },
          py::arg("t"),
          "Orientation R_WB(t) as a quaternion (w, x, y, z); raises rigid.Error if t is not "
          "finite or so far that an angle of the motion exceeds 1e15 rad.")
      .def(
          "omega_body",
          [](const rigid::body::FreeBodyMotion& motion, const py::object& t) {
            const cv::Arg arg{"rigid.body.FreeBodyMotion.omega_body", "t"};
            const double time = time_arg(t, arg);
            return at_time(arg, [&] { return Eigen::Vector3d(motion.omega_body(time)); });
          },
          py::arg("t"), "Body angular velocity at t (s); raises rigid.Error as orientation.")
      .def_property_readonly("angular_momentum_world", &rigid::body::FreeBodyMotion::angular_momentum_world,
                             "L_W (kg·m²/s), constant.")
      .def_property_readonly("period", [](const rigid::body::FreeBodyMotion& motion) { return motion.omega_solution().period(); },
                             "Period of ω_B(t) (s).")
      .def_property_readonly("modulus", [](const rigid::body::FreeBodyMotion& motion) { return motion.omega_solution().modulus(); },
                             "Elliptic modulus k of the body angular velocity's solution.")
      .def("__repr__", [](const rigid::body::FreeBodyMotion& motion) {
        return fmt::format("FreeBodyMotion(angular_momentum_world={} kg·m²/s, period={} s, modulus={})",
                           rigid::to_string(motion.angular_momentum_world().transpose()),
                           motion.omega_solution().period(), motion.omega_solution().modulus());
      });
  body.def(
      "simulate_free_body",
      [](const std::string& method, const py::object& I_B, const py::object& q_wxyz, const py::object& w_B,
         double h_max, const py::object& times) {
        const char* f = "rigid.body.simulate_free_body";
        const rigid::body::FreeBodyState s{rotation_arg(q_wxyz, {f, "q_wxyz"}), cv::vector3(w_B, {f, "omega_body"})};
        const Eigen::Vector3d I = cv::vector3(I_B, {f, "principal_moments"});
        const std::vector<double> out_times = cv::values(times, {f, "times"});
        const auto stepper = rigid::body::free_body_method_from_name(method);
        rigid::python::Interruptible interrupt;
        rigid::body::FreeBodyTrajectory traj;
        {
          py::gil_scoped_release release;
          traj = rigid::body::simulate_free_body(stepper, I, s, h_max, out_times, interrupt.control());
        }
        return free_trajectory(traj);
      },
      py::arg("method"), py::arg("principal_moments"), py::arg("q_wxyz"), py::arg("omega_body"),
      py::arg("h_max"), py::arg("times"),
      "Integrate a free body in its principal frame (method: rk4, splitting2, splitting4, "
      "splitting6, midpoint, rkmk4, moser_veselov); returns a dict of arrays sampled at `times` "
      "(s): t, q_wxyz (R_WB), omega_body (rad/s), L_world (kg·m²/s), energy (J), orthonormality_error.");
  body.def(
      "step_free_body",
      [](const std::string& method, const py::object& I_B, const py::object& q_wxyz, const py::object& w_B, double h) {
        const char* f = "rigid.body.step_free_body";
        const auto stepper = rigid::body::free_body_method_from_name(method);
        const rigid::body::FreeBodyState s{rotation_arg(q_wxyz, {f, "q_wxyz"}), cv::vector3(w_B, {f, "omega_body"})};
        const auto next = rigid::body::step_free_body(stepper, moments_arg(I_B, {f, "principal_moments"}), s, step_arg(h, f));
        // the kernel leaves a diverged step non-finite for a march's check: refused here
        if (const auto bad = rigid::body::find_nonfinite(next)) {
          throw rigid::Error(fmt::format("{}(): the step of h = {} s diverged: {} = {} after it, expected a "
                                         "finite state (a smaller step h)",
                                         f, h, bad->component, bad->value));
        }
        return py::make_tuple(Eigen::Vector4d(next.R_WB.quaternion()), next.w_B);
      },
      py::arg("method"), py::arg("principal_moments"), py::arg("q_wxyz"), py::arg("omega_body"), py::arg("h"),
      "One step of size h (s) of a free-body method (as simulate_free_body) with principal moments "
      "(kg·m²), from R_WB (q_wxyz, principal body frame) and ω_B (rad/s): (q_wxyz, omega_body) after it.");
  body.def(
      "step_free_bodies",
      [](const std::string& method, const py::object& I_B, const py::object& q_wxyz, const py::object& w_B, double h,
         long long steps) {
        const char* f = "rigid.body.step_free_bodies";
        const auto stepper = rigid::body::free_body_method_from_name(method);
        const Eigen::MatrixXd I = cv::matrix(I_B, {f, "principal_moments"}, -1, 3, cv::Finite::kRequired, "N");
        const Eigen::MatrixXd q = cv::matrix(q_wxyz, {f, "q_wxyz"}, I.rows(), 4, cv::Finite::kRequired, "N");
        const Eigen::MatrixXd w = cv::matrix(w_B, {f, "omega_body"}, I.rows(), 3, cv::Finite::kRequired, "N");
        step_arg(h, f);
        if (steps < 1) throw rigid::Error(fmt::format("{}(): steps is {}, expected a count of at least 1", f, steps));
        // each row read and checked as moments_arg and rotation_arg would (the same refusals, naming
        // the row), without a Python object per row
        std::vector<Eigen::Vector3d> moments(static_cast<std::size_t>(I.rows()));
        std::vector<rigid::body::FreeBodyState> states(static_cast<std::size_t>(I.rows()));
        for (Eigen::Index i = 0; i < I.rows(); ++i) {
          const auto k = static_cast<std::size_t>(i);
          moments[k] = I.row(i).transpose();
          if (const auto why = rigid::check_rotational_moments(moments[k])) {
            throw rigid::Error(fmt::format("{}(): argument 'principal_moments[{}]': {}", f, i, *why));
          }
          try {
            states[k] = {rotation_of(q.row(i).transpose()), w.row(i).transpose()};
          } catch (const rigid::Error& e) {
            throw rigid::Error(fmt::format("{}(): argument 'q_wxyz[{}]': {}", f, i, rigid::strip_function_names(e.what())));
          }
        }
        {
          py::gil_scoped_release release;
          for (long long k = 0; k < steps; ++k) {
            try {
              rigid::body::step_free_bodies(stepper, moments, states, h);
            } catch (const rigid::Error& e) {
              if (steps == 1) throw;
              throw rigid::Error(fmt::format("{}(): step {} of {}: {}", f, k + 1, steps, rigid::strip_function_names(e.what())));
            }
          }
        }
        const auto n = static_cast<py::ssize_t>(I.rows());
        py::array_t<double> q_out({n, py::ssize_t{4}}), w_out({n, py::ssize_t{3}});
        double* qo = q_out.mutable_data();
        double* wo = w_out.mutable_data();
        for (std::size_t i = 0; i < states.size(); ++i) {
          const Eigen::Vector4d qi = states[i].R_WB.quaternion();
          for (int c = 0; c < 4; ++c) qo[4 * i + static_cast<std::size_t>(c)] = qi(c);
          for (int c = 0; c < 3; ++c) wo[3 * i + static_cast<std::size_t>(c)] = states[i].w_B(c);
        }
        return py::make_tuple(q_out, w_out);
      },
      py::arg("method"), py::arg("principal_moments"), py::arg("q_wxyz"), py::arg("omega_body"), py::arg("h"),
      py::kw_only(), py::arg("steps") = 1,
      "`steps` steps (default 1) of size h (s) for N free bodies at once: principal_moments (N, 3) kg·m², "
      "q_wxyz (N, 4), omega_body (N, 3) rad/s; returns (q_wxyz, omega_body) after them, each row bitwise "
      "equal to `steps` calls of step_free_body on that body. The splittings run four bodies at a time in "
      "vector registers (AVX2 where the CPU has it).");
  body.def(
      "euler_rhs",
      [](const py::object& I_B, const py::object& w_B, const py::object& tau_B) {
        const char* f = "rigid.body.euler_rhs";
        return rigid::body::euler_rhs<double>(moments_arg(I_B, {f, "principal_moments"}),
                                              cv::vector3(w_B, {f, "omega_body"}), cv::vector3(tau_B, {f, "torque_body"}));
      },
      py::arg("principal_moments"), py::arg("omega_body"), py::arg("torque_body") = py::make_tuple(0.0, 0.0, 0.0),
      "ω̇_B (rad/s²) from Euler's equations I ω̇ + ω × (I ω) = τ in the principal body frame: "
      "principal moments (kg·m²), ω_B (rad/s), τ_B (N·m).");
  body.def(
      "rotational_energy",
      [](const py::object& I_B, const py::object& w_B) {
        const char* f = "rigid.body.rotational_energy";
        return rigid::body::rotational_energy<double>(cv::vector3(I_B, {f, "principal_moments"}),
                                                      cv::vector3(w_B, {f, "omega_body"}));
      },
      py::arg("principal_moments"), py::arg("omega_body"),
      "Kinetic energy of the rotation ½ ωᵀ I ω (J): principal moments (kg·m²), ω_B (rad/s).");
  body.def(
      "method_order", [](const std::string& method) { return rigid::body::order_of(rigid::body::free_body_method_from_name(method)); },
      py::arg("method"), "Classical order of accuracy of a free-body method (rk4 4, splitting2 2, ...).");

  bind_rigid_body(body);
  bind_heavy_top(body);
  bind_euler_arnold(body);
}
