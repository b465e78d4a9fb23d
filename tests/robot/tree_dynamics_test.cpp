// robot::TreeDynamics against MuJoCo (libmujoco 2.2.2, an independent implementation loaded
// through its C API) and against closed forms: M(q) = mj_fullM (armature included), the bias
// forces = qfrc_bias, the passive forces = qfrc_passive, on trees this test writes both as an
// io::RobotModel and as MJCF.
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include "rigid/common/error.hpp"
#include "rigid/robot/tree_dynamics.hpp"
#include "support/mujoco_model.hpp"

namespace rigid::robot {
namespace {

namespace fs = std::filesystem;

using MjModel = test::MjModelPtr;
using MjData = test::MjDataPtr;

// MuJoCo's model of an MJCF text (mj_loadXML reads files: the text goes through a temporary)
MjModel load_mjcf(const std::string& xml) {
  const fs::path path = fs::temp_directory_path() / fmt::format("rigid_tree_{}.xml", ::getpid());
  std::ofstream(path) << xml;
  MjModel m = test::load_mujoco(path);
  fs::remove(path);
  return m;
}

// A random tree written twice: as the io::RobotModel under test and as MJCF for MuJoCo. Links
// have rotated frames, inertias full in their frame (diagonal in a rotated inertial frame), and
// 0 to 2 joints each (hinges through off-origin anchors, slides), with ref, damping,
// stiffness, springref and armature.
struct RandomTree {
  io::RobotModel model;
  std::string mjcf;
};

std::string numbers(const Eigen::VectorXd& v) {
  std::string s;
  for (Eigen::Index i = 0; i < v.size(); ++i) s += fmt::format("{}{:.17g}", i ? " " : "", v(i));
  return s;
}

using test::random_rotation;

io::RobotJoint random_joint(std::mt19937& rng, int index) {
  std::uniform_real_distribution<double> u(-1, 1), pos(0, 1);
  io::RobotJoint j;
  j.name = fmt::format("j{}", index);
  j.type = pos(rng) < 0.25 ? io::RobotJointType::kSlide : io::RobotJointType::kHinge;
  j.axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
  if (j.type == io::RobotJointType::kHinge)
    j.anchor = 0.2 * Eigen::Vector3d(u(rng), u(rng), u(rng));
  j.ref = 0.3 * u(rng);
  j.damping = pos(rng);
  j.stiffness = 2 * pos(rng);
  j.springref = 0.5 * u(rng);
  j.armature = 0.05 * pos(rng);
  return j;
}

std::string joint_mjcf(const io::RobotJoint& j) {
  return fmt::format(
      R"(<joint name="{}" type="{}" axis="{}" pos="{}" ref="{:.17g}" damping="{:.17g}" stiffness="{:.17g}" springref="{:.17g}" armature="{:.17g}"/>)",
      j.name, j.type == io::RobotJointType::kHinge ? "hinge" : "slide", numbers(j.axis),
      numbers(j.anchor), j.ref, j.damping, j.stiffness, j.springref, j.armature);
}

RandomTree random_tree(unsigned seed, int links) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1), pos(0, 1);
  RandomTree t;
  t.model.source = "random";
  t.model.gravity = Eigen::Vector3d(0.5, -0.3, -9.81);
  std::vector<std::string> body_xml(static_cast<std::size_t>(links));
  int joint_count = 0;
  for (int i = 0; i < links; ++i) {
    io::RobotLink l;
    l.name = fmt::format("b{}", i);
    l.parent = i == 0 ? -1 : static_cast<int>(pos(rng) * i);  // any earlier link: a tree
    const Eigen::Quaterniond q = random_rotation(rng);
    l.position = 0.3 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    l.rotation = q.toRotationMatrix();
    const int joints = i == 0 ? 1 : static_cast<int>(pos(rng) * 3);
    for (int k = 0; k < joints; ++k) l.joints.push_back(random_joint(rng, joint_count++));
    // principal moments that satisfy the triangle inequality, in a rotated inertial frame
    const Eigen::Vector3d moments(0.1 + 0.05 * pos(rng), 0.1 + 0.05 * pos(rng),
                                  0.1 + 0.05 * pos(rng));
    const Eigen::Quaterniond qi = random_rotation(rng);
    l.mass = 0.5 + 2 * pos(rng);
    l.com = 0.1 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    l.inertia_com =
        qi.toRotationMatrix() * moments.asDiagonal() * qi.toRotationMatrix().transpose();
    std::string xml =
        fmt::format(R"(<body name="{}" pos="{}" quat="{:.17g} {:.17g} {:.17g} {:.17g}">)", l.name,
                    numbers(l.position), q.w(), q.x(), q.y(), q.z());
    xml += fmt::format(
        R"(<inertial pos="{}" quat="{:.17g} {:.17g} {:.17g} {:.17g}" mass="{:.17g}" diaginertia="{}"/>)",
        numbers(l.com), qi.w(), qi.x(), qi.y(), qi.z(), l.mass, numbers(moments));
    for (const io::RobotJoint& j : l.joints) xml += joint_mjcf(j);
    body_xml[static_cast<std::size_t>(i)] = xml;
    t.model.links.push_back(std::move(l));
  }
  // nest the bodies: each closes after its subtree (links are in depth-first order only if a
  // child follows its parent's subtree: build the MJCF recursively and reorder the model alike)
  std::vector<std::vector<int>> children(static_cast<std::size_t>(links));
  for (int i = 1; i < links; ++i)
    children[static_cast<std::size_t>(t.model.links[static_cast<std::size_t>(i)].parent)].push_back(
        i);
  std::vector<io::RobotLink> ordered;
  std::vector<int> new_index(static_cast<std::size_t>(links));
  std::function<std::string(int, int)> emit = [&](int i, int parent) {
    io::RobotLink l = t.model.links[static_cast<std::size_t>(i)];
    l.parent = parent;
    new_index[static_cast<std::size_t>(i)] = static_cast<int>(ordered.size());
    ordered.push_back(std::move(l));
    std::string xml = body_xml[static_cast<std::size_t>(i)];
    for (int c : children[static_cast<std::size_t>(i)])
      xml += emit(c, new_index[static_cast<std::size_t>(i)]);
    return xml + "</body>";
  };
  const std::string bodies = emit(0, -1);
  t.model.links = std::move(ordered);
  t.mjcf = fmt::format(
      R"(<mujoco><compiler angle="radian"/><option gravity="{}"/><worldbody>{}</worldbody></mujoco>)",
      numbers(t.model.gravity), bodies);
  return t;
}

