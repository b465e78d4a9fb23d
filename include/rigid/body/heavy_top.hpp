#pragma once

/// Heavy top: a rigid body turning about a fixed frictionless pivot P in uniform gravity.
/// State (R_WB, ω_B) in the body frame B of the body's mass properties; the centre of mass C
/// moves with it, p_WC = p_WP + R_WB p_PC_B.
/// H = ½ ω_Bᵀ I_P_B ω_B + V(R),  V = −m g_W · (R_WB p_PC_B),  with I_P_B the inertia about the
/// pivot (parallel-axis theorem from the inertia about the COM).

#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "rigid/body/free_body_integrators.hpp"
#include "rigid/mass/mass_properties.hpp"

namespace rigid::body {

/// The model of a heavy top.
///
/// Class invariant (checked by the constructor): the principal moments of the inertia about the
/// pivot pass rigid::check_rotational_moments; pivot and gravity finite. The free flow runs in
/// the principal frame P of I_P_B (R_BP from MassProperties::principal_axes, or the identity
/// when I_P_B is diagonal in B, so that a top described in its principal frame is stepped with
/// no change of frame).
class HeavyTop {
 public:
  /// `mass_B`: the body's mass properties in B (origin O); `pivot_B`: the pivot p_OP_B (m);
  /// `g_W`: gravity (m/s²).
  /// @throws rigid::Error for a non-finite pivot or gravity, or moments about the pivot that fail
  /// check_rotational_moments (e.g. a thin rod pivoted on its own axis).
  HeavyTop(const MassProperties& mass_B, const Eigen::Vector3d& pivot_B,
           const Eigen::Vector3d& g_W = Eigen::Vector3d(0.0, 0.0, -9.81));

  [[nodiscard]] double mass() const { return mass_; }
  [[nodiscard]] const Eigen::Vector3d& gravity() const { return g_W_; }
  /// p_OP_B (m).
  [[nodiscard]] const Eigen::Vector3d& pivot() const { return pivot_B_; }
  /// p_PC_B: the centre of mass from the pivot, in B (m).
  [[nodiscard]] const Eigen::Vector3d& com_from_pivot() const { return p_PC_B_; }
  /// I_P_B: the inertia about the pivot in B (kg·m²).
  [[nodiscard]] const Eigen::Matrix3d& inertia_about_pivot() const { return I_P_B_; }
  /// Principal moments about the pivot (the diagonal of the frame P, kg·m²) and R_BP.
  [[nodiscard]] const Eigen::Vector3d& principal_moments() const { return I_P_; }
  [[nodiscard]] const SO3d& principal_axes() const { return R_BP_; }

  /// Total energy (J): ½ ω_Bᵀ I_P_B ω_B − m g_W · (R_WB p_PC_B).
  [[nodiscard]] double energy(const FreeBodyState& s) const;
  /// Gravity torque about the pivot in B: τ_B = p_PC_B × (m R_WBᵀ g_W) (N·m).
  [[nodiscard]] Eigen::Vector3d torque(const SO3d& R_WB) const;
  /// Angular momentum about the pivot in the world: R_WB I_P_B ω_B (kg·m²/s).
  [[nodiscard]] Eigen::Vector3d angular_momentum_world(const FreeBodyState& s) const;

  /// One step of the symmetric splitting V(h/2) · T(h) · V(h/2): the gravity kick
  /// L_B += ½h τ_B (R frozen, the exact flow of V) around the free-body flow of the kinetic
  /// part by `free_method` (a splitting method, each sub-flow exact). Symplectic; keeps the
  /// vertical world angular momentum g_W·L_W to round-off (the kick's ΔL_W = ½h m p_PC_W × g_W
  /// is ⟂ g_W and the free flow keeps L_W).
  /// @throws rigid::Error if free_method is not splitting2/4/6.
  [[nodiscard]] FreeBodyState step(const FreeBodyState& s, double h,
                                   FreeBodyMethod free_method = FreeBodyMethod::kSplitting2) const;

  /// Integrates from t = 0 to every entry of `output_times` by rigid::integrate::march (the
  /// fewest equal steps ≤ h_max between outputs, every step checked for a non-finite state).
  /// The diagnostics' energy is the total energy and L_W is about the pivot.
  [[nodiscard]] FreeBodyTrajectory simulate(const FreeBodyState& initial, double h_max,
                                            const std::vector<double>& output_times,
                                            FreeBodyMethod free_method = FreeBodyMethod::kSplitting2,
                                            const integrate::MarchControl& control = {}) const;

 private:
  double mass_;
  Eigen::Vector3d pivot_B_, p_PC_B_, g_W_;
  Eigen::Matrix3d I_P_B_, I_P_B_inv_;
  Eigen::Vector3d I_P_;
  SO3d R_BP_ = SO3d::identity();
  bool principal_is_body_ = true;  // R_BP = 1: the free flow needs no change of frame
};

/// The splitting methods a heavy top (or any body with a torque) accepts as its free flow:
/// splitting2, splitting4, splitting6. @throws rigid::Error naming them otherwise.
void require_splitting(FreeBodyMethod free_method, std::string_view who);

}  // namespace rigid::body
