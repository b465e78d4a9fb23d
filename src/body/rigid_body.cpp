#include "rigid/body/rigid_body.hpp"

#include <cmath>
#include <string>
#include <utility>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "body/detail/principal_frame.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"

namespace rigid::body {

RigidBody::RigidBody(const MassProperties& mass_B, const Eigen::Vector3d& g_W)
    : mass_(mass_B.mass()), p_BC_B_(mass_B.com()), I_C_B_(mass_B.inertia_com()), g_W_(g_W) {
  RIGID_REQUIRE(g_W.allFinite(), "gravity g_W must be finite, got {} m/s²", rigid::to_string(g_W.transpose()));
  const PrincipalFrame frame = principal_frame(I_C_B_, "RigidBody", "about the COM");
  I_P_ = frame.moments;
  R_BP_ = frame.R_BP;
  principal_is_body_ = frame.is_body;
  I_C_B_inv_ = I_C_B_.inverse();
}

RigidBody::RigidBody(double mass, const Eigen::Matrix3d& I_C_B, const Eigen::Vector3d& g_W)
    : RigidBody(MassProperties(mass, Eigen::Vector3d::Zero(), I_C_B), g_W) {}

FreeBodyState RigidBody::free_flow(const FreeBodyState& s, double h, FreeBodyMethod method) const {
  if (principal_is_body_) return step_free_body(method, I_P_, s, h);
  return from_principal(step_free_body(method, I_P_, to_principal(s, R_BP_), h), R_BP_);
}

std::optional<integrate::NonFinite> find_nonfinite(const RigidBodyState& s, std::string_view owner) {
  // fast path, every step: a NaN or an infinity makes the sum non-finite (finite values whose
  // sum overflows fall through to the scan, which then finds nothing)
  if (std::isfinite(s.R_WB.quaternion().sum() + s.w_B.sum() + s.p_WC.sum() + s.v_WC.sum())) [[likely]] {
    return std::nullopt;
  }
  static constexpr const char* kNames[13] = {"R_WB.w", "R_WB.x", "R_WB.y", "R_WB.z", "w_B.x",
                                             "w_B.y",  "w_B.z",  "p_WC.x", "p_WC.y", "p_WC.z",
                                             "v_WC.x", "v_WC.y", "v_WC.z"};
  const Eigen::Vector4d q = s.R_WB.quaternion();
  const double values[13] = {q(0),      q(1),      q(2),      q(3),      s.w_B(0),
                             s.w_B(1),  s.w_B(2),  s.p_WC(0), s.p_WC(1), s.p_WC(2),
                             s.v_WC(0), s.v_WC(1), s.v_WC(2)};
  if (auto i = integrate::first_nonfinite(values)) [[unlikely]] {
    return integrate::NonFinite{std::string(owner), kNames[*i], values[*i]};
  }
  return std::nullopt;
}

void RigidBody::add_load(AppliedLoad load) {
  RIGID_REQUIRE(static_cast<bool>(load.wrench), "load {} has no wrench function", loads_.size());
  RIGID_REQUIRE(load.p_CQ_B.allFinite(), "load {}: point of application p_CQ_B must be finite, got {} m",
                loads_.size(), rigid::to_string(load.p_CQ_B.transpose()));
  loads_.push_back(std::move(load));
}

Wrench RigidBody::total_wrench(double t, const RigidBodyState& state) const {
  const SO3d& R_WB = state.R_WB;
  Wrench total;  // force in W, torque about C in B
  total.force = mass_ * g_W_;
  for (std::size_t i = 0; i < loads_.size(); ++i) {
    const AppliedLoad& load = loads_[i];
    const Wrench w = load.wrench(t, state);
    RIGID_REQUIRE(w.force.allFinite() && w.torque.allFinite(),
                  "load {} returned a non-finite wrench at t = {} s: force {}, torque {}", i, t,
                  rigid::to_string(w.force.transpose()), rigid::to_string(w.torque.transpose()));
    // a force F at the body point Q adds the torque p_CQ × F about C, in the load's frame
    if (load.frame == LoadFrame::kWorld) {
      const Eigen::Vector3d p_CQ_W = R_WB * load.p_CQ_B;
      total.force += w.force;
      total.torque += R_WB.inverse() * (w.torque + p_CQ_W.cross(w.force));
    } else {
      total.force += R_WB * w.force;
      total.torque += w.torque + load.p_CQ_B.cross(w.force);
    }
  }
  return total;
}

RigidBodyAcceleration RigidBody::acceleration(double t, const RigidBodyState& state) const {
  const Wrench w = total_wrench(t, state);
  const Eigen::Vector3d& omega = state.w_B;
  // m v̇ = F_W;  I ω̇ = τ_B − ω × I ω  [Landau1976, §36]
  return {w.force / mass_, I_C_B_inv_ * (w.torque - omega.cross(I_C_B_ * omega))};
}

double RigidBody::energy(const RigidBodyState& s) const {
  const Eigen::Vector3d L_B = I_C_B_ * s.w_B;
  return 0.5 * mass_ * s.v_WC.squaredNorm() + 0.5 * s.w_B.dot(L_B) - mass_ * g_W_.dot(s.p_WC);
}

RigidBodyDiagnostics RigidBody::diagnose(const RigidBodyState& s) const {
  RigidBodyDiagnostics d;
  const Eigen::Vector3d L_B = I_C_B_ * s.w_B;
  d.energy = energy(s);
  d.P_W = mass_ * s.v_WC;
  // L about the world origin O = spin about C + orbital part p_OC × m v  [Goldstein2002, §1.2]
  d.L_W = s.R_WB * L_B + s.p_WC.cross(d.P_W);
  const Eigen::Matrix3d R = s.R_WB.matrix();
  d.orthonormality_error = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  return d;
}

namespace {

// Kick of length `tau`: v̇ = F_W/m, L̇_B = τ_B with p, R and t frozen, by the explicit
// midpoint rule (exact when the loads do not depend on v or ω: then the rates are constant).
void kick(const RigidBody& body, double t, RigidBodyState& s, double tau, bool has_loads) {
  if (!has_loads) {  // gravity alone: no torque about C, a constant acceleration g
    s.v_WC += tau * body.gravity();
    return;
  }
  const Eigen::Matrix3d& I_inv = body.inertia_inverse();
  Wrench w = body.total_wrench(t, s);
  if (has_loads) {
    RigidBodyState mid = s;
    mid.v_WC += (0.5 * tau / body.mass()) * w.force;
    mid.w_B += (0.5 * tau) * (I_inv * w.torque);
    w = body.total_wrench(t, mid);
  }
  s.v_WC += (tau / body.mass()) * w.force;
  // ΔL_B = τ Δt and I is constant in B, so Δω_B = I⁻¹ τ Δt
  s.w_B += tau * (I_inv * w.torque);
}

// Drift of length h: the flow of the kinetic energy, p += h v and the free rotation, done in
// the principal frame P (R_WP = R_WB R_BP, ω_P = R_BPᵀ ω_B) where I is diagonal.
void drift(const RigidBody& body, RigidBodyState& s, double h, FreeBodyMethod free_method) {
  s.p_WC += h * s.v_WC;
  const FreeBodyState fs = body.free_flow({s.R_WB, s.w_B}, h, free_method);
  s.R_WB = fs.R_WB;
  s.w_B = fs.w_B;
}

// RK4 on y = (q, ω_B, p_WC, v_WC), q the quaternion coefficients of R_WB: the stages carry
// q unnormalised (q̇ = ½ q ⊗ (0, ω_B), SO3::quaternion_rate); the loads see the stage's
// rotation back on |q| = 1 (SO3::from_integrated_quaternion), and so does the step's result.
struct Rk4Point {
  Eigen::Vector4d q;
  Eigen::Vector3d w, p, v;
};

// y + c k
Rk4Point advanced(const Rk4Point& y, double c, const Rk4Point& k) {
  return {y.q + c * k.q, y.w + c * k.w, y.p + c * k.p, y.v + c * k.v};
}

RigidBodyState state_of(const Rk4Point& y) {
  return {SO3d::from_integrated_quaternion(y.q), y.w, y.p, y.v};
}

Rk4Point rk4_rate(const RigidBody& body, double t, const Rk4Point& y) {
  const RigidBodyAcceleration a = body.acceleration(t, state_of(y));
  return {SO3d::quaternion_rate(y.q, y.w), a.alpha_B, y.v, a.a_WC};
}

}  // namespace

RigidBodyMethod rigid_body_method_from_name(std::string_view name) {
  if (name == "splitting2") return RigidBodyMethod::kSplitting2;
  if (name == "rk4") return RigidBodyMethod::kRk4;
  RIGID_THROW("unknown rigid-body method '{}'; expected one of splitting2, rk4", name);
}

RigidBodyState step_rigid_body(const RigidBody& body, RigidBodyMethod method, double t,
                               const RigidBodyState& state, double h, FreeBodyMethod free_method) {
  RIGID_REQUIRE(std::isfinite(h) && h > 0, "step h must be positive and finite, got {} s", h);
  RIGID_REQUIRE(std::isfinite(t), "time t must be finite, got {} s", t);
  RIGID_REQUIRE(state.w_B.allFinite() && state.p_WC.allFinite() && state.v_WC.allFinite(),
                "state at t = {} s is not finite: w_B = {}, p_WC = {}, v_WC = {}", t,
                rigid::to_string(state.w_B.transpose()), rigid::to_string(state.p_WC.transpose()),
                rigid::to_string(state.v_WC.transpose()));
  if (method == RigidBodyMethod::kSplitting2) {
    // K(h/2) D(h) K(h/2); the drift advances t, so the second kick sees t + h
    // gravity alone is a constant rate: one evaluation per kick is then exact
    const bool has_loads = body.load_count() > 0;
    RigidBodyState s = state;
    kick(body, t, s, 0.5 * h, has_loads);
    drift(body, s, h, free_method);
    kick(body, t + h, s, 0.5 * h, has_loads);
    return s;
  }
  const Rk4Point y{state.R_WB.quaternion(), state.w_B, state.p_WC, state.v_WC};
  const Rk4Point k1 = rk4_rate(body, t, y);
  const Rk4Point k2 = rk4_rate(body, t + 0.5 * h, advanced(y, 0.5 * h, k1));
  const Rk4Point k3 = rk4_rate(body, t + 0.5 * h, advanced(y, 0.5 * h, k2));
  const Rk4Point k4 = rk4_rate(body, t + h, advanced(y, h, k3));
  const double c = h / 6.0;
  return state_of({y.q + c * (k1.q + 2.0 * k2.q + 2.0 * k3.q + k4.q), y.w + c * (k1.w + 2.0 * k2.w + 2.0 * k3.w + k4.w),
                   y.p + c * (k1.p + 2.0 * k2.p + 2.0 * k3.p + k4.p), y.v + c * (k1.v + 2.0 * k2.v + 2.0 * k3.v + k4.v)});
}

RigidBodyTrajectory simulate_rigid_body(const RigidBody& body, RigidBodyMethod method,
                                        const RigidBodyState& initial, double h_max,
                                        const std::vector<double>& output_times, FreeBodyMethod free_method,
                                        const integrate::MarchControl& control) {
  if (auto bad = find_nonfinite(initial)) {
    RIGID_THROW("the initial state is not finite: {} = {}", bad->component, bad->value);
  }
  RigidBodyTrajectory traj;
  RigidBodyState s = initial;
  (void)integrate::march(
      integrate::TimeGrid::from_times(0.0, output_times), h_max,
      [&](double t, double h) { s = step_rigid_body(body, method, t, s, h, free_method); },
      [&] { return find_nonfinite(s); },
      [&](std::size_t, double t) {
        traj.t.push_back(t);
        traj.states.push_back(s);
        traj.diagnostics.push_back(body.diagnose(s));
      },
      control);
  return traj;
}

}  // namespace rigid::body

auto fmt::formatter<rigid::body::RigidBodyState>::format(const rigid::body::RigidBodyState& s,
                                                         fmt::format_context& ctx) const
    -> decltype(ctx.out()) {
  const std::string text = fmt::format(
      "RigidBodyState{{R_WB: {}, w_B: {} rad/s, p_WC: {} m, v_WC: {} m/s}}",
      rigid::to_string(s.R_WB.quaternion().transpose()), rigid::to_string(s.w_B.transpose()),
      rigid::to_string(s.p_WC.transpose()), rigid::to_string(s.v_WC.transpose()));
  return fmt::formatter<std::string_view>::format(text, ctx);
}

auto fmt::formatter<rigid::body::Wrench>::format(const rigid::body::Wrench& w,
                                                 fmt::format_context& ctx) const -> decltype(ctx.out()) {
  const std::string text = fmt::format("Wrench{{force: {} N, torque: {} N·m}}",
                                       rigid::to_string(w.force.transpose()),
                                       rigid::to_string(w.torque.transpose()));
  return fmt::formatter<std::string_view>::format(text, ctx);
}