struct MuJoCoForces {
  Eigen::MatrixXd M;
  Eigen::VectorXd bias, passive;
};

MuJoCoForces mujoco_forces(const mjModel* m, const Eigen::VectorXd& q,
                           const Eigen::VectorXd& q_dot) {
  MjData d(mj_makeData(m));
  for (int i = 0; i < m->nq; ++i) d->qpos[i] = q(i);
  for (int i = 0; i < m->nv; ++i) d->qvel[i] = q_dot(i);
  mj_forward(m, d.get());
  MuJoCoForces r;
  r.M.resize(m->nv, m->nv);
  std::vector<mjtNum> dense(static_cast<std::size_t>(m->nv * m->nv));
  mj_fullM(m, dense.data(), d->qM);
  for (int i = 0; i < m->nv; ++i)
    for (int j = 0; j < m->nv; ++j) r.M(i, j) = dense[static_cast<std::size_t>(i * m->nv + j)];
  r.bias = Eigen::Map<const Eigen::VectorXd>(d->qfrc_bias, m->nv);
  r.passive = Eigen::Map<const Eigen::VectorXd>(d->qfrc_passive, m->nv);
  return r;
}

// Relative to the largest entry of the reference: the two implementations round differently
// (MuJoCo at the subtree COM, this one at the world origin), a few hundred ε of the entries'
// scale; 1e-9 is the acceptance bound and leaves room for MuJoCo's normalisations.
double relative_error(const Eigen::MatrixXd& a, const Eigen::MatrixXd& ref) {
  return (a - ref).cwiseAbs().maxCoeff() / std::max(1.0, ref.cwiseAbs().maxCoeff());
}

