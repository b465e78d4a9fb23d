// robot::regressor and robot::base_parameters against robot::TreeDynamics (the recursive
// Newton–Euler algorithm on spatial inertias, written independently of the regressor's
// per-parameter wrenches) and against the closed form of a planar two-link arm.
//
// Tolerances: Y π and TreeDynamics' τ sum the same physical terms in different orders, so they
// differ by round-off of the largest term, a few ε × (|Y| |π|); 1e-12 of that (and of |τ|)
// leaves a factor ~1e3 of headroom for the depth of the humanoid's tree. Y_b β carries in
// addition the round-off of K (a least-squares solve on a well-conditioned W_I), the same order.
// Measured: at most 2.3e-15 for both, on every model and state below.
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <Eigen/SVD>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "rigid/common/error.hpp"
#include "rigid/io/robot_model.hpp"
#include "rigid/robot/regressor.hpp"
#include "rigid/robot/tree_dynamics.hpp"
#include "support/expect_error.hpp"

namespace rigid::robot {
namespace {

namespace fs = std::filesystem;

const fs::path kExamples = fs::path(RIGID_TEST_DATA_DIR).parent_path().parent_path() / "examples";
const fs::path kModels = "/usr/share/mujoco/model";  // Debian's libmujoco-samples

// A tree with slides and hinges, several joints on one body, hinges through off-origin anchors,
// rotated body frames, an inertial off the body origin and every passive term, in MJCF (degrees).
constexpr const char* kSliders = R"(<mujoco model="sliders">
  <option gravity="0.3 -0.2 -9.81"/>
  <worldbody>
    <body name="cart" pos="0.1 0 0.2">
      <joint name="rail" type="slide" axis="1 0.2 0" damping="0.7" armature="0.3" stiffness="5"
             springref="0.1"/>
      <inertial pos="0.02 0.01 -0.03" mass="2" diaginertia="0.02 0.03 0.04"/>
      <body name="arm" pos="0 0.1 0" euler="10 20 30">
        <joint name="swing" type="hinge" axis="0 1 0" pos="0.05 0 0" damping="0.1"
               armature="0.01" ref="5"/>
        <joint name="reach" type="slide" axis="0 0 1" stiffness="3" springref="0.05"/>
        <inertial pos="0 0.01 -0.2" quat="0.9 0.1 0.3 0.2" mass="1.2"
                  diaginertia="0.011 0.013 0.004"/>
        <body name="hand" pos="0 0 -0.4" euler="0 40 0">
          <joint name="wrist" type="hinge" axis="1 0 1"/>
          <joint name="twist" type="hinge" axis="0 0 1" pos="0.01 0.02 0" damping="0.02"/>
          <inertial pos="0.01 0 -0.05" mass="0.5" diaginertia="0.001 0.002 0.0025"/>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>)";

// A floating base with every passive term on its free joint, a ball joint below it and one on
// the world (data/floating.xml)
const fs::path kFloating = fs::path(RIGID_TEST_DATA_DIR).parent_path() / "robot" / "data" / "floating.xml";

struct NamedModel {
  std::string name;
  io::RobotModel model;
};

std::vector<NamedModel> models() {
  io::RobotReadOptions pin;
  pin.pin_free_root = true;
  const std::string humanoid = (kModels / "humanoid" / "humanoid.xml").string();
  return {
      {"arm7", io::read_robot_model_file((kExamples / "arm7.urdf").string())},
      {"cart_arm", io::read_robot_model_file((kExamples / "cart_arm.urdf").string())},
      {"humanoid", io::read_robot_model_file(humanoid, pin)},
      {"humanoid (free root)", io::read_robot_model_file(humanoid)},
      {"sliders", io::read_robot_model(kSliders, "sliders.xml")},
      {"floating", io::read_robot_model_file(kFloating.string())},
  };
}

struct State {
  Eigen::VectorXd q, q_dot, q_ddot;
};

// q uniform in ±2 per hinge or slide (and per coordinate of a free joint's position), a ball's
// or free joint's quaternion uniform over the rotations; q̇ and q̈ uniform in ±2
State random_state(std::mt19937& rng, const io::RobotModel& model) {
  std::uniform_real_distribution<double> u(-2, 2);
  std::normal_distribution<double> gauss;
  std::vector<double> q, v;
  for (const io::RobotLink& link : model.links) {
    for (const io::RobotJoint& joint : link.joints) {
      if (joint.type == io::RobotJointType::kFree) {
        for (int k = 0; k < 3; ++k) q.push_back(u(rng));
      }
      if (joint.type == io::RobotJointType::kFree || joint.type == io::RobotJointType::kBall) {
        Eigen::Vector4d r(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
        r.normalize();
        q.insert(q.end(), r.data(), r.data() + 4);
      } else {
        q.push_back(u(rng));
      }
      for (int k = 0; k < io::velocity_count(joint.type); ++k) v.push_back(0);
    }
  }
  const auto n = static_cast<Eigen::Index>(v.size());
  State s{Eigen::Map<const Eigen::VectorXd>(q.data(), static_cast<Eigen::Index>(q.size())),
          Eigen::VectorXd(n), Eigen::VectorXd(n)};
  for (Eigen::Index i = 0; i < n; ++i) {
    s.q_dot(i) = u(rng);
    s.q_ddot(i) = u(rng);
  }
  return s;
}

// ‖a − b‖∞ relative to the larger of ‖b‖∞ and the largest |Y| |π| (the terms summed)
double relative_error(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const Eigen::MatrixXd& Y,
                      const Eigen::VectorXd& pi) {
  const double terms = (Y.cwiseAbs() * pi.cwiseAbs()).maxCoeff();
  return (a - b).cwiseAbs().maxCoeff() / std::max(b.cwiseAbs().maxCoeff(), terms);
}

TEST(Regressor, TimesStandardParametersIsInverseDynamics) {
  std::mt19937 rng(7);
  for (const NamedModel& m : models()) {
    const TreeDynamics tree(m.model);
    const StandardParameters pi = standard_parameters(m.model);
    for (int k = 0; k < 5; ++k) {
      const State s = random_state(rng, m.model);
      const Eigen::MatrixXd Y = regressor(m.model, s.q, s.q_dot, s.q_ddot);
      ASSERT_EQ(Y.cols(), pi.values.size());
      const Eigen::VectorXd tau = tree.inverse_dynamics(s.q, s.q_dot, s.q_ddot);
      EXPECT_LT(relative_error(Y * pi.values, tau, Y, pi.values), 1e-12) << m.name;
    }
  }
}

TEST(Regressor, DoesNotDependOnTheParameters) {
  // Y is kinematics only: another model with other inertials and passive terms has the same Y,
  // and Y times its parameters is its τ
  io::RobotModel other = io::read_robot_model(kSliders, "sliders.xml");
  const io::RobotModel model = other;
  for (io::RobotLink& link : other.links) {
    link.mass *= 1.7;
    link.com = Eigen::Vector3d(0.03, -0.02, 0.1);
    link.inertia_com = Eigen::Vector3d(0.02, 0.03, 0.035).asDiagonal();
    for (io::RobotJoint& j : link.joints) {
      j.armature += 0.2;
      j.damping += 0.3;
      j.stiffness += 4;
    }
  }
  std::mt19937 rng(11);
  const State s = random_state(rng, model);
  const Eigen::MatrixXd Y = regressor(model, s.q, s.q_dot, s.q_ddot);
  EXPECT_EQ(Y, regressor(other, s.q, s.q_dot, s.q_ddot));
  const Eigen::VectorXd pi = standard_parameters(other).values;
  EXPECT_LT(
      relative_error(Y * pi, TreeDynamics(other).inverse_dynamics(s.q, s.q_dot, s.q_ddot), Y, pi),
      1e-12);
}

TEST(Regressor, StandardParametersAreAboutTheLinkOrigin) {
  // cart_arm's cart: m 5, COM (0, 0, 0.05), I_C diag (0.05, 0.08, 0.1); parallel axes
  const StandardParameters s =
      standard_parameters(io::read_robot_model_file((kExamples / "cart_arm.urdf").string()));
  const auto value = [&](const std::string& name) {
    for (std::size_t i = 0; i < s.names.size(); ++i) {
      if (s.names[i] == name) return s.values(static_cast<Eigen::Index>(i));
    }
    ADD_FAILURE() << "no parameter " << name;
    return 0.0;
  };
  EXPECT_EQ(value("m_cart"), 5);
  EXPECT_DOUBLE_EQ(value("mz_cart"), 0.25);
  EXPECT_DOUBLE_EQ(value("Ixx_cart"), 0.05 + 5 * 0.05 * 0.05);
  EXPECT_DOUBLE_EQ(value("Izz_cart"), 0.1);
  EXPECT_EQ(value("fv_x"), 2);
  EXPECT_EQ(s.names.front(), "m_cart");  // the massless rail has no parameters
}

TEST(BaseParameters, ReproduceInverseDynamicsWithFullColumnRank) {
  std::mt19937 rng(3);
  for (const NamedModel& m : models()) {
    const TreeDynamics tree(m.model);
    const BaseParameters base = base_parameters(m.model);
    const auto r = static_cast<Eigen::Index>(base.rank);
    const auto n = static_cast<Eigen::Index>(tree.dof());
    ASSERT_EQ(base.independent.size() + base.dependent.size() + base.unidentifiable.size(),
              static_cast<std::size_t>(base.standard.values.size()));
    // Y_b β = τ at states the base parameters were not computed from
    constexpr Eigen::Index kStates = 40;
    Eigen::MatrixXd Yb_stack(kStates * n, r), Y_stack(kStates * n, base.standard.values.size());
    for (Eigen::Index k = 0; k < kStates; ++k) {
      const State s = random_state(rng, m.model);
      const Eigen::MatrixXd Y = regressor(m.model, s.q, s.q_dot, s.q_ddot);
      const Eigen::MatrixXd Yb = base.reduce(Y);
      const Eigen::VectorXd tau = tree.inverse_dynamics(s.q, s.q_dot, s.q_ddot);
      EXPECT_LT(relative_error(Yb * base.values, tau, Y, base.standard.values), 1e-12) << m.name;
      Y_stack.middleRows(k * n, n) = Y;
      Yb_stack.middleRows(k * n, n) = Yb;
    }
    // Y_b has full column rank, well clear of the rank tolerance; and r is the numerical rank
    // of the stacked Y by its singular values (an independent rank decision), at the same
    // tolerance
    // (singular values copied to std::vector: GCC 12 sees a null dereference in sb(0))
    const Eigen::VectorXd sb_e = Eigen::BDCSVD<Eigen::MatrixXd>(Yb_stack).singularValues();
    const std::vector<double> sb(sb_e.data(), sb_e.data() + sb_e.size());
    ASSERT_EQ(sb.size(), static_cast<std::size_t>(r));
    EXPECT_GT(sb.back() / sb.front(), 1e3 * base.rank_tolerance) << m.name;
    const Eigen::VectorXd sy_e = Eigen::BDCSVD<Eigen::MatrixXd>(Y_stack).singularValues();
    const std::vector<double> sy(sy_e.data(), sy_e.data() + sy_e.size());
    Eigen::Index rank = 0;
    for (double s : sy) rank += s > base.rank_tolerance * sy.front() ? 1 : 0;
    EXPECT_EQ(rank, r) << m.name;
    // the decision's margins: structural dependencies at round-off, chosen columns far above
    EXPECT_LT(base.largest_dependent, 1e-3 * base.rank_tolerance) << m.name;
    EXPECT_GT(base.smallest_independent, 1e3 * base.rank_tolerance) << m.name;
    // β = C π, each row the independent parameter plus dependent ones
    for (Eigen::Index i = 0; i < r; ++i) {
      EXPECT_EQ(base.combination(i, static_cast<Eigen::Index>(base.independent[i])), 1);
      for (std::size_t u : base.unidentifiable) {
        EXPECT_EQ(base.combination(i, static_cast<Eigen::Index>(u)), 0);
      }
    }
  }
}

TEST(BaseParameters, AreDeterministic) {
  const io::RobotModel model = io::read_robot_model_file((kExamples / "arm7.urdf").string());
  const BaseParameters a = base_parameters(model), b = base_parameters(model);
  EXPECT_EQ(a.independent, b.independent);
  EXPECT_EQ(a.combination, b.combination);  // bit for bit
}

// A planar 2R arm: hinges about parallel z axes, link 2's origin at (l1, 0, 0) in link 1's
// frame, gravity in the plane (−y). Khalil & Dombre 2002 (ch. 9, the regrouping rules): with
// armature, the inertial base parameters are 7,
//   ZZR1 = Izz1 + Ia1 + m2 l1²,  MXR1 = mx1 + m2 l1,  MY1,  ZZ2,  MX2,  MY2,  Ia2,
// (Ia1 has Izz1's column, m2 only moves link 1 as a point mass at link 2's origin; gravity in
// the plane makes MY1 identifiable); this parameterisation adds each joint's damping fv and
// stiffness k (identifiable: their columns q̇_j, q_j − springref_j): 7 + 4 = 11. m1, mz and the
// inertias other than Izz of both links do not move τ (13 unidentifiable); Ia1 and m2 are the
// dependent ones.
TEST(BaseParameters, PlanarTwoLinkArmClosedForm) {
  const double l1 = 0.7;
  io::RobotModel model;
  model.source = "planar2r";
  model.gravity = Eigen::Vector3d(0, -9.81, 0);
  io::RobotLink link1, link2;
  link1.name = "link1";
  link1.mass = 2.0;
  link1.com = Eigen::Vector3d(0.3, 0.02, 0.01);
  link1.inertia_com = Eigen::Vector3d(0.01, 0.05, 0.055).asDiagonal();
  link1.joints.push_back(io::RobotJoint{
      .name = "j1", .damping = 0.2, .stiffness = 1.5, .springref = 0.1, .armature = 0.03});
  link2 = link1;
  link2.name = "link2";
  link2.parent = 0;
  link2.position = Eigen::Vector3d(l1, 0, 0);
  link2.mass = 1.3;
  link2.com = Eigen::Vector3d(0.25, -0.01, 0.0);
  link2.joints.front().name = "j2";
  model.links = {link1, link2};

  const BaseParameters base = base_parameters(model);
  ASSERT_EQ(base.rank, 11u);
  const auto index = [&](const std::string& name) {
    for (std::size_t i = 0; i < base.standard.names.size(); ++i) {
      if (base.standard.names[i] == name) return static_cast<Eigen::Index>(i);
    }
    ADD_FAILURE() << "no parameter " << name;
    return Eigen::Index{0};
  };
  std::vector<std::string> independent;
  for (std::size_t i : base.independent) independent.push_back(base.standard.names[i]);
  EXPECT_EQ(independent, (std::vector<std::string>{"mx_link1", "my_link1", "Izz_link1", "fv_j1",
                                                   "k_j1", "mx_link2", "my_link2", "Izz_link2",
                                                   "Ia_j2", "fv_j2", "k_j2"}));
  std::vector<std::string> dependent, unidentifiable;
  for (std::size_t i : base.dependent) dependent.push_back(base.standard.names[i]);
  for (std::size_t i : base.unidentifiable) unidentifiable.push_back(base.standard.names[i]);
  EXPECT_EQ(dependent, (std::vector<std::string>{"Ia_j1", "m_link2"}));
  EXPECT_EQ(unidentifiable.size(), 13u);

  // the rows of ZZR1 and MXR1: coefficients 1 (Ia1) and l1² (m2); 1 and l1; nothing else.
  // 1e-12 relative: K is a least-squares solve on a well-conditioned 11-column W_I
  const auto row = [&](const std::string& name) {
    for (std::size_t i = 0; i < base.rank; ++i) {
      if (base.independent[i] == static_cast<std::size_t>(index(name))) {
        return static_cast<Eigen::Index>(i);
      }
    }
    ADD_FAILURE() << name << " is not independent";
    return Eigen::Index{0};
  };
  const Eigen::Index zz1 = row("Izz_link1"), mx1 = row("mx_link1");
  EXPECT_NEAR(base.combination(zz1, index("Ia_j1")), 1, 1e-12);
  EXPECT_NEAR(base.combination(zz1, index("m_link2")), l1 * l1, 1e-12);
  EXPECT_NEAR(base.combination(mx1, index("m_link2")), l1, 1e-12);
  EXPECT_EQ(base.combination.row(zz1).cwiseAbs().sum() > 0, true);
  EXPECT_EQ((base.combination.row(zz1).array() != 0).count(), 3);  // Izz1, Ia1, m2
  EXPECT_EQ((base.combination.row(mx1).array() != 0).count(), 2);  // mx1, m2
  EXPECT_EQ((base.combination.row(row("Izz_link2")).array() != 0).count(), 1);
  // their values: Izz1 about the link origin = I_C,zz + m1 (c_x² + c_y²)
  const double Izz1 = 0.055 + 2.0 * (0.3 * 0.3 + 0.02 * 0.02);
  EXPECT_NEAR(base.values(zz1), Izz1 + 0.03 + 1.3 * l1 * l1, 1e-12);
  EXPECT_NEAR(base.values(mx1), 2.0 * 0.3 + 1.3 * l1, 1e-12);
  EXPECT_EQ(base.expression(static_cast<std::size_t>(zz1)), "Izz_link1 + Ia_j1 + 0.49*m_link2");
}

TEST(Regressor, RefusesBadInput) {
  const io::RobotModel arm = io::read_robot_model_file((kExamples / "cart_arm.urdf").string());
  const Eigen::VectorXd ok = Eigen::VectorXd::Zero(3);
  EXPECT_RIGID_ERROR((void)regressor(arm, Eigen::VectorXd::Zero(2), ok, ok),
                     "q has 2 entries; the model has 3 coordinates (nq)");
  EXPECT_RIGID_ERROR((void)regressor(arm, ok, ok, Eigen::VectorXd::Constant(3, NAN)),
                     "q_ddot is not finite");
  EXPECT_RIGID_ERROR((void)base_parameters(arm, {.rank_tolerance = 0}),
                     "rank_tolerance 0 is not in (0, 1)");
  // a quaternion off the unit sphere, named by its joint, as TreeDynamics refuses it
  const io::RobotModel floating = io::read_robot_model_file(kFloating.string());
  std::mt19937 rng(5);
  State s = random_state(rng, floating);
  EXPECT_RIGID_ERROR((void)regressor(floating, s.q, s.q_dot.head(3), s.q_ddot),
                     "q_dot has 3 entries; the model has 13 velocities (nv)");
  s.q.segment<4>(3) << 1.01, 0, 0, 0;  // the root's quaternion, norm 1.01
  EXPECT_RIGID_ERROR((void)regressor(floating, s.q, s.q_dot, s.q_ddot),
                     "joint 'root' (type free): its quaternion q[3..6]");
}

}  // namespace
}  // namespace rigid::robot
