#pragma once

/// The inverse dynamics of a kinematic tree as a linear function of its inertial and joint
/// parameters, τ = Y(q, q̇, q̈) π, and the base (minimal, identifiable) parameters of that map:
/// what identification from measured joint forces can recover.
///
/// Standard parameters π, in this order (names with the link's or the joint's name after `_`):
///  - for each link with an inertial (mass > 0 or a non-zero inertia), in the model's link
///    order, 10 parameters in the LINK frame about the LINK origin:
///      m, m c_x, m c_y, m c_z, J_xx, J_xy, J_xz, J_yy, J_yz, J_zz
///    named m_L, mx_L, my_L, mz_L, Ixx_L, Ixy_L, Ixz_L, Iyy_L, Iyz_L, Izz_L, where c is the COM
///    and J = I_C + m (|c|² 1 − c cᵀ) the inertia matrix about the link origin (its entries as
///    the matrix holds them: J_xy = −∫ x y dm);
///  - after each link's 10, for each joint of the link (coordinate order) three joint terms:
///      Ia_J armature (kg·m² or kg), its column q̈_J;
///      fv_J viscous damping (N·m·s/rad or N·s/m), its column q̇_J;
///      k_J  stiffness (N·m/rad or N/m), its column (q_J − springref_J), springref known;
///    a ball or free joint has one of each for all its velocity entries (MuJoCo's), the
///    columns of a ball's rows ω̇, ω and the rotation vector r of its quaternion, of a free
///    joint's its six accelerations, velocities and (p − p₀, r of q₀⁻¹ ⊗ q), p₀ and q₀ its
///    link's placement (TreeDynamics::passive_forces).
///    The passive forces enter Y so that Y π is the whole τ of TreeDynamics::inverse_dynamics,
///    τ = M q̈ + b − p with p = −damping q̇ − stiffness (q − springref); the springs' springref
///    is a known constant of the model, not a parameter.
/// A link without an inertial (a frame only) has no parameters: it is not part of π.
///
/// Form of Y [Atkeson, An & Hollerbach 1986, "Estimation of inertial parameters of manipulator
/// loads and links", IJRR 5(3); Khalil & Dombre 2002, "Modeling, Identification and
/// Control of Robots", ch. 9]: the Newton–Euler wrench of link b about its origin, in its
/// frame, is linear in its 10 parameters π_b,
///   f = m a + α × (m c) + ω × (ω × m c),   n = J α + ω × (J ω) + (m c) × a,
/// with ω, α the link's angular velocity and acceleration and a the acceleration of its origin
/// less gravity; so F_b = Ψ(V_b, A_b) π_b, and τ_j = S_jᵀ Σ_{b in subtree(j)} F_b.
///
/// Every joint of io::RobotJointType: a ball's or free joint's quaternion in q (nq entries,
/// MuJoCo's qpos) and its velocities in q̇, q̈ (nv entries, qvel), as TreeDynamics takes them;
/// Y has a row per velocity. A quaternion not of unit norm is refused, naming the joint.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rigid/io/robot_model.hpp"