TEST(TreeDynamics, MatchesMuJoCoOnRandomTrees) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    SCOPED_TRACE(fmt::format("seed {}", seed));
    const RandomTree t = random_tree(seed, 7);
    const MjModel m = load_mjcf(t.mjcf);
    ASSERT_NE(m, nullptr);
    const TreeDynamics tree(t.model);
    ASSERT_EQ(static_cast<int>(tree.dof()), m->nv);
    std::mt19937 rng(seed * 77);
    std::uniform_real_distribution<double> u(-2, 2);
    for (int state = 0; state < 20; ++state) {
      Eigen::VectorXd q(m->nv), v(m->nv);
      for (int i = 0; i < m->nv; ++i) {
        q(i) = u(rng);
        v(i) = u(rng);
      }
      const MuJoCoForces ref = mujoco_forces(m.get(), q, v);
      EXPECT_LT(relative_error(tree.mass_matrix(q), ref.M), 1e-9) << tree.mass_matrix(q) << "\n\n"
                                                                  << ref.M;
      EXPECT_LT(relative_error(tree.bias_forces(q, v), ref.bias), 1e-9);
      EXPECT_LT(relative_error(tree.passive_forces(q, v), ref.passive), 1e-12);
    }
  }
}

// Inverse and forward dynamics are each other's inverse, and the inverse dynamics is M q̈ + b − p
// (three computations: RNEA with q̈, CRBA, RNEA without).
TEST(TreeDynamics, InverseAndForwardDynamicsAgree) {
  const RandomTree t = random_tree(11, 9);
  const TreeDynamics tree(t.model);
  const auto n = static_cast<Eigen::Index>(tree.dof());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int state = 0; state < 10; ++state) {
    Eigen::VectorXd q(n), v(n), a(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      q(i) = u(rng);
      v(i) = u(rng);
      a(i) = u(rng);
    }
    const Eigen::VectorXd tau = tree.inverse_dynamics(q, v, a);
    const Eigen::VectorXd expected =
        tree.mass_matrix(q) * a + tree.bias_forces(q, v) - tree.passive_forces(q, v);
    EXPECT_LT((tau - expected).cwiseAbs().maxCoeff(),
              1e-12 * std::max(1.0, tau.cwiseAbs().maxCoeff()));
    EXPECT_LT((tree.forward_dynamics(q, v, tau) - a).cwiseAbs().maxCoeff(), 1e-10);
  }
}

// Energy balance: d/dt (T + V) = −q̇ᵀ D q̇ along the motion with τ = 0 (the power of the
// damping; gravity and the springs are in V). Checked with a central difference of T + V along
// one RK4-accurate step of the forward dynamics: the identity holds only if M, b and p are
// mutually consistent (b's Coriolis part must be Ṁ q̇ − ½ ∂(q̇ᵀMq̇)/∂q).
TEST(TreeDynamics, PowerBalanceOfTheForwardDynamics) {
  const RandomTree t = random_tree(5, 6);
  const TreeDynamics tree(t.model);
  const auto n = static_cast<Eigen::Index>(tree.dof());
  Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(n, -0.7, 0.9),
                  v = Eigen::VectorXd::LinSpaced(n, 1.1, -0.4);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  auto f = [&](const Eigen::VectorXd& x) {
    Eigen::VectorXd dx(2 * n);
    dx << x.tail(n), tree.forward_dynamics(x.head(n), x.tail(n), zero);
    return dx;
  };
  auto energy = [&](const Eigen::VectorXd& x) {
    return tree.kinetic_energy(x.head(n), x.tail(n)) + tree.potential_energy(x.head(n));
  };
  auto rk4 = [&](const Eigen::VectorXd& x, double h) {
    const Eigen::VectorXd k1 = f(x), k2 = f(x + h / 2 * k1), k3 = f(x + h / 2 * k2),
                          k4 = f(x + h * k3);
    return Eigen::VectorXd(x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4));
  };
  Eigen::VectorXd x(2 * n);
  x << q, v;
  const double h = 1e-4;
  const double dE = (energy(rk4(x, h)) - energy(rk4(x, -h))) / (2 * h);
  // the damping's power −Σ d_i q̇_i² (springs are in V)
  Eigen::Index c = 0;
  double damping_power = 0;
  for (const io::RobotLink& link : tree.model().links) {
    for (const io::RobotJoint& joint : link.joints) {
      damping_power -= joint.damping * v(c) * v(c);
      ++c;
    }
  }
  // central difference error O(h²·E''') plus RK4's O(h⁵): well below 1e-6 of the power's scale
  EXPECT_NEAR(dE, damping_power, 1e-6 * std::max(1.0, std::abs(damping_power)));
}

