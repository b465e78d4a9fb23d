// robot::TreeDynamics with ball and free joints (nq ≠ nv, MuJoCo's qpos/qvel) against MuJoCo
// (libmujoco 2.2.2 through its C API): M = mj_fullM, −b + p = −qfrc_bias + qfrc_passive on
// MuJoCo's own humanoid with its free root and on a ball-joint tree written here; and against
// independent computations: the kinetic energy from the links' velocities, the conservation of
// momentum of a free-floating tree, the same robot read from URDF (floating) and MJCF (free).
// The symbolic equations of the same models (lagrange::System through the robot's scene, ball
// coordinates) against MuJoCo likewise, and a run of them that keeps the momentum.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include "rigid/common/error.hpp"
#include "rigid/io/robot_model.hpp"
#include "rigid/lagrange/system.hpp"
#include "rigid/robot/tree_dynamics.hpp"
#include "rigid/scene/model.hpp"
#include "rigid/scene/robot_scene.hpp"
#include "rigid/scene/scene.hpp"
#include "support/expect_error.hpp"
#include "support/mujoco_model.hpp"

namespace rigid::robot {
namespace {

namespace fs = std::filesystem;

using Vector6d = Eigen::Matrix<double, 6, 1>;

const fs::path kHumanoid = "/usr/share/mujoco/model/humanoid/humanoid.xml";

fs::path write_temp(const std::string& name, const std::string& text) {
  const fs::path path = fs::temp_directory_path() / fmt::format("rigid_fb_{}_{}", ::getpid(), name);
  std::ofstream(path) << text;
  return path;
}

// Relative to the largest entry of the reference (at least 1): the two implementations round
// differently (MuJoCo at the subtree COM, this one at the world origin) by a few hundred ε of
// the entries' scale; 1e-9 is the acceptance bound.
double relative_error(const Eigen::MatrixXd& a, const Eigen::MatrixXd& ref) {
  return (a - ref).cwiseAbs().maxCoeff() / std::max(1.0, ref.cwiseAbs().maxCoeff());
}

struct MuJoCoForces {
  Eigen::MatrixXd M;
  Eigen::VectorXd f;  // −qfrc_bias + qfrc_passive
};

MuJoCoForces mujoco_forces(const mjModel* m, const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
  test::MjDataPtr d(mj_makeData(m));
  for (int i = 0; i < m->nq; ++i) d->qpos[i] = q(i);
  for (int i = 0; i < m->nv; ++i) d->qvel[i] = v(i);
  mj_forward(m, d.get());
  MuJoCoForces r;
  std::vector<mjtNum> dense(static_cast<std::size_t>(m->nv * m->nv));
  mj_fullM(m, dense.data(), d->qM);
  r.M = Eigen::Map<const Eigen::MatrixXd>(dense.data(), m->nv, m->nv).transpose();
  r.f = Eigen::Map<const Eigen::VectorXd>(d->qfrc_passive, m->nv) -
        Eigen::Map<const Eigen::VectorXd>(d->qfrc_bias, m->nv);
  return r;
}

// The largest relative errors of M and of f = −b + p, from `dynamics(q, v)`, against MuJoCo's
// over `states` random states; q0 is the model's reference configuration, MuJoCo's qpos0 (a
// quaternion's sign aside).
template <typename Dynamics>
std::pair<double, double> compare_with_mujoco(const Eigen::VectorXd& q0, const Dynamics& dynamics,
                                              const mjModel* m, unsigned seed, int states) {
  const Eigen::VectorXd mq0 = Eigen::Map<const Eigen::VectorXd>(m->qpos0, m->nq);
  EXPECT_EQ(q0.size(), m->nq);
  if (q0.size() == m->nq) {
    EXPECT_LT((q0 - mq0).cwiseAbs().maxCoeff(), 1e-12) << q0.transpose() << "\n" << mq0.transpose();
  }
  std::mt19937 rng(seed);
  double worst_M = 0, worst_f = 0;
  for (int s = 0; s < states; ++s) {
    Eigen::VectorXd q, v;
    test::random_state(m, rng, q, v);
    const MuJoCoForces ref = mujoco_forces(m, q, v);
    const auto [M, f] = dynamics(q, v);
    worst_M = std::max(worst_M, relative_error(M, ref.M));
    worst_f = std::max(worst_f, relative_error(f, ref.f));
  }
  return {worst_M, worst_f};
}

// The same for TreeDynamics.
std::pair<double, double> compare_with_mujoco(const TreeDynamics& tree, const mjModel* m,
                                              unsigned seed, int states) {
  EXPECT_EQ(static_cast<int>(tree.nv()), m->nv);
  return compare_with_mujoco(
      tree.reference_configuration(),
      [&](const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
        return std::pair<Eigen::MatrixXd, Eigen::VectorXd>(
            tree.mass_matrix(q), tree.passive_forces(q, v) - tree.bias_forces(q, v));
      },
      m, seed, states);
}

TEST(FloatingBase, HumanoidWithItsFreeRootMatchesMuJoCo) {
  if (!fs::exists(kHumanoid)) GTEST_SKIP() << kHumanoid << " is not installed";
  const TreeDynamics tree(io::read_robot_model_file(kHumanoid));
  const test::MjModelPtr m = test::load_mujoco(kHumanoid);
  ASSERT_NE(m, nullptr);
  ASSERT_EQ(m->jnt_type[0], mjJNT_FREE);
  EXPECT_EQ(tree.nq(), 28u);
  EXPECT_EQ(tree.nv(), 27u);
  const auto [M, f] = compare_with_mujoco(tree, m.get(), 7, 24);
  fmt::print("humanoid (free root), 24 states: max relative error M {:.2e}, -b+p {:.2e}\n", M, f);
  EXPECT_LT(M, 1e-9);
  EXPECT_LT(f, 1e-9);
}

// A pendulum on a ball joint (off its body's origin, its body turned on the parent, with
// damping, stiffness and armature) carrying a hinge child, hung from a link on a hinge; and a
// second ball joint below the world.
constexpr const char* kBallTree = R"(<mujoco>
  <compiler angle="radian"/>
  <option gravity="0.3 -0.2 -9.81"/>
  <worldbody>
    <body name="base" pos="0.1 0 1" quat="0.9 0.1 -0.3 0.2">
      <joint name="yaw" type="hinge" axis="0 0 1" damping="0.3"/>
      <inertial pos="0.02 0 0" mass="3" diaginertia="0.05 0.04 0.03"/>
      <body name="bob" pos="0 0.1 -0.2" quat="0.8 0.3 0.1 -0.4">
        <joint name="swing" type="ball" pos="0.05 -0.02 0.3" damping="0.7" stiffness="2"
               armature="0.02"/>
        <inertial pos="0.01 0.02 -0.1" quat="0.7 0.1 0.6 0.2" mass="1.5"
                  diaginertia="0.02 0.03 0.04"/>
        <body name="tail" pos="0 0 -0.3" euler="0.2 0.1 0">
          <joint name="flap" type="hinge" axis="0.3 1 0.2" pos="0 0.01 0.02" stiffness="1"
                 damping="0.1"/>
          <inertial pos="0 0 -0.1" mass="0.5" diaginertia="0.005 0.006 0.007"/>
        </body>
      </body>
    </body>
    <body name="hanger" pos="-0.5 0.2 0.8">
      <joint name="cup" type="ball" stiffness="4"/>
      <inertial pos="0 0.1 -0.2" mass="0.8" diaginertia="0.01 0.012 0.014"/>
    </body>
  </worldbody>
</mujoco>
)";

TEST(FloatingBase, BallJointTreeMatchesMuJoCo) {
  const fs::path path = write_temp("ball.xml", kBallTree);
  const TreeDynamics tree(io::read_robot_model_file(path.string()));
  const test::MjModelPtr m = test::load_mujoco(path);
  fs::remove(path);
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(tree.nq(), 10u);
  EXPECT_EQ(tree.nv(), 8u);
  const auto [M, f] = compare_with_mujoco(tree, m.get(), 11, 24);
  fmt::print("ball-joint tree, 24 states: max relative error M {:.2e}, -b+p {:.2e}\n", M, f);
  EXPECT_LT(M, 1e-9);
  EXPECT_LT(f, 1e-9);
}

// q advanced by the velocity v for a time h: hinges and slides q + h v, a free joint's
// position p + h v_lin, a quaternion q ⊗ exp(h ω/2) (ω in the link frame: q̇ = ½ q ⊗ (0, ω)).
// Exact along the motion of constant v.
Eigen::VectorXd advance(const io::RobotModel& model, const Eigen::VectorXd& q,
                        const Eigen::VectorXd& v, double h) {
  Eigen::VectorXd out = q;
  Eigen::Index e = 0, c = 0;
  auto turn = [&](Eigen::Index at, const Eigen::Vector3d& w) {
    const Eigen::Quaterniond Q(q(at), q(at + 1), q(at + 2), q(at + 3));
    const double angle = h * w.norm();
    const Eigen::Quaterniond dQ = angle != 0
                                      ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, w.normalized()))
                                      : Eigen::Quaterniond::Identity();
    const Eigen::Quaterniond R = (Q * dQ).normalized();
    out.segment<4>(at) << R.w(), R.x(), R.y(), R.z();
  };
  for (const io::RobotLink& link : model.links) {
    for (const io::RobotJoint& j : link.joints) {
      switch (j.type) {
        case io::RobotJointType::kHinge:
        case io::RobotJointType::kSlide:
          out(e) += h * v(c);
          break;
        case io::RobotJointType::kBall:
          turn(e, v.segment<3>(c));
          break;
        case io::RobotJointType::kFree:
          out.segment<3>(e) += h * v.segment<3>(c);
          turn(e + 3, v.segment<3>(c + 3));
          break;
      }
      e += io::position_count(j.type);
      c += io::velocity_count(j.type);
    }
  }
  return out;
}

