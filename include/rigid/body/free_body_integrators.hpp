#pragma once

/// Time steppers for the free (torque-free) rigid body, state (R_WB, ω_B): orientation of
/// the body's principal frame B in the world W and body angular velocity. These are the
/// principal-frame kernels: `I_B` is the diagonal of the inertia in B (the principal moments).
/// A body described in any frame (rigid::MassProperties) is stepped by rigid::body::RigidBody,
/// which rotates into its principal frame once and calls these kernels.
///
/// | method                  | order | conserves                                               |
/// |-------------------------|-------|---------------------------------------------------------|
/// | kRk4                    | 4     | |q| = 1 (projected each step); energy, |L| drift O(h⁴)  |
/// | kSplitting2 (Strang)    | 2     | L_W exactly (each sub-flow is a rotation), |L|, |q| = 1 |
/// | kSplitting4 (Yoshida)   | 4     | as kSplitting2; symplectic, energy error bounded        |
/// | kSplitting6 (Yoshida)   | 6     | as kSplitting2; symplectic, energy error bounded        |
/// | kLiePoissonMidpoint     | 2     | |L| and energy (quadratic invariants) to round-off      |
/// | kRkmk4 (Lie-group RK)   | 4     | |q| = 1 / RᵀR = 1 to round-off (update by exp); energy, |L| drift O(h⁴) |
/// | kMoserVeselov           | 2     | L_W, |L| and energy ½ L·I⁻¹L to round-off; symplectic   |
///
/// RKMK4: classical RK4 tableau on the Lie algebra, R = R0 exp(Θ̂),
/// Θ̇ = dexp⁻¹_{−Θ}(ω) ≈ ω + ½ Θ × ω + (1/12) Θ × (Θ × ω) (truncated after the terms
/// that affect order 4) [MuntheKaas1998; Iserles2000, §5]; ω by RK4 on Euler's equations.
/// Moser–Veselov: solve h L_k = 2 q0 I q + 2 q × (I q) for the unit quaternion (q0, q)
/// of Ω_k (the matrix form h M̂ = ΩJ − JΩᵀ, J = ½ tr(I) 1 − I), then
/// L_{k+1} = Ω_kᵀ L_k, R_{k+1} = R_k Ω_k [Moser1991; McLachlan2005, eq. 2.3].
///
/// Splitting: H = Σ L_i²/(2 I_i) is split into the three body-axis Hamiltonians;
/// each flow rotates L_B about e_i by −h L_i/I_i and the body by +h L_i/I_i
/// [McLachlan1993; Yoshida1990 for the compositions]. The kernel (shared with
/// `step_free_bodies`) merges neighbouring sub-flows about the same axis (they commute, since
/// each keeps its L_i): Strang 5, Yoshida-4 13 (not 15), Yoshida-6 37 (not 45) sub-flows per
/// step; each takes one sin/cos pair of the half angle θ/2 (a Maclaurin polynomial for
/// |θ/2| ≤ 0.5) from which cos θ, sin θ and the quaternion of the turn follow, and |q| is
/// restored once per step by one Newton step q ← q (3 − |q|²)/2 (no square root).

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "rigid/integrate/march.hpp"
#include "rigid/lie/so3.hpp"

namespace rigid::body {

/// Orientation R_WB (body to world) and body angular velocity w_B (rad/s) of a free rigid body.
struct FreeBodyState {
  SO3d R_WB = SO3d::identity();
  Eigen::Vector3d w_B = Eigen::Vector3d::Zero();
};

/// The first non-finite component of a state ("R_WB.w" … "R_WB.z", "w_B.x" … "w_B.z") for the
/// finiteness check of rigid::integrate::march; `owner` names the body in the message.
[[nodiscard]] std::optional<integrate::NonFinite> find_nonfinite(const FreeBodyState& s,
                                                                 std::string_view owner = {});

enum class FreeBodyMethod {
  kRk4,
  kSplitting2,
  kSplitting4,
  kSplitting6,
  kLiePoissonMidpoint,
  kRkmk4,
  kMoserVeselov
};

/// Method from its name: "rk4", "splitting2", "splitting4", "splitting6", "midpoint",
/// "rkmk4", "moser_veselov".
/// Throws rigid::Error listing the valid names otherwise.
[[nodiscard]] FreeBodyMethod free_body_method_from_name(std::string_view name);
[[nodiscard]] std::string_view name_of(FreeBodyMethod method);
/// Classical order of accuracy of the method.
[[nodiscard]] int order_of(FreeBodyMethod method);

/// One step of size h (s) with principal moments I_B (kg·m²).
///
/// The implicit methods (kLiePoissonMidpoint, kMoserVeselov) solve their equation by
/// fixed-point iteration, which contracts for h |ω| max(I)/min(I) < 1. Their iteration stops
/// when an update is below about one ulp of the solution; one that has not stopped after 100
/// iterations is accepted only if the residual of the implicit equation is at round-off,
/// 16 ε times the magnitudes of its terms (it stalled just above the stopping rule).
/// @throws rigid::Error for a midpoint or Moser–Veselov step that does not converge, naming the
/// method, h, |ω|, the residual reached relative to |L| and the tolerance, with the remedy
/// (a smaller step). rigid::integrate::march puts the step number and t in front.
/// This is the kernel of every march (simulate_free_body, RigidBody, HeavyTop) and is not
/// checked per call: pass moments > 0, a finite state and h > 0. A step that diverges returns
/// a non-finite state (SO3d::invalid() for the rotation) for the caller's finiteness check
/// (find_nonfinite); step_free_bodies checks its inputs and results once per batch.
[[nodiscard]] FreeBodyState step_free_body(FreeBodyMethod method, const Eigen::Vector3d& I_B,
                                           const FreeBodyState& state, double h);

/// Diagnostics of a state: kinetic energy (J), world angular momentum L_W = R_WB I ω_B,
/// and the orthonormality defect ‖RᵀR − 1‖_max of the rotation matrix of R_WB.
struct FreeBodyDiagnostics {
  double energy = 0;
  Eigen::Vector3d L_W = Eigen::Vector3d::Zero();
  double orthonormality_error = 0;
};
[[nodiscard]] FreeBodyDiagnostics diagnose(const Eigen::Vector3d& I_B, const FreeBodyState& state);

/// A sampled trajectory: times (s), states and diagnostics at each output time.
struct FreeBodyTrajectory {
  std::vector<double> t;
  std::vector<FreeBodyState> states;
  std::vector<FreeBodyDiagnostics> diagnostics;
};

/// Integrates from t = 0 to every entry of `output_times` (ascending, ≥ 0) by
/// rigid::integrate::march: between two output times the fewest equal steps no longer than
/// `h_max` (s). Every step is checked for a non-finite state.
/// @throws rigid::Error if I_B fails rigid::check_rotational_moments, h_max is not positive and
/// finite, the output times are not ascending and finite, the state diverges (naming the
/// component and t), a step of an implicit method does not converge (step_free_body's error,
/// with the step number and t in front), or `control` cancels the run (rigid::Cancelled).
[[nodiscard]] FreeBodyTrajectory simulate_free_body(FreeBodyMethod method,
                                                    const Eigen::Vector3d& I_B,
                                                    const FreeBodyState& initial, double h_max,
                                                    const std::vector<double>& output_times,
                                                    const integrate::MarchControl& control = {});

}  // namespace rigid::body