// A pendulum: one hinge about y, a point-like mass m at distance l below a pivot at the origin,
// moment I about its COM: M = I + m l², b = m g l sin θ (θ from the hanging pose).
TEST(TreeDynamics, PendulumClosedForm) {
  io::RobotModel model;
  model.source = "pendulum";
  io::RobotLink l;
  l.name = "bob";
  l.mass = 2;
  l.com = Eigen::Vector3d(0, 0, -0.5);
  l.inertia_com = Eigen::Vector3d(0.01, 0.02, 0.03).asDiagonal();
  io::RobotJoint j;
  j.name = "theta";
  j.axis = Eigen::Vector3d::UnitY();
  l.joints.push_back(j);
  model.links.push_back(l);
  const TreeDynamics tree(model);
  for (double th : {-2.0, 0.0, 0.3, 1.4}) {
    const Eigen::VectorXd q = Eigen::VectorXd::Constant(1, th),
                          v = Eigen::VectorXd::Constant(1, 0.7);
    EXPECT_NEAR(tree.mass_matrix(q)(0, 0), 0.02 + 2 * 0.25, 1e-15);
    EXPECT_NEAR(tree.bias_forces(q, v)(0), 2 * 9.81 * 0.5 * std::sin(th), 1e-14);
  }
}

TEST(TreeDynamics, RefusesAJointThatMovesNothing) {
  io::RobotModel model;
  model.source = "arm.urdf";
  io::RobotLink l;
  l.name = "ghost";
  l.file = "arm.urdf";
  io::RobotJoint j;
  j.name = "spin";
  j.line = 12;
  l.joints.push_back(j);
  model.links.push_back(l);
  try {
    (void)TreeDynamics(model);
    FAIL() << "expected rigid::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("arm.urdf:12"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("joint 'spin' moves nothing"), std::string::npos)
        << e.what();
  }
  io::RobotModel none;
  none.source = "fixed.urdf";
  EXPECT_THROW((void)TreeDynamics(none), Error);
}

// One immutable tree, eight threads at once (ThreadSanitizer in make test): every thread's M, b
// and forward dynamics equal the serial ones bit for bit.
TEST(TreeDynamicsThreads, EightThreadsGiveTheSerialAnswers) {
  const RandomTree t = random_tree(21, 8);
  const TreeDynamics tree(t.model);
  const auto n = static_cast<Eigen::Index>(tree.dof());
  std::vector<Eigen::VectorXd> qs, vs;
  std::vector<Eigen::MatrixXd> Ms;
  std::vector<Eigen::VectorXd> bs, as;
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 16; ++k) {
    Eigen::VectorXd q(n), v(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      q(i) = u(rng);
      v(i) = u(rng);
    }
    qs.push_back(q);
    vs.push_back(v);
    Ms.push_back(tree.mass_matrix(q));
    bs.push_back(tree.bias_forces(q, v));
    as.push_back(tree.forward_dynamics(q, v, Eigen::VectorXd::Zero(n)));
  }
  std::atomic<int> mismatches{0};
  std::vector<std::thread> threads;
  for (int th = 0; th < 8; ++th) {
    threads.emplace_back([&] {
      for (int rep = 0; rep < 20; ++rep) {
        for (std::size_t k = 0; k < qs.size(); ++k) {
          if (tree.mass_matrix(qs[k]) != Ms[k] || tree.bias_forces(qs[k], vs[k]) != bs[k] ||
              tree.forward_dynamics(qs[k], vs[k], Eigen::VectorXd::Zero(n)) != as[k]) {
            ++mismatches;
          }
        }
      }
    });
  }
  for (std::thread& th : threads) th.join();
  EXPECT_EQ(mismatches.load(), 0);
}

}  // namespace
}  // namespace rigid::robot
