// Bodies that hang from bodies (Body::parent, Body::joints): the same double pendulum written
// with world expressions and as a tree, a 3D chain checked against a numeric Jacobian
// M = Σ m Jvᵀ Jv + Jωᵀ I Jω written here, and the refusals.
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "rigid/lagrange/linearize.hpp"
#include "rigid/lagrange/system.hpp"
#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid::lagrange {
namespace {

using Kind = JointMotion::Kind;

// A link: mass m (kg), its COM at (0, 0, −c) in its frame (m) and a diagonal inertia about the
// COM (kg·m²), as exact fractions so that both ways of writing a model print the same numbers.
BodyMass link_mass(const char* m, const char* c, std::array<const char*, 3> I) {
  BodyMass b;
  b.mass = m;
  b.com = Vector3Expression(std::array<Expression, 3>{"0", "0", fmt::format("-({})", c)});
  b.inertia = {I[0], I[1], I[2], "0", "0", "0"};
  return b;
}

// A planar double pendulum of two links in the x–z plane turning about y, θ2 relative to link 1,
// written the existing way: each frame's world position and rotations as expressions. Link 1's
// frame sits at the pivot, link 2's at the elbow R_y(θ1) (0, 0, −l1) = (−l1 sin θ1, 0, −l1 cos θ1)
// with l1 = 0.7 m.
SystemSpec double_pendulum_in_world() {
  SystemSpec spec;
  spec.parameters = {{"g", 9.81}};
  spec.coordinates = {{"theta1", 0.3, 0.0}, {"theta2", -0.2, 0.0}};
  spec.gravity_W = Vector3Expression(std::array<Expression, 3>{"0", "0", "-g"});
  Body link1{"link1",
             link_mass("3/2", "7/20", {"3/50", "7/100", "1/50"}),
             {"0", "0", "0"},
             {AxisRotation{Eigen::Vector3d::UnitY(), "theta1"}}};
  Body link2{"link2",
             link_mass("4/5", "1/4", {"1/50", "3/100", "3/200"}),
             {"-7/10*sin(theta1)", "0", "-7/10*cos(theta1)"},
             {AxisRotation{Eigen::Vector3d::UnitY(), "theta1"},
              AxisRotation{Eigen::Vector3d::UnitY(), "theta2"}}};
  spec.bodies = {link1, link2};
  return spec;
}

// The same pendulum as a tree: link 1 turns about y through the pivot; link 2 hangs from link 1
// with its frame on link 1's and turns about y through the elbow (0, 0, −l1) of that frame, so
// its COM is at (0, 0, −l1 − 0.25) in its own frame.
SystemSpec double_pendulum_as_tree() {
  SystemSpec spec = double_pendulum_in_world();
  Body& link1 = spec.bodies[0];
  link1.rotations.clear();
  link1.joints = {
      JointMotion{Kind::kTurn, Eigen::Vector3d::UnitY(), Eigen::Vector3d::Zero(), "theta1"}};
  Body& link2 = spec.bodies[1];
  link2.position = {"0", "0", "0"};
  link2.rotations.clear();
  link2.mass.com[2] = "-(7/10 + 1/4)";
  link2.parent = "link1";
  link2.joints = {
      JointMotion{Kind::kTurn, Eigen::Vector3d::UnitY(), Eigen::Vector3d(0, 0, -0.7), "theta2"}};
  return spec;
}

TEST(BodyTree, DoublePendulumAsTreeEqualsWorldExpressions) {
  const System world(double_pendulum_in_world()), tree(double_pendulum_as_tree());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-3.0, 3.0), rate(-4.0, 4.0);
  for (int k = 0; k < 6; ++k) {
    const Eigen::Vector2d q(angle(rng), angle(rng)), qd(rate(rng), rate(rng));
    Eigen::MatrixXd Mw, Mt;
    Eigen::VectorXd fw, ft;
    world.mass_matrix_and_forces(0.0, q, qd, Mw, fw);
    tree.mass_matrix_and_forces(0.0, q, qd, Mt, ft);
    // the same physical quantities by two expression trees: a few roundings of terms of size
    // |M| ≲ 1 kg·m², |f| ≲ 30 N·m; 1e-12 leaves a margin of ~100 over that
    EXPECT_LT((Mw - Mt).cwiseAbs().maxCoeff(), 1e-12) << "q = " << q.transpose();
    EXPECT_LT((fw - ft).cwiseAbs().maxCoeff(), 1e-12) << "q = " << q.transpose();
    // the world poses of the two links agree (link 2's frame differs: compare its COM)
    const auto pw = world.body_poses(0.0, q), pt = tree.body_poses(0.0, q);
    EXPECT_LT((pw[0].p_WB - pt[0].p_WB).norm(), 1e-15);
    EXPECT_LT((pw[1].R_WB.matrix() - pt[1].R_WB.matrix()).cwiseAbs().maxCoeff(), test::ulps(8));
    const Eigen::Vector3d com_w = pw[1].p_WB + pw[1].R_WB.matrix() * Eigen::Vector3d(0, 0, -0.25);
    const Eigen::Vector3d com_t = pt[1].p_WB + pt[1].R_WB.matrix() * Eigen::Vector3d(0, 0, -0.95);
    EXPECT_LT((com_w - com_t).norm(), test::ulps(16));
  }
  // both simplify to the same printed equations
  const Equations ew = world.equations(), et = tree.equations();
  EXPECT_EQ(ew.text, et.text);
  EXPECT_EQ(ew.energy_text, et.energy_text);
}