// Each link's world angular velocity and COM velocity, by central differences of its pose along
// the motion q(t) = advance(q, v, t): independent of the motion subspaces.
struct LinkVelocity {
  Eigen::Vector3d w, v_com;
};
std::vector<LinkVelocity> link_velocities(const TreeDynamics& tree, const Eigen::VectorXd& q,
                                          const Eigen::VectorXd& v, double h) {
  const auto plus = tree.link_poses(advance(tree.model(), q, v, h));
  const auto minus = tree.link_poses(advance(tree.model(), q, v, -h));
  std::vector<LinkVelocity> out;
  for (std::size_t i = 0; i < plus.size(); ++i) {
    const io::RobotLink& l = tree.model().links[i];
    const Eigen::AngleAxisd d(plus[i].rotation * minus[i].rotation.transpose());
    out.push_back(
        {d.angle() * d.axis() / (2 * h), ((plus[i].position + plus[i].rotation * l.com) -
                                          (minus[i].position + minus[i].rotation * l.com)) /
                                             (2 * h)});
  }
  return out;
}

// ½ vᵀ M v is Σ ½ m |v_c|² + ½ ωᵀ I ω of the links (armature aside: the humanoid's is taken out
// of M), with velocities from finite differences of the poses: the free joint's convention
// (world linear velocity of the origin, body angular velocity) enters only through `advance`.
TEST(FloatingBase, KineticEnergyIsTheLinksKineticEnergy) {
  if (!fs::exists(kHumanoid)) GTEST_SKIP() << kHumanoid << " is not installed";
  const TreeDynamics tree(io::read_robot_model_file(kHumanoid));
  const test::MjModelPtr m = test::load_mujoco(kHumanoid);
  ASSERT_NE(m, nullptr);
  Eigen::VectorXd armature(tree.nv());
  Eigen::Index c = 0;
  for (const auto& l : tree.model().links) {
    for (const auto& j : l.joints) {
      for (int k = 0; k < io::velocity_count(j.type); ++k) armature(c++) = j.armature;
    }
  }
  std::mt19937 rng(3);
  for (int s = 0; s < 5; ++s) {
    Eigen::VectorXd q, v;
    test::random_state(m.get(), rng, q, v);
    const double T =
        0.5 * v.dot((tree.mass_matrix(q) - Eigen::MatrixXd(armature.asDiagonal())) * v);
    const auto poses = tree.link_poses(q);
    const auto vel = link_velocities(tree, q, v, 1e-5);
    double T_links = 0;
    for (std::size_t i = 0; i < vel.size(); ++i) {
      const io::RobotLink& l = tree.model().links[i];
      const Eigen::Matrix3d I = poses[i].rotation * l.inertia_com * poses[i].rotation.transpose();
      T_links += 0.5 * l.mass * vel[i].v_com.squaredNorm() + 0.5 * vel[i].w.dot(I * vel[i].w);
    }
    // central differences with h = 1e-5: truncation O(h²) ~ 1e-10 of the velocities squared,
    // rounding ~ ε/h ~ 1e-11 relative: 1e-8 of T is a safe bound
    EXPECT_NEAR(T, T_links, 1e-8 * T) << "state " << s;
  }
}