namespace rigid::robot {

/// The standard parameters of a model: names and the model's values, in the order above.
struct StandardParameters {
  std::vector<std::string> names;
  std::vector<std::string> units;  ///< SI: "kg", "kg·m", "kg·m²", "N·m·s/rad", ...
  Eigen::VectorXd values;
};

/// The standard parameters π of `model` (names, units, values from the model's inertials and
/// joints).
[[nodiscard]] StandardParameters standard_parameters(const io::RobotModel& model);

/// Y(q, q̇, q̈), nv × p (p standard parameters), with Y π = τ of
/// TreeDynamics::inverse_dynamics (gravity and passive forces included) for every π.
/// q (nq) in rad, m or a unit quaternion, q̇ and q̈ (nv) the velocities and their rates, in the
/// model's coordinate and velocity order.
/// @throws rigid::Error for a vector whose size is not nq (q) or nv or that is not finite, or a
///   quaternion not of unit norm, naming its joint.
[[nodiscard]] Eigen::MatrixXd regressor(const io::RobotModel& model, const Eigen::VectorXd& q,
                                        const Eigen::VectorXd& q_dot,
                                        const Eigen::VectorXd& q_ddot);

/// How the base parameters are found.
struct BaseParameterOptions {
  /// Random states whose Y are stacked; 0: automatic, ⌈3 p / n⌉ + 8 (three rows per column
  /// and a margin, so that a generic stack has the rank of the structure).
  std::size_t samples = 0;
  std::uint64_t seed = 20240611;  ///< of the random states (std::mt19937_64): deterministic
  /// A column is independent when its distance to the span of the columns chosen before it
  /// exceeds rank_tolerance × the largest column norm (the largest R diagonal of a pivoted QR);
  /// a column whose own norm is below that is unidentifiable. See base_parameters.
  double rank_tolerance = 1e-9;
};

/// The base parameters β = C π (r of them), with τ = Y_b β, Y_b = the independent columns of Y.
struct BaseParameters {
  StandardParameters standard;              ///< π (names, units, the model's values)
  std::size_t rank = 0;                     ///< r
  std::vector<std::size_t> independent;     ///< π_I: r indices into π, increasing
  std::vector<std::size_t> dependent;       ///< π_D: indices whose columns are combinations
  std::vector<std::size_t> unidentifiable;  ///< indices whose column of Y is zero
  /// K, r × |dependent|: β = π_I + K π_D (entries below 1e-10 relative set to 0, see
  /// base_parameters).
  Eigen::MatrixXd K;
  Eigen::MatrixXd combination;  ///< C, r × p: β = C π (C = [1 K] in π's order, 0 elsewhere)
  Eigen::VectorXd values;       ///< β of the model: C π
  std::size_t samples = 0;      ///< the random states stacked
  double rank_tolerance = 0;    ///< as used (BaseParameterOptions::rank_tolerance)
  /// The smallest distance of a chosen column and the largest of a dependent one, each
  /// relative to the largest column norm: the margin of the rank decision on either side.
  double smallest_independent = 0;
  double largest_dependent = 0;

  /// "beta_<i+1>": the name of base parameter i (0-based).
  [[nodiscard]] std::string name(std::size_t i) const;
  /// Base parameter i as a combination of named standard parameters, e.g.
  /// "Izz_link1 + Ia_joint1 + 0.09*m_link2 - 0.3*mx_link2" (coefficients to 12 digits).
  [[nodiscard]] std::string expression(std::size_t i) const;
  /// Y_b: the columns `independent` of a regressor Y (n × p → n × r).
  [[nodiscard]] Eigen::MatrixXd reduce(const Eigen::MatrixXd& Y) const;
};

/// The base parameters of `model` [Gautier 1990, "Numerical calculation of the base inertial
/// parameters of robots", J. Robotic Systems 7(4); Khalil & Dombre 2002, ch. 9]:
///  1. W = Y stacked at random states (q uniform in ref ± π rad or ref ± 1 m, q̇ and q̈ uniform
///     in ±1 per unit; a fixed seed, so the result is deterministic);
///  2. a Householder QR of W whose pivot is the next column, in a preference order, whose
///     distance to the span of the columns already chosen, |R_kk|, exceeds rank_tolerance ×
///     the largest column norm; the others are dependent (zero columns: unidentifiable). The
///     order is Khalil's: link by link from the root, each link's J (xx, xy, xz, yy, yz, zz),
///     then m c, then m, then its joints' Ia, fv, k. Taking the first such column rather than
///     the largest keeps the parameters of the links nearer the base and a link's inertia,
///     and groups masses and later links into them as Khalil's regrouping does
///     (Izz_1 + Ia_1 + m_2 l_1², not m_2 + Izz_1 / l_1²);
///  3. K = R_II⁻¹ R_ID from a QR of [W_I W_D], so W_D = W_I K and β = π_I + K π_D; an entry
///     with |K_ij| ‖W_i‖ < 1e-10 ‖W_j‖ (its share of the dependent column) is round-off of a
///     structural zero and set to 0.
/// The default tolerance 1e-9: a structural dependency leaves |R_kk| at round-off, about
/// √rows × ε × (the tree's depth) ≈ 1e-13 of the largest column for the stacks used here,
/// while a column that moves τ by less than 1e-9 of the largest cannot be identified from
/// data in double precision anyway; smallest_independent and largest_dependent report the
/// margin actually found.
/// A ball's random orientations are uniform over the rotations, a free joint's position its
/// placement ± 1 m per axis.
/// @throws rigid::Error for options out of range (rank_tolerance not in (0, 1)) or a model
///   without joints.
[[nodiscard]] BaseParameters base_parameters(const io::RobotModel& model,
                                             const BaseParameterOptions& options = {});

}  // namespace rigid::robot