// ---------------------------------------------------------------------------------------------
// A spatial chain: link A turns about z through an anchor; link B (on A, moved and tilted) turns
// about y through an anchor, then slides along its x; link C (on B) turns about x through an
// anchor. Forward kinematics is written again here with Eigen, independently of the System.

struct Link {
  std::string name, parent;
  Eigen::Vector3d position;
  Eigen::Vector3d rotation_axis;  // one fixed rotation (angle below), or zero for none
  double rotation_angle = 0;
  std::vector<JointMotion> joints;  // amounts are single coordinates, numbered in `coordinate`
  std::vector<int> coordinate;
  double m;
  Eigen::Vector3d com;
  Eigen::Matrix3d I;  // about the COM, in the link frame
};

std::vector<Link> spatial_chain() {
  Eigen::Matrix3d IA, IB, IC;
  IA << 0.05, 0.004, -0.002, 0.004, 0.04, 0.001, -0.002, 0.001, 0.03;
  IB << 0.02, -0.001, 0.0, -0.001, 0.025, 0.002, 0.0, 0.002, 0.01;
  IC << 0.008, 0.0, 0.001, 0.0, 0.006, 0.0, 0.001, 0.0, 0.004;
  return {
      {"A",
       "",
       {0.1, -0.05, 0.2},
       {0, 0, 0},
       0,
       {{Kind::kTurn, {0, 0, 1}, {0.05, 0.02, 0}, "q1"}},
       {0},
       2.0,
       {0.1, 0.02, -0.15},
       IA},
      {"B",
       "A",
       {0.0, 0.1, -0.3},
       {1, 0, 0},
       0.3,
       {{Kind::kTurn, {0, 1, 0}, {0.0, 0.0, 0.1}, "q2"},
        {Kind::kSlide, {1, 0, 0}, {0, 0, 0}, "q3"}},
       {1, 2},
       1.2,
       {0.15, 0, -0.05},
       IB},
      {"C",
       "B",
       {0.3, 0, 0},
       {0, 0, 0},
       0,
       {{Kind::kTurn, {1, 0, 0}, {0.2, 0.0, -0.1}, "q4"}},
       {3},
       0.7,
       {0.05, 0.1, -0.1},
       IC},
  };
}

SystemSpec spatial_chain_spec() {
  SystemSpec spec;
  spec.parameters = {{"g", 9.81}};
  for (const char* q : {"q1", "q2", "q3", "q4"}) spec.coordinates.push_back({q, 0.0, 0.0});
  spec.gravity_W = Vector3Expression(std::array<Expression, 3>{"0", "0", "-g"});
  for (const Link& l : spatial_chain()) {
    Body b;
    b.name = l.name;
    b.parent = l.parent;
    b.mass = BodyMass(MassProperties(l.m, l.com, l.I));
    b.position = {fmt::format("{}", l.position.x()), fmt::format("{}", l.position.y()),
                  fmt::format("{}", l.position.z())};
    if (l.rotation_angle != 0) {
      b.rotations = {AxisRotation{l.rotation_axis, fmt::format("{}", l.rotation_angle)}};
    }
    b.joints = l.joints;
    spec.bodies.push_back(b);
  }
  return spec;
}