// Inverse and forward dynamics of the free-root humanoid are each other's inverse, and the
// inverse dynamics is M v̇ + b − p (RNEA with v̇ against CRBA and RNEA without).
TEST(FloatingBase, InverseAndForwardDynamicsAgree) {
  if (!fs::exists(kHumanoid)) GTEST_SKIP() << kHumanoid << " is not installed";
  const TreeDynamics tree(io::read_robot_model_file(kHumanoid));
  const test::MjModelPtr m = test::load_mujoco(kHumanoid);
  ASSERT_NE(m, nullptr);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int s = 0; s < 5; ++s) {
    Eigen::VectorXd q, v;
    test::random_state(m.get(), rng, q, v);
    Eigen::VectorXd a(tree.nv());
    for (Eigen::Index i = 0; i < a.size(); ++i) a(i) = u(rng);
    const Eigen::VectorXd tau = tree.inverse_dynamics(q, v, a);
    const Eigen::VectorXd expected =
        tree.mass_matrix(q) * a + tree.bias_forces(q, v) - tree.passive_forces(q, v);
    // sums of a few dozen terms of the entries' scale: 1e-12 of the largest
    EXPECT_LT((tau - expected).cwiseAbs().maxCoeff(),
              1e-12 * std::max(1.0, tau.cwiseAbs().maxCoeff()));
    // the solve loses up to cond(M) ~ 1e4 (the humanoid's light hands on its heavy torso): 1e-9
    EXPECT_LT((tree.forward_dynamics(q, v, tau) - a).cwiseAbs().maxCoeff(), 1e-9);
  }
}

