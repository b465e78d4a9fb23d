#pragma once

/// The equations of motion of a kinematic tree, in numbers:
///   M(q) v̇ = τ + f(q, v),   f = −b(q, v) + p(q, v),
/// with M the joint-space mass matrix (armature on its diagonal), b the bias forces (Coriolis,
/// centrifugal and gravity: the τ that holds q̈ = 0) and p the passive forces of the joints
/// (−damping q̇ − stiffness (q − springref)). These are MuJoCo's qM (mj_fullM), qfrc_bias and
/// qfrc_passive, and the test suite holds them to that (hinge/slide trees, MuJoCo's humanoid
/// with its free root, ball joints).
///
/// State: q is MuJoCo's qpos (nq entries) and v its qvel (nv entries), io::RobotModel's
/// convention: a hinge or slide has one of each (v = q̇); a ball joint has the unit quaternion
/// (w, x, y, z) parent side ← link and the link's angular velocity in the link frame; a free
/// joint has the link origin's world position and the quaternion world ← link, and the
/// origin's world velocity and the angular velocity in the link frame. M, b, p, τ and v̇ have nv
/// entries. A quaternion of q must be finite and of norm 1 within 1e-6: others are refused,
/// naming the joint, rather than normalised (MuJoCo normalises), so that a q that drifted off
/// the unit sphere is seen. A quaternion's rate is q̇ = ½ q ⊗ (0, ω_link).
///
/// Algorithms [Featherstone2008, ch. 5–6]: the recursive Newton–Euler algorithm for b and the
/// inverse dynamics, the composite-rigid-body algorithm for M; spatial vectors (angular; linear)
/// expressed in the world frame at the world origin, so that one joint's motion axis is
/// S = (u, a × u) for a hinge about the unit axis u through the point a, and (0, u) for a slide.
/// A ball joint's three columns are (R e_k, a × R e_k), the link's axes R e_k through the
/// anchor a; a free joint's are (0, e_k) (world-fixed translations) and (R e_k, p × R e_k) (the
/// link's axes through its origin p). Axes that turn with the link change at the rate
/// Ṡ = V × S, V the link's spatial velocity (MuJoCo's cdof_dot).
/// Written here rather than taken from a library because the tree dynamics are the product; it
/// is the independent numeric reference of the symbolic equations of the same tree.

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rigid/io/robot_model.hpp"
#include "rigid/lie/so3.hpp"

namespace rigid::robot {

/// A link's pose in the world: p_WL (m) and R_WL.
struct LinkPose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
};

/// A tree ready for its dynamics. Immutable: every method is const and may be called from any
/// number of threads at once.
class TreeDynamics {
 public:
  /// @throws rigid::Error if the model has no joint, or a joint moves nothing: its column of
  ///   M(q_ref) is zero (a subtree without mass or inertia about that axis), naming the joint;
  ///   or a free joint is not on a root link, or a ball or free joint shares its link.
  explicit TreeDynamics(io::RobotModel model);

  [[nodiscard]] const io::RobotModel& model() const { return model_; }
  /// Degrees of freedom: nv.
  [[nodiscard]] std::size_t dof() const { return nv_; }
  /// Entries of q (qpos), io::RobotModel::coordinate_names' order.
  [[nodiscard]] std::size_t nq() const { return nq_; }
  /// Entries of v (qvel) and of every force, io::RobotModel::velocity_names' order.
  [[nodiscard]] std::size_t nv() const { return nv_; }
  /// q at which every link sits at its placement (MuJoCo's qpos0): each hinge's and slide's
  /// ref, a ball's identity (1, 0, 0, 0), a free joint's link placement (position, quaternion
  /// with w ≥ 0).
  [[nodiscard]] Eigen::VectorXd reference_configuration() const;

  /// World poses of the links at q, in the model's link order.
  [[nodiscard]] std::vector<LinkPose> link_poses(const Eigen::VectorXd& q) const;
  /// M(q), nv × nv, symmetric positive definite (kg·m², kg·m or kg per entry).
  [[nodiscard]] Eigen::MatrixXd mass_matrix(const Eigen::VectorXd& q) const;
  /// b(q, q̇): Coriolis, centrifugal and gravity forces (N·m or N).
  [[nodiscard]] Eigen::VectorXd bias_forces(const Eigen::VectorXd& q,
                                            const Eigen::VectorXd& q_dot) const;
  /// p(q, q̇) = −damping q̇ − stiffness (q − springref); a ball's or free joint's as
  /// io::RobotModel says (MuJoCo's qfrc_passive).
  [[nodiscard]] Eigen::VectorXd passive_forces(const Eigen::VectorXd& q,
                                               const Eigen::VectorXd& q_dot) const;
  /// τ = M q̈ + b − p: the joint forces that give the accelerations q̈.
  [[nodiscard]] Eigen::VectorXd inverse_dynamics(const Eigen::VectorXd& q,
                                                 const Eigen::VectorXd& q_dot,
                                                 const Eigen::VectorXd& q_ddot) const;
  /// q̈ = M⁻¹ (τ − b + p), by a Cholesky factorisation of M.
  [[nodiscard]] Eigen::VectorXd forward_dynamics(const Eigen::VectorXd& q,
                                                 const Eigen::VectorXd& q_dot,
                                                 const Eigen::VectorXd& tau) const;
  /// Kinetic energy ½ q̇ᵀ M q̇ (J, armature included).
  [[nodiscard]] double kinetic_energy(const Eigen::VectorXd& q, const Eigen::VectorXd& q_dot) const;
  /// Potential energy of gravity −Σ m g·c plus the joint springs ½ k (q − springref)² (J); a
  /// ball's or free joint's ½ k |r|² (r its rotation vector from the reference) and ½ k |p − p₀|².
  [[nodiscard]] double potential_energy(const Eigen::VectorXd& q) const;

 private:
  struct Kinematics;
  // world poses, joint axes S (6 × nv) and link spatial inertias at q
  void kinematics(const Eigen::VectorXd& q, Kinematics& k) const;
  // τ of the recursive Newton–Euler algorithm at the kinematics' q, gravity included
  [[nodiscard]] Eigen::VectorXd rnea(const Kinematics& k, const Eigen::VectorXd& q_dot,
                                     const Eigen::VectorXd& q_ddot) const;
  // M of the composite-rigid-body algorithm at the kinematics' q, armature included
  [[nodiscard]] Eigen::MatrixXd crba(const Kinematics& k) const;
  void check_sizes(const char* what, const Eigen::VectorXd& v, std::size_t n) const;

  io::RobotModel model_;
  std::size_t nq_ = 0, nv_ = 0;
  std::vector<std::size_t> first_q_;  // per link: index of its first joint's entry of q
  std::vector<std::size_t> first_v_;  // per link: index of its first joint's entry of v
  std::vector<std::size_t> link_nv_;  // per link: its joints' entries of v
  Eigen::VectorXd armature_, damping_;  // per entry of v
  Eigen::VectorXd q0_;                  // reference_configuration()
};

}  // namespace rigid::robot