// The world pose of each link at q: X_WB = X_WP Trans(position) Rot(rotation) J₁ ⋯ J_m.
std::vector<Eigen::Isometry3d> chain_poses(const Eigen::VectorXd& q) {
  std::vector<Eigen::Isometry3d> X;
  const std::vector<Link> links = spatial_chain();
  for (std::size_t b = 0; b < links.size(); ++b) {
    const Link& l = links[b];
    Eigen::Isometry3d T = b > 0 ? X[b - 1] : Eigen::Isometry3d::Identity();  // parent = previous
    T.translate(l.position);
    if (l.rotation_angle != 0)
      T.rotate(Eigen::AngleAxisd(l.rotation_angle, l.rotation_axis.normalized()));
    for (std::size_t j = 0; j < l.joints.size(); ++j) {
      const JointMotion& J = l.joints[j];
      const double a = q[l.coordinate[j]];
      if (J.kind == Kind::kTurn) {
        T.translate(J.anchor);
        T.rotate(Eigen::AngleAxisd(a, J.axis.normalized()));
        T.translate(-J.anchor);
      } else {
        T.translate(a * J.axis.normalized());
      }
    }
    X.push_back(T);
  }
  return X;
}

// M(q) = Σ m Jvᵀ Jv + Jωᵀ I Jω with Jv = ∂c/∂q and the columns of Jω = (R_WBᵀ ∂R_WB/∂q_i)ˇ, both
// by central differences with step h = 1e-5 (truncation h²/6 · |c'''| ≲ 1e-11 m, round-off
// ε/h ≈ 2e-11).
Eigen::MatrixXd numeric_mass_matrix(const Eigen::VectorXd& q) {
  constexpr double h = 1e-5;
  const int n = static_cast<int>(q.size());
  const std::vector<Link> links = spatial_chain();
  const std::vector<Eigen::Isometry3d> X = chain_poses(q);
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
  std::vector<Eigen::MatrixXd> Jv(links.size(), Eigen::MatrixXd(3, n)),
      Jw(links.size(), Eigen::MatrixXd(3, n));
  for (int i = 0; i < n; ++i) {
    Eigen::VectorXd qp = q, qm = q;
    qp[i] += h;
    qm[i] -= h;
    const auto Xp = chain_poses(qp), Xm = chain_poses(qm);
    for (std::size_t b = 0; b < links.size(); ++b) {
      Jv[b].col(i) = (Xp[b] * links[b].com - Xm[b] * links[b].com) / (2 * h);
      const Eigen::Matrix3d W =
          X[b].linear().transpose() * (Xp[b].linear() - Xm[b].linear()) / (2 * h);
      Jw[b].col(i) = Eigen::Vector3d(W(2, 1) - W(1, 2), W(0, 2) - W(2, 0), W(1, 0) - W(0, 1)) / 2;
    }
  }
  for (std::size_t b = 0; b < links.size(); ++b) {
    M += links[b].m * Jv[b].transpose() * Jv[b] + Jw[b].transpose() * links[b].I * Jw[b];
  }
  return M;
}

// V(q) = −Σ m g·c with g = (0, 0, −9.81).
double chain_potential(const Eigen::VectorXd& q) {
  const std::vector<Link> links = spatial_chain();
  const auto X = chain_poses(q);
  double V = 0;
  for (std::size_t b = 0; b < links.size(); ++b) V += links[b].m * 9.81 * (X[b] * links[b].com).z();
  return V;
}