// A free body carrying a ball-jointed link and a hinged one, no gravity: no external force, so
// the total momentum (Σ I_i V_i, spatial, about the world origin) is constant along the motion.
constexpr const char* kFloatingChain = R"(<mujoco>
  <compiler angle="radian"/>
  <option gravity="0 0 0"/>
  <worldbody>
    <body name="hub" pos="0.2 -0.1 0.5" quat="0.9 0.2 0.1 -0.3">
      <freejoint name="root"/>
      <inertial pos="0.03 -0.02 0.01" quat="0.8 0.1 0.5 0.3" mass="2" diaginertia="0.04 0.05 0.06"/>
      <body name="arm" pos="0.2 0 0" quat="0.9 0 0.3 0.1">
        <joint name="shoulder" type="ball" pos="-0.05 0 0" damping="0.4" stiffness="1.5"/>
        <inertial pos="0.1 0.01 0" mass="0.7" diaginertia="0.003 0.01 0.011"/>
        <body name="hand" pos="0.2 0 0">
          <joint name="wrist" type="hinge" axis="0 0.6 0.8" damping="0.2" stiffness="3"/>
          <inertial pos="0.05 0 0.02" mass="0.3" diaginertia="0.001 0.002 0.0025"/>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>
)";

Vector6d total_momentum(const TreeDynamics& tree, const Eigen::VectorXd& q,
                        const Eigen::VectorXd& v) {
  // Σ m v_c (linear) and Σ (c × m v_c + I ω) (angular, about the origin), link velocities
  // from finite differences of the poses (h = 1e-6: O(h²) ~ 1e-12 relative)
  const auto poses = tree.link_poses(q);
  const auto vel = link_velocities(tree, q, v, 1e-6);
  Vector6d h = Vector6d::Zero();
  for (std::size_t i = 0; i < vel.size(); ++i) {
    const io::RobotLink& l = tree.model().links[i];
    const Eigen::Vector3d c = poses[i].position + poses[i].rotation * l.com;
    const Eigen::Matrix3d I = poses[i].rotation * l.inertia_com * poses[i].rotation.transpose();
    h.head<3>() += c.cross(l.mass * vel[i].v_com) + I * vel[i].w;
    h.tail<3>() += l.mass * vel[i].v_com;
  }
  return h;
}

