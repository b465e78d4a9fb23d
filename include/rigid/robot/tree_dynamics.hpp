#pragma once

/// The equations of motion of a kinematic tree, in numbers:
///   M(q) q̈ = τ + f(q, q̇),   f = −b(q, q̇) + p(q, q̇),
/// with M the joint-space mass matrix (armature on its diagonal), b the bias forces (Coriolis,
/// centrifugal and gravity: the τ that holds q̈ = 0) and p the passive forces of the joints
/// (−damping q̇ − stiffness (q − springref)). These are MuJoCo's qM (mj_fullM), qfrc_bias and
/// qfrc_passive for hinge/slide trees, and the test suite holds them to that.
///
/// Algorithms [Featherstone2008, ch. 5–6]: the recursive Newton–Euler algorithm for b and the
/// inverse dynamics, the composite-rigid-body algorithm for M; spatial vectors (angular; linear)
/// expressed in the world frame at the world origin, so that one joint's motion axis is
/// S = (u, a × u) for a hinge about the unit axis u through the point a, and (0, u) for a slide.
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
  ///   M(q_ref) is zero (a subtree without mass or inertia about that axis), naming the joint.
  explicit TreeDynamics(io::RobotModel model);

  [[nodiscard]] const io::RobotModel& model() const { return model_; }
  /// Number of coordinates n (the joints, in io::RobotModel's coordinate order).
  [[nodiscard]] std::size_t dof() const { return n_; }
  /// q at which every link sits at its placement (each joint's ref).
  [[nodiscard]] Eigen::VectorXd reference_configuration() const;

  /// World poses of the links at q, in the model's link order.
  [[nodiscard]] std::vector<LinkPose> link_poses(const Eigen::VectorXd& q) const;
  /// M(q), n × n, symmetric positive definite (kg·m², kg·m or kg per entry).
  [[nodiscard]] Eigen::MatrixXd mass_matrix(const Eigen::VectorXd& q) const;
  /// b(q, q̇): Coriolis, centrifugal and gravity forces (N·m or N).
  [[nodiscard]] Eigen::VectorXd bias_forces(const Eigen::VectorXd& q,
                                            const Eigen::VectorXd& q_dot) const;
  /// p(q, q̇) = −damping q̇ − stiffness (q − springref).
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
  /// Potential energy of gravity −Σ m g·c plus the joint springs ½ k (q − springref)² (J).
  [[nodiscard]] double potential_energy(const Eigen::VectorXd& q) const;

 private:
  struct Kinematics;
  // world poses, joint axes S (6 × n) and link spatial inertias at q
  void kinematics(const Eigen::VectorXd& q, Kinematics& k) const;
  // τ of the recursive Newton–Euler algorithm at the kinematics' q, gravity included
  [[nodiscard]] Eigen::VectorXd rnea(const Kinematics& k, const Eigen::VectorXd& q_dot,
                                     const Eigen::VectorXd& q_ddot) const;
  // M of the composite-rigid-body algorithm at the kinematics' q, armature included
  [[nodiscard]] Eigen::MatrixXd crba(const Kinematics& k) const;
  void check_sizes(const char* what, const Eigen::VectorXd& v) const;

  io::RobotModel model_;
  std::size_t n_ = 0;
  std::vector<std::size_t> first_dof_;  // per link: index of its first joint's coordinate
};

}  // namespace rigid::robot