TEST(BodyTree, SpatialChainMassMatrixMatchesNumericJacobians) {
  const System sys(spatial_chain_spec());
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> angle(-3.0, 3.0), slide(-0.2, 0.2);
  for (int k = 0; k < 5; ++k) {
    Eigen::VectorXd q(4);
    q << angle(rng), angle(rng), slide(rng), angle(rng);
    Eigen::MatrixXd M;
    Eigen::VectorXd f;
    sys.mass_matrix_and_forces(0.0, q, Eigen::VectorXd::Zero(4), M, f);
    // |M| ≲ 1 kg·m²; the differences above are good to ~1e-10
    EXPECT_LT((M - numeric_mass_matrix(q)).cwiseAbs().maxCoeff(), 1e-9) << "q = " << q.transpose();
    // at rest f = −∂V/∂q, by central differences (h = 1e-6: h² |V'''| ≲ 1e-11, ε|V|/h ≲ 1e-9)
    for (int i = 0; i < 4; ++i) {
      Eigen::VectorXd qp = q, qm = q;
      qp[i] += 1e-6;
      qm[i] -= 1e-6;
      EXPECT_NEAR(f[i], -(chain_potential(qp) - chain_potential(qm)) / 2e-6, 1e-8) << "i = " << i;
    }
    // the world poses are the forward kinematics
    const auto poses = sys.body_poses(0.0, q);
    const auto X = chain_poses(q);
    for (std::size_t b = 0; b < 3; ++b) {
      EXPECT_LT((poses[b].p_WB - X[b].translation()).norm(), test::ulps(32)) << "body " << b;
      EXPECT_LT((poses[b].R_WB.matrix() - X[b].linear()).cwiseAbs().maxCoeff(), test::ulps(32));
    }
  }
}

TEST(BodyTree, SpatialChainVelocityTermsAreTheLagrangian) {
  // f at q̇ ≠ 0: f_i = ½ q̇ᵀ ∂M/∂q_i q̇ − (Ṁ q̇)_i − ∂V/∂q_i (T = ½ q̇ᵀ M q̇), with ∂M/∂q from the
  // System's own M by central differences (h = 1e-5: h² |M'''| ≲ 1e-10, ε|M|/h ≈ 2e-11); M
  // itself is checked against independent Jacobians above
  const System sys(spatial_chain_spec());
  Eigen::VectorXd q(4), qd(4);
  q << 0.4, -1.1, 0.07, 2.0;
  qd << 1.3, -0.7, 0.4, 2.1;
  Eigen::MatrixXd M;
  Eigen::VectorXd f, f0;
  sys.mass_matrix_and_forces(0.0, q, qd, M, f);
  sys.mass_matrix_and_forces(0.0, q, Eigen::VectorXd::Zero(4), M, f0);
  constexpr double h = 1e-5;
  std::vector<Eigen::MatrixXd> dM(4);
  for (int i = 0; i < 4; ++i) {
    Eigen::VectorXd qp = q, qm = q, unused;
    qp[i] += h;
    qm[i] -= h;
    Eigen::MatrixXd Mp, Mm;
    sys.mass_matrix_and_forces(0.0, qp, qd, Mp, unused);
    sys.mass_matrix_and_forces(0.0, qm, qd, Mm, unused);
    dM[static_cast<std::size_t>(i)] = (Mp - Mm) / (2 * h);
  }
  Eigen::MatrixXd Mdot = Eigen::MatrixXd::Zero(4, 4);
  for (int j = 0; j < 4; ++j) Mdot += dM[static_cast<std::size_t>(j)] * qd[j];
  for (int i = 0; i < 4; ++i) {
    const double expected =
        0.5 * qd.dot(dM[static_cast<std::size_t>(i)] * qd) - (Mdot * qd)[i] + f0[i];
    EXPECT_NEAR(f[i], expected, 1e-8) << "i = " << i;
  }
}

TEST(BodyTree, JointWithoutParentIsAMotionInTheWorld) {
  // a joint with no parent is the body's own motion in the world: the pendulum link 1 written
  // with a joint and with a rotation prints the same equations
  SystemSpec a = double_pendulum_in_world(), b = double_pendulum_in_world();
  a.bodies.resize(1);
  b.bodies.resize(1);
  b.bodies[0].rotations.clear();
  b.bodies[0].joints = {
      JointMotion{Kind::kTurn, Eigen::Vector3d::UnitY(), Eigen::Vector3d::Zero(), "theta1"}};
  a.coordinates.resize(1);
  b.coordinates.resize(1);
  EXPECT_EQ(System(a).equations().text, System(b).equations().text);
}

TEST(BodyTreeErrors, ParentMustBeDeclaredBefore) {
  SystemSpec spec = double_pendulum_as_tree();
  std::swap(spec.bodies[0], spec.bodies[1]);
  EXPECT_RIGID_ERROR(System{spec},
                     "body 'link2' names the parent 'link1', which is declared after it");
  spec = double_pendulum_as_tree();
  spec.bodies[1].parent = "lnk1";
  EXPECT_RIGID_ERROR(
      System{spec},
      "body 'link2' names the parent 'lnk1', which is no body; did you mean 'link1'?");
  spec.bodies[1].parent = "link2";
  EXPECT_RIGID_ERROR(System{spec}, "body 'link2' names itself as its parent");
}