// The largest change of the momentum over a march of `steps` RK4 steps of h with τ = 0: each
// stage's q is the start's advanced by that stage's velocity (q ← q ⊗ exp(ω dt/2)).
double momentum_drift(const TreeDynamics& tree, Eigen::VectorXd q, Eigen::VectorXd v, double h,
                      int steps) {
  const io::RobotModel& model = tree.model();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(tree.nv()));
  const Vector6d start = total_momentum(tree, q, v);
  double drift = 0;
  for (int s = 0; s < steps; ++s) {
    const Eigen::VectorXd a1 = tree.forward_dynamics(q, v, zero);
    const Eigen::VectorXd v2 = v + h / 2 * a1;
    const Eigen::VectorXd q2 = advance(model, q, v, h / 2);
    const Eigen::VectorXd a2 = tree.forward_dynamics(q2, v2, zero);
    const Eigen::VectorXd v3 = v + h / 2 * a2;
    const Eigen::VectorXd q3 = advance(model, q, v2, h / 2);
    const Eigen::VectorXd a3 = tree.forward_dynamics(q3, v3, zero);
    const Eigen::VectorXd v4 = v + h * a3;
    const Eigen::VectorXd q4 = advance(model, q, v3, h);
    const Eigen::VectorXd a4 = tree.forward_dynamics(q4, v4, zero);
    q = advance(model, q, (v + 2 * v2 + 2 * v3 + v4) / 6, h);
    v += h / 6 * (a1 + 2 * a2 + 2 * a3 + a4);
    drift = std::max(drift, (total_momentum(tree, q, v) - start).norm());
  }
  return drift;
}

TEST(FloatingBase, FreeFloatingTreeConservesMomentum) {
  const TreeDynamics tree(io::read_robot_model(kFloatingChain, "chain.xml"));
  EXPECT_EQ(tree.nq(), 12u);
  EXPECT_EQ(tree.nv(), 10u);
  Eigen::VectorXd q = tree.reference_configuration();
  q(7) = 0.8;  // the ball turned about its x axis (a unit quaternion)
  q(8) = 0.6;
  q(11) = 0.4;  // the wrist
  Eigen::VectorXd v(10);
  v << 0.3, -0.2, 0.5, 1.5, -2.0, 0.7, 3.0, -1.0, 2.0, -4.0;
  const double scale = total_momentum(tree, q, v).norm();
  // the march's error: RK4 stages that advance the quaternion from the step's start (rather than
  // composing the stages on the group) make the scheme of order 2 in the orientation, so
  // halving h divides the drift by about 4 (measured 4.1); a wrong bias term (Ṡ v) would
  // instead change the momentum by O(1) of its scale whatever h. Over 0.1 s with h = 1e-3 the
  // drift measured is 3.4e-7 of the momentum; 1e-6 bounds it with margin.
  const double coarse = momentum_drift(tree, q, v, 2e-3, 50);
  const double fine = momentum_drift(tree, q, v, 1e-3, 100);
  fmt::print("momentum drift over 0.1 s: h = 2e-3 {:.2e}, h = 1e-3 {:.2e} (momentum {:.3f})\n",
             coarse, fine, scale);
  EXPECT_LT(fine, 1e-6 * scale);
  EXPECT_LT(fine, coarse / 3.5);
}

