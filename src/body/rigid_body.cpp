#include "rigid/body/rigid_body.hpp"

#include <cmath>
#include <string>
#include <utility>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"

namespace rigid::body {

namespace {

// relative tolerance of the symmetry and triangle-inequality checks of I_C_B
constexpr double kInertiaRelTol = 1e-12;

Eigen::Quaterniond to_eigen(const SO3d& R) {
  const Eigen::Vector4d q = R.quaternion();  // (w, x, y, z)
  return {q(0), q(1), q(2), q(3)};
}

SO3d from_eigen(const Eigen::Quaterniond& q) { return SO3d::from_quaternion(q.w(), q.x(), q.y(), q.z()); }

}  // namespace

RigidBody::RigidBody(double mass, const Eigen::Matrix3d& I_C_B, const Eigen::Vector3d& g_W)
    : mass_(mass), g_W_(g_W), R_BP_(SO3d::identity()) {
  RIGID_REQUIRE(std::isfinite(mass) && mass > 0, "mass must be positive and finite, got {} kg", mass);
  RIGID_REQUIRE(I_C_B.allFinite(), "inertia I_C_B must be finite, got\n{}", rigid::to_string(I_C_B));
  RIGID_REQUIRE(g_W.allFinite(), "gravity g_W must be finite, got {} m/s²", rigid::to_string(g_W.transpose()));
  const double scale = I_C_B.cwiseAbs().maxCoeff();
  const double asym = (I_C_B - I_C_B.transpose()).cwiseAbs().maxCoeff();
  RIGID_REQUIRE(asym <= kInertiaRelTol * scale,
                "inertia I_C_B must be symmetric; |I − Iᵀ|_max = {} kg·m² exceeds {} × the largest "
                "entry {}",
                asym, kInertiaRelTol, scale);
  I_C_B_ = 0.5 * (I_C_B + I_C_B.transpose());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(I_C_B_);
  I_P_ = eig.eigenvalues();  // ascending
  RIGID_REQUIRE(I_P_(0) > 0, "inertia I_C_B must be positive definite; principal moments are {} kg·m²",
                rigid::to_string(I_P_.transpose()));
  RIGID_REQUIRE(I_P_(2) <= (I_P_(0) + I_P_(1)) * (1 + kInertiaRelTol),
                "inertia I_C_B violates the triangle inequality: largest principal moment {} > {} + {} "
                "kg·m² (no mass distribution has these moments)",
                I_P_(2), I_P_(0), I_P_(1));
  // principal axes as a proper rotation: flip one axis if the eigenvector basis is left-handed
  Eigen::Matrix3d V = eig.eigenvectors();
  if (V.determinant() < 0) V.col(2) = -V.col(2);
  R_BP_ = SO3d::from_matrix(V);
  I_C_B_inv_ = I_C_B_.inverse();
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

RigidBodyDiagnostics RigidBody::diagnose(const RigidBodyState& s) const {
  RigidBodyDiagnostics d;
  const Eigen::Vector3d L_B = I_C_B_ * s.w_B;
  d.energy = 0.5 * mass_ * s.v_WC.squaredNorm() + 0.5 * s.w_B.dot(L_B) - mass_ * g_W_.dot(s.p_WC);
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
  const SO3d& R_BP = body.principal_axes();
  FreeBodyState fs{to_eigen(s.R_WB * R_BP), R_BP.inverse() * s.w_B};
  fs = step_free_body(free_method, body.principal_moments(), fs, h);
  s.R_WB = from_eigen(fs.q_WB) * R_BP.inverse();
  s.w_B = R_BP * fs.w_B;
}

// RK4 state y = (q_WB (w, x, y, z), ω_B, p_WC, v_WC).
using Vec13 = Eigen::Matrix<double, 13, 1>;

Vec13 pack(const RigidBodyState& s) {
  Vec13 y;
  y << s.R_WB.quaternion(), s.w_B, s.p_WC, s.v_WC;
  return y;
}

RigidBodyState unpack(const Vec13& y) {
  return {SO3d::from_quaternion(y(0), y(1), y(2), y(3)), y.segment<3>(4), y.segment<3>(7), y.segment<3>(10)};
}

Vec13 rk4_rate(const RigidBody& body, double t, const Vec13& y) {
  const RigidBodyState s = unpack(y);
  const RigidBodyAcceleration a = body.acceleration(t, s);
  // q̇ = ½ q ⊗ (0, ω_B) on the unnormalised stage quaternion:
  // (w, v) ⊗ (0, ω) = (−v·ω, w ω + v × ω)
  const double qw = y(0);
  const Eigen::Vector3d qv = y.segment<3>(1);
  const Eigen::Vector3d w = y.segment<3>(4);
  Vec13 r;
  r(0) = -0.5 * qv.dot(w);
  r.segment<3>(1) = 0.5 * (qw * w + qv.cross(w));
  r.segment<3>(4) = a.alpha_B;
  r.segment<3>(7) = y.segment<3>(10);
  r.segment<3>(10) = a.a_WC;
  return r;
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
  const Vec13 y = pack(state);
  const Vec13 k1 = rk4_rate(body, t, y);
  const Vec13 k2 = rk4_rate(body, t + 0.5 * h, y + 0.5 * h * k1);
  const Vec13 k3 = rk4_rate(body, t + 0.5 * h, y + 0.5 * h * k2);
  const Vec13 k4 = rk4_rate(body, t + h, y + h * k3);
  // from_quaternion renormalises q (SO3d keeps |q| = 1 as its invariant)
  return unpack(y + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4));
}

RigidBodyTrajectory simulate_rigid_body(const RigidBody& body, RigidBodyMethod method,
                                        const RigidBodyState& initial, double h_max,
                                        const std::vector<double>& output_times, FreeBodyMethod free_method) {
  RIGID_REQUIRE(std::isfinite(h_max) && h_max > 0, "step h_max must be positive and finite, got {} s", h_max);
  RigidBodyTrajectory traj;
  RigidBodyState s = initial;
  double t = 0;
  for (std::size_t i = 0; i < output_times.size(); ++i) {
    const double t_out = output_times[i];
    RIGID_REQUIRE(std::isfinite(t_out) && t_out >= t,
                  "output times must be finite, ≥ 0 and ascending; entry {} is {} s after {} s", i, t_out, t);
    const double span = t_out - t;
    // the 1e-12 keeps a span that is a multiple of h_max up to round-off from taking one extra step
    const auto n = static_cast<long>(std::ceil(span / h_max - 1e-12));
    for (long k = 0; k < n; ++k) {
      const double h = span / static_cast<double>(n);
      s = step_rigid_body(body, method, t + h * static_cast<double>(k), s, h, free_method);
    }
    t = t_out;
    traj.t.push_back(t);
    traj.states.push_back(s);
    traj.diagnostics.push_back(body.diagnose(s));
  }
  return traj;
}

}  // namespace rigid::body

auto fmt::formatter<rigid::body::RigidBodyState>::format(const rigid::body::RigidBodyState& s,
                                                         fmt::format_context& ctx) const
    -> decltype(ctx.out()) {
  const std::string text = fmt::format(
      "RigidBodyState{{q_WB: {}, w_B: {} rad/s, p_WC: {} m, v_WC: {} m/s}}",
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
