// Ball coordinates (Coordinate::Kind::kBall: a unit quaternion in q, the body's ω as its
// velocity) against equivalent systems written another way: what a potential or a given
// Lagrangian adds to a ball's equations (Nᵀ ∂V/∂q over the quaternion, Euler–Poincaré's
// (∂L/∂ω) × ω) equals what the same physics gives through a body's own gravity and inertia, which
// the tree's recursions derive; the kinematics q̇ = ½ q ⊗ (0, ω); the refusals.
#include <cmath>
#include <random>
#include <string>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "rigid/lagrange/system.hpp"
#include "support/expect_error.hpp"

namespace rigid::lagrange {
namespace {

// A body turning about the world origin on a ball joint 'b' (the pivot at its origin), its COM
// at d in its frame, inertia I_C about the COM (full tensor), gravity `g` along −z.
SystemSpec top(const std::string& g, const Eigen::Vector3d& d, const Eigen::Matrix3d& I_C) {
  SystemSpec spec;
  spec.parameters = {{"g", 9.81}, {"m", 2.5}};
  Coordinate ball{"b"};
  ball.kind = Coordinate::Kind::kBall;
  spec.coordinates.push_back(ball);
  Body body;
  body.name = "top";
  body.mass.mass = "m";
  for (int k = 0; k < 3; ++k) body.mass.com.e[static_cast<std::size_t>(k)] = fmt::format("{}", d[k]);
  for (std::size_t k = 0; k < 6; ++k) {
    const auto& [name, row, col] = BodyMass::kInertiaElements[k];
    body.mass.inertia[k] = fmt::format("{}", I_C(row, col));
  }
  JointMotion joint;
  joint.kind = JointMotion::Kind::kBall;
  joint.amount = "b";
  body.joints.push_back(joint);
  spec.bodies.push_back(body);
  spec.gravity_W = Vector3Expression(std::array<Expression, 3>{"0", "0", "-" + g});
  return spec;
}

const Eigen::Vector3d kCom(0.05, -0.02, 0.3);
const Eigen::Matrix3d kInertia = (Eigen::Matrix3d() << 0.04, 0.002, -0.003, 0.002, 0.05, 0.001,
                                  -0.003, 0.001, 0.02).finished();

// The largest difference of M and f of two systems over random unit quaternions and ω, relative
// to the entries' scale: the same physics through different terms, each rounded its own way
// (sums of a few dozen products: 1e-13).
double largest_difference(const System& a, const System& b) {
  std::mt19937 rng(5);
  std::normal_distribution<double> n;
  double worst = 0;
  for (int s = 0; s < 20; ++s) {
    Eigen::VectorXd q(4), v(3);
    q << n(rng), n(rng), n(rng), n(rng);
    q.normalize();
    v << 2 * n(rng), 2 * n(rng), 2 * n(rng);
    Eigen::MatrixXd Ma, Mb;
    Eigen::VectorXd fa, fb;
    a.mass_matrix_and_forces(0.0, q, v, Ma, fa);
    b.mass_matrix_and_forces(0.0, q, v, Mb, fb);
    worst = std::max({worst, (Ma - Mb).cwiseAbs().maxCoeff() / Ma.cwiseAbs().maxCoeff(),
                      (fa - fb).cwiseAbs().maxCoeff() / std::max(1.0, fa.cwiseAbs().maxCoeff())});
  }
  return worst;
}

// Gravity on the offset COM, derived by the tree, against no gravity and the potential
// V = m g (R(q) d)_z written in the quaternion's entries: a ball's generalized force is
// Nᵀ ∂V/∂q (N = ∂q̇/∂ω), the torque d × R^T(−m g e_z) of a heavy top.
TEST(BallCoordinates, APotentialOfTheQuaternionActsAsItsTorque) {
  const System heavy(top("g", kCom, kInertia));
  SystemSpec spec = top("0", kCom, kInertia);
  const std::string Rd_z = fmt::format(
      "2*(b_qx*b_qz - b_qw*b_qy)*({}) + 2*(b_qy*b_qz + b_qw*b_qx)*({}) + (1 - 2*(b_qx^2 + b_qy^2))*({})",
      kCom.x(), kCom.y(), kCom.z());
  spec.potentials.push_back({"weight", "m*g*(" + Rd_z + ")"});
  const System written(spec);
  EXPECT_EQ(written.num_coordinates(), 4);
  EXPECT_EQ(written.num_velocities(), 3);
  EXPECT_LT(largest_difference(heavy, written), 1e-13);
}

// A given Lagrangian ½ Σ a_k ω_k² in the body's axes is a body whose inertia about the pivot is
// larger by diag(a): Euler–Poincaré's (∂L/∂ω) × ω = (a ∘ ω) × ω is its gyroscopic torque.
TEST(BallCoordinates, AGivenKineticEnergyInOmegaTurnsAsInertia) {
  const Eigen::Vector3d a(0.011, 0.023, 0.037);
  const System heavier(top("g", kCom, kInertia + Eigen::Matrix3d(a.asDiagonal())));
  SystemSpec spec = top("g", kCom, kInertia);
  spec.lagrangian = fmt::format("{}/2*b_wx^2 + {}/2*b_wy^2 + {}/2*b_wz^2", a.x(), a.y(), a.z());
  const System written(spec);
  EXPECT_LT(largest_difference(heavier, written), 1e-13);
  // the torque is gyroscopic: nonzero where ω is not along a principal axis
  Eigen::MatrixXd M;
  Eigen::VectorXd f0, f1;
  const Eigen::Vector4d q(1, 0, 0, 0);
  SystemSpec bare = top("0", Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero());
  bare.lagrangian = spec.lagrangian;
  const System spinning(bare);
  spinning.mass_matrix_and_forces(0.0, q, Eigen::Vector3d(1, 2, 3), M, f0);
  // (a ∘ ω) × ω for ω = (1, 2, 3)
  const Eigen::Vector3d w(1, 2, 3);
  const Eigen::Vector3d expected = a.cwiseProduct(w).cross(w);
  EXPECT_LT((f0 - expected).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((M - Eigen::Matrix3d(a.asDiagonal())).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(BallCoordinates, KinematicsAndRefusals) {
  const System s(top("g", kCom, kInertia));
  // q̇ = ½ q ⊗ (0, ω), against Eigen's quaternion product
  const Eigen::Quaterniond Q = Eigen::Quaterniond(0.3, -0.5, 0.7, 0.4).normalized();
  const Eigen::Vector3d w(0.4, -1.1, 2.0);
  const Eigen::Quaterniond dQ = Q * Eigen::Quaterniond(0, w.x(), w.y(), w.z());
  const Eigen::VectorXd rate = s.coordinate_rates(Eigen::Vector4d(Q.w(), Q.x(), Q.y(), Q.z()), w);
  EXPECT_LT((rate - 0.5 * Eigen::Vector4d(dQ.w(), dQ.x(), dQ.y(), dQ.z())).cwiseAbs().maxCoeff(), 1e-16);
  EXPECT_EQ(s.velocity_names(), (std::vector<std::string>{"b_wx", "b_wy", "b_wz"}));
  // an initial orientation off the unit sphere
  SystemSpec off = top("g", kCom, kInertia);
  off.coordinates[0].orientation = {1, 0.1, 0, 0};
  EXPECT_RIGID_ERROR(System{off}, "ball coordinate 'b': the orientation (1, 0.1, 0, 0) has norm");
  // the expanded derivation cannot take a quasi-velocity
  SystemSpec expanded = top("g", kCom, kInertia);
  expanded.derivation = SystemSpec::Derivation::kExpanded;
  EXPECT_RIGID_ERROR(System{expanded}, "the ball coordinate 'b' needs the recursive derivation");
  // a velocity term that depends on the orientation
  SystemSpec mixed = top("g", kCom, kInertia);
  mixed.lagrangian = "b_qx*b_wy^2";
  EXPECT_RIGID_ERROR(System{mixed}, "the Lagrangian's velocity-dependent part depends on the ball "
                                    "coordinate's 'b_qx'");
  // a turn moved by a ball coordinate, a ball that turns nothing
  SystemSpec turn = top("g", kCom, kInertia);
  turn.bodies[0].joints[0].kind = JointMotion::Kind::kTurn;
  EXPECT_RIGID_ERROR(System{turn}, "joint 0 is a turn by the ball coordinate 'b'");
  // constraints on a system with a ball
  SystemSpec held = top("g", kCom, kInertia);
  held.constraints.push_back({"level", "b_qx"});
  EXPECT_RIGID_ERROR(System{held}, "constraints of a system with ball coordinates (here 'b'");
  // the state's sizes: q has four entries, the velocities three
  Eigen::MatrixXd M;
  Eigen::VectorXd f;
  EXPECT_RIGID_ERROR(s.mass_matrix_and_forces(0.0, Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(3), M, f),
                     "expected q of size 4 (four per ball coordinate) and q_dot of size 3");
}

}  // namespace
}  // namespace rigid::lagrange