// One robot written twice: URDF (a world link, a floating joint to the base, a revolute child)
// and MJCF (a free body with a hinge child). The same placements, inertials and state give the
// same M, b and link poses.
constexpr const char* kUrdfFloating = R"(<?xml version="1.0"?>
<robot name="r">
  <link name="world"/>
  <link name="base">
    <inertial><origin xyz="0.02 -0.01 0.03"/><mass value="4"/>
      <inertia ixx="0.1" ixy="0.01" ixz="-0.02" iyy="0.12" iyz="0.005" izz="0.09"/></inertial>
  </link>
  <link name="arm">
    <inertial><origin xyz="0 0 -0.2"/><mass value="1"/>
      <inertia ixx="0.02" ixy="0" ixz="0" iyy="0.025" iyz="0" izz="0.01"/></inertial>
  </link>
  <joint name="root" type="floating"><parent link="world"/><child link="base"/>
    <origin xyz="0.1 0.2 1.0"/></joint>
  <joint name="elbow" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0.3 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
</robot>
)";

constexpr const char* kMjcfFree = R"(<mujoco>
  <worldbody>
    <body name="base" pos="0.1 0.2 1.0">
      <freejoint name="root"/>
      <inertial pos="0.02 -0.01 0.03" mass="4" fullinertia="0.1 0.12 0.09 0.01 -0.02 0.005"/>
      <body name="arm" pos="0.3 0 0">
        <joint name="elbow" axis="0 1 0"/>
        <inertial pos="0 0 -0.2" mass="1" diaginertia="0.02 0.025 0.01"/>
      </body>
    </body>
  </worldbody>
</mujoco>
)";

TEST(FloatingBase, UrdfFloatingReadsAsTheMjcfFreeJoint) {
  const TreeDynamics urdf(io::read_robot_model(kUrdfFloating, "r.urdf"));
  const TreeDynamics mjcf(io::read_robot_model(kMjcfFree, "r.xml"));
  ASSERT_EQ(urdf.nq(), 8u);
  ASSERT_EQ(urdf.nv(), 7u);
  EXPECT_EQ(urdf.model().coordinate_names(), mjcf.model().coordinate_names());
  EXPECT_EQ(urdf.model().velocity_names(), mjcf.model().velocity_names());
  EXPECT_EQ(urdf.reference_configuration(), mjcf.reference_configuration());
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int s = 0; s < 5; ++s) {
    Eigen::VectorXd q(8), v(7);
    const Eigen::Quaterniond r = test::random_rotation(rng);
    q << u(rng), u(rng), 1 + u(rng), r.w(), r.x(), r.y(), r.z(), 2 * u(rng);
    for (Eigen::Index i = 0; i < 7; ++i) v(i) = 2 * u(rng);
    // the same arithmetic on the same numbers (the URDF's world link adds a massless root):
    // equal to rounding, 1e-14 of entries of order 1
    EXPECT_LT((urdf.mass_matrix(q) - mjcf.mass_matrix(q)).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_LT((urdf.bias_forces(q, v) - mjcf.bias_forces(q, v)).cwiseAbs().maxCoeff(), 1e-13);
  }
}