TEST(BodyTreeErrors, JointAxisAndAmount) {
  SystemSpec spec = double_pendulum_as_tree();
  spec.bodies[1].joints[0].axis = Eigen::Vector3d::Zero();
  EXPECT_RIGID_ERROR(System{spec},
                     "body 'link2' joint 0: the axis must be a non-zero finite vector");
  spec = double_pendulum_as_tree();
  spec.bodies[1].joints[0].anchor.x() = std::nan("");
  EXPECT_RIGID_ERROR(System{spec}, "body 'link2' joint 0: the anchor must be finite");
  spec = double_pendulum_as_tree();
  spec.bodies[1].joints[0].amount = "theta2_dot";
  EXPECT_RIGID_ERROR(System{spec}, "depends on the velocity 'theta2_dot'");
  spec.bodies[1].joints[0].amount = "theta3";
  EXPECT_RIGID_ERROR(System{spec}, "body 'link2' joint 0 turn");
}

// The spatial chain with its constant rotation as an orientation (the recursion takes joints
// and constant frames only), a damper, spring potentials (one on q1, which would otherwise be
// cyclic: q1 turns about the vertical) and a rotor's ½ J q̇₁² in L.
SystemSpec chain_with_extras(SystemSpec::Derivation derivation) {
  SystemSpec spec = spatial_chain_spec();
  const std::vector<Link> links = spatial_chain();
  for (std::size_t b = 0; b < links.size(); ++b) {
    spec.bodies[b].rotations.clear();
    if (links[b].rotation_angle != 0) {
      spec.bodies[b].orientation =
          Eigen::AngleAxisd(links[b].rotation_angle, links[b].rotation_axis.normalized()).toRotationMatrix();
    }
  }
  spec.forces = {{"q2", "-3/10*q2_dot"}};
  spec.potentials = {{"spring", "2*q3^2 + 1 - cos(q1)"}};
  spec.lagrangian = "1/20*q1_dot^2";
  spec.derivation = derivation;
  return spec;
}

TEST(BodyTreeRecursive, EqualsTheExpandedLagrangian) {
  // two derivations of one model: Lagrange's equations of the expanded T − V, and the tree's
  // recursions (composite inertias, Newton–Euler) on named intermediates. Both tapes round
  // differently; |M| ≲ 1 kg·m², |f| ≲ 100 N·m, so 1e-12 of the largest entry is ~1e3 ulps
  const System expanded(chain_with_extras(SystemSpec::Derivation::kExpanded));
  const System recursive(chain_with_extras(SystemSpec::Derivation::kRecursive));
  EXPECT_TRUE(expanded.equations().intermediates.empty());
  EXPECT_FALSE(recursive.equations().intermediates.empty());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int k = 0; k < 6; ++k) {
    Eigen::VectorXd q(4), qd(4);
    for (int i = 0; i < 4; ++i) {
      q[i] = u(rng);
      qd[i] = 2 * u(rng);
    }
    q[2] /= 10;  // the slide, in m
    Eigen::MatrixXd Me, Mr;
    Eigen::VectorXd fe, fr;
    expanded.mass_matrix_and_forces(0.0, q, qd, Me, fe);
    recursive.mass_matrix_and_forces(0.0, q, qd, Mr, fr);
    EXPECT_LT((Me - Mr).cwiseAbs().maxCoeff(), 1e-12 * Me.cwiseAbs().maxCoeff()) << Me << "\n\n" << Mr;
    EXPECT_LT((fe - fr).cwiseAbs().maxCoeff(), 1e-12 * std::max(1.0, fe.cwiseAbs().maxCoeff()))
        << fe.transpose() << "\n" << fr.transpose();
    const double E = expanded.energy(0.0, q, qd);
    EXPECT_NEAR(recursive.energy(0.0, q, qd), E, 1e-12 * std::max(1.0, std::abs(E)));
    const double h = expanded.jacobi_integral(0.0, q, qd);
    EXPECT_NEAR(recursive.jacobi_integral(0.0, q, qd), h, 1e-12 * std::max(1.0, std::abs(h)));
    const auto Pe = expanded.body_poses(0.0, q), Pr = recursive.body_poses(0.0, q);
    ASSERT_EQ(Pe.size(), Pr.size());
    for (std::size_t b = 0; b < Pe.size(); ++b) {
      EXPECT_LT((Pe[b].p_WB - Pr[b].p_WB).norm(), test::ulps(64));
      EXPECT_LT((Pe[b].R_WB.matrix() - Pr[b].R_WB.matrix()).cwiseAbs().maxCoeff(), test::ulps(64));
    }
  }
}

