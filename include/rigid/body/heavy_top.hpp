#pragma once

/// Heavy top: a rigid body on a fixed frictionless pivot P in uniform gravity.
/// `I_B` are the principal moments about the pivot (kg·m²), `p_PC_B` the position of
/// the centre of mass C from the pivot in the body frame (m), `g_W` gravity (m/s²).
/// H = Σ L_i²/(2 I_i) + V(R), V = −m g_W · (R_WB p_PC_B).

#include <Eigen/Core>

#include "rigid/body/free_body_integrators.hpp"

namespace rigid::body {

struct HeavyTop {
  double mass = 1.0;
  Eigen::Vector3d I_B = Eigen::Vector3d::Ones();
  Eigen::Vector3d p_PC_B = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d g_W{0.0, 0.0, -9.81};
};

/// Total energy (J): kinetic + gravitational.
[[nodiscard]] double heavy_top_energy(const HeavyTop& top, const FreeBodyState& state);

/// Gravity torque about the pivot in the body frame: τ_B = p_PC_B × (m R_WBᵀ g_W) (N·m).
[[nodiscard]] Eigen::Vector3d heavy_top_torque_body(const HeavyTop& top, const Eigen::Quaterniond& q_WB);

/// One step of the symmetric splitting V(h/2) · T(h) · V(h/2): the gravity kick
/// L_B += ½h τ_B (R frozen, exact flow of V) around the free-body flow of the kinetic
/// part by `free_method` (a splitting method: each sub-flow exact). Symplectic; keeps
/// the vertical world angular momentum g_W·L_W to round-off (the kick's ΔL_W = ½h m
/// p_PC_W × g_W is ⟂ g_W and the free flow keeps L_W).
[[nodiscard]] FreeBodyState step_heavy_top(const HeavyTop& top, const FreeBodyState& state, double h,
                                           FreeBodyMethod free_method = FreeBodyMethod::kSplitting2);

}  // namespace rigid::body