TEST(FloatingBase, QuaternionsMustBeUnit) {
  const TreeDynamics tree(io::read_robot_model(kMjcfFree, "r.xml"));
  Eigen::VectorXd q = tree.reference_configuration();
  q(3) = 1.001;
  EXPECT_RIGID_ERROR((void)tree.mass_matrix(q),
                     "joint 'root' (type free): its quaternion q[3..6] = (1.001, 0, 0, 0) has "
                     "norm 1.001; expected a unit quaternion");
  EXPECT_RIGID_ERROR((void)tree.bias_forces(q.head(7), Eigen::VectorXd::Zero(7)),
                     "q has 7 entries; the model has 8 (entries of qpos)");
  EXPECT_RIGID_ERROR(
      (void)tree.bias_forces(tree.reference_configuration(), Eigen::VectorXd::Zero(8)),
      "q_dot has 8 entries; the model has 7");
}


// ---------------------------------------------------------------------------------------------
// The symbolic equations (lagrange::System of the robot's scene: a free joint as three slides
// and a ball coordinate, a ball joint as a ball coordinate) against MuJoCo

// The same for the symbolic equations, q and q̇ in MuJoCo's qpos and qvel.
std::pair<double, double> compare_system_with_mujoco(const lagrange::System& system, const mjModel* m,
                                                     unsigned seed, int states) {
  EXPECT_EQ(system.num_velocities(), m->nv);
  lagrange::Workspace w = system.make_workspace();
  return compare_with_mujoco(
      system.initial_q(),
      [&](const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
        std::pair<Eigen::MatrixXd, Eigen::VectorXd> Mf;
        system.mass_matrix_and_forces(w, 0.0, q, v, Mf.first, Mf.second);
        return Mf;
      },
      m, seed, states);
}

TEST(FloatingBase, SymbolicHumanoidWithItsFreeRootMatchesMuJoCo) {
  if (!fs::exists(kHumanoid)) GTEST_SKIP() << kHumanoid << " is not installed";
  const scene::Model model(scene::load_scene(kHumanoid));
  const lagrange::System& system = model.system();
  const test::MjModelPtr m = test::load_mujoco(kHumanoid);
  ASSERT_NE(m, nullptr);
  // MuJoCo's names and order: qpos, then qvel (a free joint's slides' rates, then ω)
  const TreeDynamics tree(io::read_robot_model_file(kHumanoid));
  EXPECT_EQ(system.coordinate_names(), tree.model().coordinate_names());
  ASSERT_EQ(system.velocity_names().size(), 27u);
  EXPECT_EQ(system.velocity_names()[0], "root_x_dot");
  EXPECT_EQ(system.velocity_names()[3], "root_wx");
  EXPECT_EQ(system.velocity_names()[6], "abdomen_z_dot");
  const auto [M, f] = compare_system_with_mujoco(system, m.get(), 17, 24);
  fmt::print("symbolic humanoid (free root), 24 states: max relative error M {:.2e}, -b+p {:.2e}\n", M, f);
  EXPECT_LT(M, 1e-9);
  EXPECT_LT(f, 1e-9);
}

TEST(FloatingBase, SymbolicBallJointTreeMatchesMuJoCo) {
  // the ball tree above without the balls' springs (the symbolic equations refuse them, below)
  std::string text = kBallTree;
  for (const char* spring : {R"( damping="0.7" stiffness="2")", R"( stiffness="4")"}) {
    const std::size_t at = text.find(spring);
    ASSERT_NE(at, std::string::npos) << spring;
    text.replace(at, std::string(spring).size(), std::string(spring).find("damping") != std::string::npos
                                                     ? R"( damping="0.7")"
                                                     : "");
  }
  const fs::path path = write_temp("ball_symbolic.xml", text);
  const test::MjModelPtr m = test::load_mujoco(path);
  ASSERT_NE(m, nullptr);
  const scene::Model model(scene::load_scene(path));
  const auto [M, f] = compare_system_with_mujoco(model.system(), m.get(), 19, 24);
  fmt::print("symbolic ball-joint tree, 24 states: max relative error M {:.2e}, -b+p {:.2e}\n", M, f);
  EXPECT_LT(M, 1e-9);
  EXPECT_LT(f, 1e-9);
  fs::remove(path);
  // a ball's spring (MuJoCo's, about the rotation vector) is refused where the joint is written
  const fs::path sprung = write_temp("ball_sprung.xml", kBallTree);
  EXPECT_RIGID_ERROR((void)scene::Model(scene::load_scene(sprung)),
                     fmt::format("{}:9: joint 'swing' (ball) has stiffness 2", sprung.string()));
  fs::remove(sprung);
}

