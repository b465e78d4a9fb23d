#pragma once

/// A free rigid body with mass, a full inertia tensor about its centre of mass C, uniform
/// gravity and applied forces/torques: Newton's and Euler's equations
///   m v̇_WC = F_W,        I_C_B ω̇_B + ω_B × (I_C_B ω_B) = τ_B,
///   ṗ_WC = v_WC,         Ṙ_WB = R_WB hat(ω_B),
/// with F_W the total force (world frame, N) and τ_B the total torque about C (body frame,
/// N·m) [Goldstein2002, §5.5; Landau1976, §34–36]. The body frame B is any frame fixed in the
/// body with origin at C; it need not be principal (I_C_B is a full symmetric 3×3 tensor).

#include <cstddef>
#include <functional>
#include <optional>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <fmt/format.h>

#include "rigid/body/free_body_integrators.hpp"
#include "rigid/lie/so3.hpp"
#include "rigid/mass/mass_properties.hpp"

namespace rigid::body {

/// State of a rigid body: orientation R_WB (body → world), body angular velocity ω_B
/// (rad/s), position p_WC (m) and velocity v_WC (m/s) of the centre of mass in the world.
struct RigidBodyState {
  SO3d R_WB = SO3d::identity();
  Eigen::Vector3d w_B = Eigen::Vector3d::Zero();
  Eigen::Vector3d p_WC = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_WC = Eigen::Vector3d::Zero();
};

/// Force (N) and torque (N·m), both expressed in the frame named by the `AppliedLoad`.
struct Wrench {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
};

/// Frame in which an applied load's force and torque are expressed.
enum class LoadFrame { kWorld, kBody };

/// An applied load: `wrench(t, state)` returns the force and a pure torque, both expressed in
/// `frame`. The force acts at the body point `p_CQ_B` (from the COM, body coordinates, m),
/// so it also contributes the torque r × F about C with r = p_CQ expressed in `frame`;
/// `p_CQ_B = 0` (the default) applies it at the COM.
struct AppliedLoad {
  std::function<Wrench(double t, const RigidBodyState& state)> wrench;
  LoadFrame frame = LoadFrame::kWorld;
  Eigen::Vector3d p_CQ_B = Eigen::Vector3d::Zero();
};

/// The first non-finite component of a state ("R_WB.w", …, "w_B.x", …, "p_WC.x", …, "v_WC.z")
/// for the finiteness check of rigid::integrate::march; `owner` names the body.
[[nodiscard]] std::optional<integrate::NonFinite> find_nonfinite(const RigidBodyState& s,
                                                                 std::string_view owner = {});

/// Time derivative of a state: ṗ_WC = v_WC, v̇_WC (m/s²), ω̇_B (rad/s²); Ṙ_WB = R_WB hat(ω_B)
/// is implied by the state's ω_B.
struct RigidBodyAcceleration {
  Eigen::Vector3d a_WC = Eigen::Vector3d::Zero();
  Eigen::Vector3d alpha_B = Eigen::Vector3d::Zero();
};

/// Energy (J) = ½ m |v|² + ½ ωᵀ I ω − m g_W · p_WC; world linear momentum m v_WC (kg·m/s);
/// world angular momentum about the world origin R_WB I ω_B + m p_WC × v_WC (kg·m²/s);
/// ‖R_WBᵀ R_WB − 1‖_max of the stored rotation.
struct RigidBodyDiagnostics {
  double energy = 0;
  Eigen::Vector3d P_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d L_W = Eigen::Vector3d::Zero();
  double orthonormality_error = 0;
};

/// The model: mass properties (mass m in kg, COM p_BC_B and inertia I_C_B about the COM in the
/// body frame B, kg·m²), uniform gravity g_W (m/s²) and any number of applied loads. The state
/// follows the COM C; B's origin is at p_WC − R_WB p_BC_B (origin_position()).
///
/// Class invariant (checked by the constructor): valid mass properties (rigid::MassProperties,
/// the one validity check) whose principal moments pass rigid::check_rotational_moments (no
/// zero moment: the rotation of a point mass or a thin rod is undefined); g_W finite. The free
/// flow runs in the principal frame P (R_BP from MassProperties::principal_axes, or the identity
/// when I_C_B is diagonal in B).
class RigidBody {
 public:
  /// @throws rigid::Error naming the violated condition and its value.
  explicit RigidBody(const MassProperties& mass_B,
                     const Eigen::Vector3d& g_W = Eigen::Vector3d::Zero());
  /// RigidBody(MassProperties(mass, 0, I_C_B), g_W): a body frame with its origin at the COM.
  RigidBody(double mass, const Eigen::Matrix3d& I_C_B,
            const Eigen::Vector3d& g_W = Eigen::Vector3d::Zero());

  /// Adds a load. @throws rigid::Error if `load.wrench` is empty or p_CQ_B is not finite.
  void add_load(AppliedLoad load);

  [[nodiscard]] double mass() const { return mass_; }
  /// The COM p_BC_B in the body frame (m).
  [[nodiscard]] const Eigen::Vector3d& com() const { return p_BC_B_; }
  [[nodiscard]] const Eigen::Matrix3d& inertia() const { return I_C_B_; }
  [[nodiscard]] const Eigen::Vector3d& gravity() const { return g_W_; }
  /// I_C_B⁻¹ (1/(kg·m²)).
  [[nodiscard]] const Eigen::Matrix3d& inertia_inverse() const { return I_C_B_inv_; }
  [[nodiscard]] std::size_t load_count() const { return loads_.size(); }
  /// Principal moments (kg·m²) and the proper rotation R_BP whose columns are the principal
  /// axes in B: I_C_B = R_BP diag(moments) R_BPᵀ (moments ascending, or B's own diagonal when
  /// I_C_B is diagonal).
  [[nodiscard]] const Eigen::Vector3d& principal_moments() const { return I_P_; }
  [[nodiscard]] const SO3d& principal_axes() const { return R_BP_; }