TEST(BodyTreeRecursive, ModesEqualTheExpandedLagrangians) {
  // K = −∂f/∂q and C = −∂f/∂q̇: symbolic derivatives of the expanded f, forward-mode derivatives
  // of the recursion's tape; the equilibrium and the eigenvalues agree to the search's and the
  // eigensolver's rounding (1e-9 relative)
  const NormalModes e = normal_modes(System(chain_with_extras(SystemSpec::Derivation::kExpanded)));
  const NormalModes r = normal_modes(System(chain_with_extras(SystemSpec::Derivation::kRecursive)));
  EXPECT_LT((e.q - r.q).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((e.K - r.K).cwiseAbs().maxCoeff(), 1e-9 * e.K.cwiseAbs().maxCoeff());
  EXPECT_LT((e.C - r.C).cwiseAbs().maxCoeff(), 1e-9 * std::max(1.0, e.C.cwiseAbs().maxCoeff()));
  ASSERT_EQ(e.eigenvalues.size(), r.eigenvalues.size());
  for (Eigen::Index k = 0; k < e.eigenvalues.size(); ++k) {
    EXPECT_LT(std::abs(e.eigenvalues[k] - r.eigenvalues[k]), 1e-9 * std::max(1.0, std::abs(e.eigenvalues[k])));
  }
}

TEST(BodyTreeRecursive, GrowsLinearlyWithTheDepth) {
  // a chain of n links turning about alternating axes: the recursion's tape grows by about the
  // same number of instructions per link (a link's intermediates use its parent's only), so
  // doubling the depth at most doubles it plus a bounded remainder (M has n² entries of six
  // products each: 6n² instructions of the 2n chain's tape, allowed for)
  auto chain = [](int n) {
    SystemSpec spec;
    spec.gravity_W = Vector3Expression(Eigen::Vector3d(0, 0, -9.81));
    for (int i = 0; i < n; ++i) {
      spec.coordinates.push_back({fmt::format("q{}", i + 1), 0.1, 0.0});
      Body b;
      b.name = fmt::format("l{}", i + 1);
      b.parent = i ? fmt::format("l{}", i) : "";
      b.position = {"0", "0", i ? "-1/5" : "0"};
      b.mass = BodyMass(MassProperties(1.0, Eigen::Vector3d(0.01, 0, -0.1),
                                       Eigen::Vector3d(0.01, 0.02, 0.015).asDiagonal()));
      b.joints = {JointMotion{Kind::kTurn, i % 2 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY(),
                              Eigen::Vector3d::Zero(), fmt::format("q{}", i + 1)}};
      spec.bodies.push_back(b);
    }
    return spec;
  };
  const std::size_t t8 = System(chain(8)).tape_size(), t16 = System(chain(16)).tape_size();
  EXPECT_LT(static_cast<double>(t16), 2.0 * static_cast<double>(t8) + 6.0 * 16 * 16)
      << t8 << " → " << t16;
}

TEST(BodyTreeRecursive, RefusedWhereItDoesNotApplyWithTheReason) {
  SystemSpec spec = spatial_chain_spec();  // link B turns by a constant rotation
  spec.derivation = SystemSpec::Derivation::kRecursive;
  EXPECT_RIGID_ERROR(System{spec}, "body 'B' turns by `rotations`; give its motion as joints");
  spec = chain_with_extras(SystemSpec::Derivation::kRecursive);
  spec.bodies[1].joints[0].amount = "2*q2";
  EXPECT_RIGID_ERROR(System{spec}, "moves by '2*q2', which is not a coordinate");
}

}  // namespace
}  // namespace rigid::lagrange