// The symbolic humanoid without gravity, its root thrown and spun and its joints moving, run by
// the engine (dopri5 on q̇ = ½ q ⊗ (0, ω) and M v̇ = f): no external force acts (joint damping
// and the hinges' armature are internal), so the links' total momentum stays what it was. It is
// read off TreeDynamics' M (checked against MuJoCo above): the free joint's rows of M v are the
// momentum P (its slides along the world's axes) and the angular momentum about the root's
// origin o in the root's frame (its ball's columns (R e_k, o × R e_k)), so about the world's
// origin L = R (M v)₃…₅ + o × P. (The armature sits on the hinges' diagonal, not in these rows.)
TEST(FloatingBase, SymbolicRunOfAFreeFloatingHumanoidKeepsItsMomentum) {
  if (!fs::exists(kHumanoid)) GTEST_SKIP() << kHumanoid << " is not installed";
  scene::Scene s = scene::load_scene(kHumanoid);
  for (auto& g : s.gravity) g = scene::Expression{"0", {}, 0.0, false};
  scene::apply_overrides(s, {"root.angular_velocity=[1.5, -2, 3]", "root_x.velocity=0.4",
                             "right_knee.velocity=-2.5", "left_shoulder1.velocity=-2.5"});
  const scene::Model model(s);
  const lagrange::System& system = model.system();
  const TreeDynamics tree(io::read_robot_model_file(kHumanoid));
  // the largest change of the momentum over 1 s at dopri5's tolerance `tol`
  auto drift_at = [&](double tol, double& scale) {
    const lagrange::Trajectory tr = system.simulate(
        lagrange::SimulationOptions{.t_end = 1.0, .tolerance = tol, .output_dt = 0.05});
    EXPECT_EQ(tr.q.cols(), 28);
    EXPECT_EQ(tr.q_dot.cols(), 27);
    EXPECT_EQ(tr.t.size(), 21);
    auto momentum = [&](Eigen::Index k) {
      const Eigen::VectorXd q = tr.q.row(k).transpose();
      const Eigen::VectorXd Mv = tree.mass_matrix(q) * tr.q_dot.row(k).transpose();
      const Eigen::Quaterniond R(q(3), q(4), q(5), q(6));
      Vector6d h;
      h.head<3>() = Mv.head<3>();
      h.tail<3>() = R * Mv.segment<3>(3) + q.head<3>().cross(Mv.head<3>());
      return h;
    };
    const Vector6d start = momentum(0);
    scale = start.norm();
    double drift = 0;
    for (Eigen::Index k = 1; k < tr.t.size(); ++k) {
      EXPECT_NEAR(tr.q.row(k).segment<4>(3).norm(), 1.0, 1e-15);  // written normalised
      drift = std::max(drift, (momentum(k) - start).norm());
    }
    return drift;
  };
  double scale = 0;
  const double coarse = drift_at(1e-9, scale), fine = drift_at(1e-13, scale);
  fmt::print("symbolic free-floating humanoid, 1 s: momentum {:.4f}, largest change {:.2e} at "
             "tolerance 1e-9, {:.2e} at 1e-13\n", scale, coarse, fine);
  EXPECT_GT(scale, 1.0);
  // measured: 1.8e-13 of the scale at 1e-9 and 1.3e-14 at 1e-13, round-off of M v's sums (27
  // terms of the scale) along the run; a wrong bias force or quaternion rate would change the
  // momentum by a fraction of its scale at any tolerance
  EXPECT_LT(coarse, 1e-11 * scale);
  EXPECT_LT(fine, 1e-13 * scale);
}

}  // namespace
}  // namespace rigid::robot