  /// Total force on the body (world frame, N, gravity included) and total torque about the
  /// COM (body frame, N·m) at time t (s). @throws rigid::Error if a load returns a
  /// non-finite value (the message names the load index and t).
  [[nodiscard]] Wrench total_wrench(double t, const RigidBodyState& state) const;
  /// Accelerations from Newton's and Euler's equations at time t (s).
  [[nodiscard]] RigidBodyAcceleration acceleration(double t, const RigidBodyState& state) const;
  /// The energy ½ m |v|² + ½ ωᵀ I ω − m g·p (J): diagnose()'s, without the rest.
  [[nodiscard]] double energy(const RigidBodyState& state) const;
  [[nodiscard]] RigidBodyDiagnostics diagnose(const RigidBodyState& state) const;
  /// Position of B's origin in the world, p_WC − R_WB p_BC_B (m).
  [[nodiscard]] Eigen::Vector3d origin_position(const RigidBodyState& state) const {
    return state.p_WC - state.R_WB * p_BC_B_;
  }
  /// The free flow of the drift: (R_WB, ω_B) advanced by h with `method` in the principal frame.
  [[nodiscard]] FreeBodyState free_flow(const FreeBodyState& s, double h, FreeBodyMethod method) const;

 private:
  double mass_;
  Eigen::Vector3d p_BC_B_;
  Eigen::Matrix3d I_C_B_;
  Eigen::Matrix3d I_C_B_inv_;
  Eigen::Vector3d g_W_;
  Eigen::Vector3d I_P_;
  SO3d R_BP_ = SO3d::identity();
  bool principal_is_body_ = true;
  std::vector<AppliedLoad> loads_;
};

/// Stepping methods for `step_rigid_body`.
///
/// | method      | order | what it keeps                                                      |
/// |-------------|-------|--------------------------------------------------------------------|
/// | kSplitting2 | 2     | with no loads and g = 0: P_W, L_W to round-off, |q| = 1; the COM    |
/// |             |       | parabola in uniform gravity exactly; rotation = the free-body flow |
/// | kRk4        | 4     | nothing exactly (classical RK4 on (q, ω, p, v), q renormalised)      |
///
/// kSplitting2 is the Strang splitting K(h/2) D(h) K(h/2) [Hairer2006, §II.5]:
/// the kick K integrates v̇ = F_W/m, L̇_B = τ_B with p, R and t frozen by the explicit
/// midpoint rule (the exact flow when the loads do not depend on velocity); the drift D
/// is p += h v plus the free-body flow of the kinetic energy in the principal frame by
/// the free-body splitting `free_method` (exact sub-flows), and advances t by h.
enum class RigidBodyMethod { kSplitting2, kRk4 };

/// Method from its name: "splitting2" or "rk4". @throws rigid::Error listing the names.
[[nodiscard]] RigidBodyMethod rigid_body_method_from_name(std::string_view name);

/// One step from time t (s) with step h (s). `free_method` is the free-body stepper of the
/// drift of kSplitting2 (default kSplitting2; kSplitting4/6 make the free rotation more
/// accurate, the method stays order 2 with loads); ignored by kRk4.
/// @throws rigid::Error if h is not positive and finite, the state is not finite, a load
/// returns a non-finite wrench, or the drift's implicit `free_method` (midpoint,
/// moser_veselov) does not converge (step_free_body).
[[nodiscard]] RigidBodyState step_rigid_body(
    const RigidBody& body, RigidBodyMethod method, double t, const RigidBodyState& state,
    double h, FreeBodyMethod free_method = FreeBodyMethod::kSplitting2);

/// A sampled trajectory: times (s), states and diagnostics at each output time.
struct RigidBodyTrajectory {
  std::vector<double> t;
  std::vector<RigidBodyState> states;
  std::vector<RigidBodyDiagnostics> diagnostics;
};

/// Integrates from t = 0 to every entry of `output_times` (ascending, ≥ 0) by
/// rigid::integrate::march: between two output times the fewest equal steps no longer than
/// `h_max` (s), every step checked for a non-finite state.
/// @throws rigid::Error on a non-positive h_max, unordered or non-finite output times, a
/// non-finite initial state, a diverging state (naming the component and t), a load that
/// returns a non-finite wrench, a free rotation by an implicit `free_method` that does not
/// converge (step_free_body; a step's error has "at step N from t = … s: " in front);
/// rigid::Cancelled from `control`.
[[nodiscard]] RigidBodyTrajectory simulate_rigid_body(
    const RigidBody& body, RigidBodyMethod method, const RigidBodyState& initial, double h_max,
    const std::vector<double>& output_times, FreeBodyMethod free_method = FreeBodyMethod::kSplitting2,
    const integrate::MarchControl& control = {});

}  // namespace rigid::body

/// "RigidBodyState{R_WB: [w, x, y, z], w_B: [..] rad/s, p_WC: [..] m, v_WC: [..] m/s}"
template <>
struct fmt::formatter<rigid::body::RigidBodyState> : fmt::formatter<std::string_view> {
  auto format(const rigid::body::RigidBodyState& s, fmt::format_context& ctx) const
      -> decltype(ctx.out());
};

/// "Wrench{force: [..] N, torque: [..] N·m}"
template <>
struct fmt::formatter<rigid::body::Wrench> : fmt::formatter<std::string_view> {
  auto format(const rigid::body::Wrench& w, fmt::format_context& ctx) const -> decltype(ctx.out());
};
