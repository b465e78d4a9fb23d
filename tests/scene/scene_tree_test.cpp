// Bodies that hang from bodies in a scene file: `parent` and [[bodies.joints]] read, passed to
// the equations and run; the refusals name file:line:col.
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "rigid/scene/model.hpp"
#include "rigid/scene/scene.hpp"
#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid::scene {
namespace {

// Two rods of 0.5 m hanging in a chain, the upper from the world, the lower from the upper: each
// frame at its rod's centre, each turning about y through its rod's top end.
constexpr std::string_view kTree = R"toml(gravity = [0, 0, -9.81]
[[coordinates]]
name = "theta1"
initial = 0.5
[[coordinates]]
name = "theta2"
initial = -0.3
velocity = 1.0
[[bodies]]
name = "upper"
primitive = "solid_cylinder"
radius = 0.02
height = 0.5
mass = 1.0
position = [0, 0, -0.25]
[[bodies.joints]]
turn = "theta1"
axis = [0, 2, 0]
anchor = [0, 0, 0.25]
[[bodies]]
name = "lower"
parent = "upper"
primitive = "solid_cylinder"
radius = 0.02
height = 0.5
mass = 0.5
position = [0, 0, -0.5]
[[bodies.joints]]
turn = "theta2"
axis = [0, 1, 0]
anchor = [0, 0, 0.25]
[simulation]
t_end = 1.0
tolerance = 1e-11
)toml";

// The same chain with each rod's world pose written out: R_y(θ) (0, 0, −d) = (−d sin θ, 0,
// −d cos θ), so the lower rod's centre is R_y(θ1) (0, 0, −0.5) + R_y(θ1 + θ2) (0, 0, −0.25).
constexpr std::string_view kWorld = R"toml(gravity = [0, 0, -9.81]
[[coordinates]]
name = "theta1"
initial = 0.5
[[coordinates]]
name = "theta2"
initial = -0.3
velocity = 1.0
[[bodies]]
name = "upper"
primitive = "solid_cylinder"
radius = 0.02
height = 0.5
mass = 1.0
position = ["-0.25*sin(theta1)", 0, "-0.25*cos(theta1)"]
rotation = [{axis = [0, 1, 0], angle = "theta1"}]
[[bodies]]
name = "lower"
primitive = "solid_cylinder"
radius = 0.02
height = 0.5
mass = 0.5
position = ["-0.5*sin(theta1) - 0.25*sin(theta1 + theta2)", 0, "-0.5*cos(theta1) - 0.25*cos(theta1 + theta2)"]
rotation = [{axis = [0, 1, 0], angle = "theta1"}, {axis = [0, 1, 0], angle = "theta2"}]
[simulation]
t_end = 1.0
tolerance = 1e-11
)toml";

TEST(SceneTree, ParentAndJointsAreRead) {
  const Scene s = parse_scene(kTree, "tree.toml");
  ASSERT_EQ(s.bodies.size(), 2u);
  EXPECT_EQ(s.bodies[0].parent, "");
  EXPECT_EQ(s.bodies[1].parent, "upper");
  EXPECT_EQ(s.bodies[1].parent_where.line, 22);
  ASSERT_EQ(s.bodies[0].joints.size(), 1u);
  const Joint& j = s.bodies[0].joints[0];
  EXPECT_EQ(j.kind, Joint::Kind::kTurn);
  EXPECT_EQ(j.amount.text, "theta1");
  // (0, 2, 0) normalised: exactly (0, 1, 0)
  EXPECT_EQ(j.axis, (std::array<double, 3>{0, 1, 0}));
  EXPECT_EQ(j.anchor, (std::array<double, 3>{0, 0, 0.25}));
  EXPECT_EQ(j.where.line, 16);
}

TEST(SceneTree, TreeRunsLikeTheWorldExpressions) {
  const Model tree(parse_scene(kTree, "tree.toml")), world(parse_scene(kWorld, "world.toml"));
  for (const auto& [a, b] : {std::pair{0.5, -0.3}, std::pair{-2.0, 1.4}, std::pair{3.0, 2.5}}) {
    const Eigen::Vector2d q(a, b), qd(0.7, -1.9);
    Eigen::MatrixXd Mt, Mw;
    Eigen::VectorXd ft, fw;
    tree.system().mass_matrix_and_forces(0.0, q, qd, Mt, ft);
    world.system().mass_matrix_and_forces(0.0, q, qd, Mw, fw);
    // |M| ≲ 0.2 kg·m², |f| ≲ 5 N·m, computed by two expression trees: a few roundings each
    EXPECT_LT((Mt - Mw).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((ft - fw).cwiseAbs().maxCoeff(), 1e-12);
  }
  const RunResult rt = tree.run(), rw = world.run();
  ASSERT_GT(rt.trajectory.rows(), 1u);
  const std::size_t last = rt.trajectory.rows() - 1;
  for (const char* column : {"theta1", "theta2"}) {
    const double a = rt.trajectory(last, rt.trajectory.column(column));
    const double b = rw.trajectory(rw.trajectory.rows() - 1, rw.trajectory.column(column));
    // both adaptive runs at tolerance 1e-11 over 1 s: the step sequences differ by round-off,
    // the results by the order of the tolerance
    EXPECT_NEAR(a, b, 1e-8) << column;
  }
}

TEST(SceneTree, SlideJointCarriesAPendulum) {
  // a cart sliding along x with a rod hanging from it: at rest the rod's weight pulls the cart
  // nowhere, and the cart's mass matrix entry is the total mass
  const Model m(parse_scene(R"toml(gravity = [0, 0, -9.81]
[[coordinates]]
name = "x"
[[coordinates]]
name = "phi"
[[bodies]]
name = "cart"
point_masses = [{mass = 2.0, position = [0, 0, 0]}]
[[bodies.joints]]
slide = "x"
axis = [1, 0, 0]
[[bodies]]
name = "rod"
parent = "cart"
point_masses = [{mass = 0.5, position = [0, 0, -1]}]
[[bodies.joints]]
turn = "phi"
axis = [0, 1, 0]
[simulation]
t_end = 0.1
)toml",
                            "cart.toml"));
  Eigen::MatrixXd M;
  Eigen::VectorXd f;
  m.system().mass_matrix_and_forces(0.0, Eigen::Vector2d(0.3, 0.4), Eigen::Vector2d::Zero(), M, f);
  // x_bob = x − sin φ, z_bob = −cos φ: M = [[2.5, −0.5 cos φ], [−0.5 cos φ, 0.5]], f = (0, −0.5 g
  // sin φ)
  EXPECT_NEAR(M(0, 0), 2.5, test::ulps(4, 2.5));
  EXPECT_NEAR(M(0, 1), -0.5 * std::cos(0.4), test::ulps(4));
  EXPECT_NEAR(M(1, 1), 0.5, test::ulps(4));
  EXPECT_NEAR(f[0], 0.0, test::ulps(4));
  EXPECT_NEAR(f[1], -0.5 * 9.81 * std::sin(0.4), test::ulps(8, 5));
  EXPECT_GT(m.run().trajectory.rows(), 1u);
}

TEST(SceneTree, DocumentedExampleRuns) {
  // the TOML block of docs/scene-format.md's section on parent and joints is a whole scene
  std::ifstream in(std::string(RIGID_EXAMPLES_DIR) + "/../docs/scene-format.md");
  std::stringstream text;
  text << in.rdbuf();
  const std::string doc = text.str();
  const std::size_t section = doc.find("#### Bodies that hang from bodies");
  ASSERT_NE(section, std::string::npos);
  const std::size_t begin = doc.find("```toml\n", section) + 8;
  const std::size_t end = doc.find("```", begin);
  const Model m(parse_scene(doc.substr(begin, end - begin), "scene-format.md"));
  ASSERT_EQ(m.system().body_names(), (std::vector<std::string>{"upper", "lower"}));
  // at θ1 = θ2 = 0 the lower rod's centre hangs 0.75 m below the pivot
  const auto poses = m.system().body_poses(0.0, Eigen::Vector2d::Zero());
  EXPECT_NEAR(poses[1].p_WB.z(), -0.75, test::ulps(4));
  EXPECT_GT(m.run().trajectory.rows(), 1u);
}

// kTree with line `line` (1-based) replaced by `text`.
std::string tree_with(int line, const std::string& text) {
  std::string out;
  int k = 0;
  std::size_t start = 0;
  while (start < kTree.size()) {
    const std::size_t end = kTree.find('\n', start);
    const std::string_view l = kTree.substr(start, end - start);
    out += ++k == line ? text : std::string(l);
    out += '\n';
    start = end + 1;
  }
  return out;
}

TEST(SceneTreeErrors, ParentMustBeAnEarlierBodyPosedByCoordinates) {
  EXPECT_RIGID_ERROR((void)parse_scene(tree_with(22, "parent = \"uper\""), "t.toml"),
                     "t.toml:22:10: body 'lower': parent 'uper' is no body of the scene; did you "
                     "mean 'upper'? (bodies declared before it: upper)");
  EXPECT_RIGID_ERROR((void)parse_scene(tree_with(22, "parent = \"lower\""), "t.toml"),
                     "t.toml:22:10: body 'lower' names itself as its parent");
  // the upper rod naming the lower one, declared after it
  EXPECT_RIGID_ERROR(
      (void)parse_scene(tree_with(10, "name = \"upper\"\nparent = \"lower\""), "t.toml"),
      "t.toml:11:10: body 'upper': parent 'lower' is declared after it (line 21)");
  EXPECT_RIGID_ERROR((void)parse_scene(tree_with(22, "parent = 3"), "t.toml"),
                     "t.toml:22:10: body 'lower' parent must be a string, got an integer");
}

TEST(SceneTreeErrors, FreeBodiesHangFromNothing) {
  constexpr std::string_view kFree = R"toml([[bodies]]
name = "a"
free = true
primitive = "solid_sphere"
radius = 0.1
mass = 1
[[bodies]]
name = "b"
free = true
parent = "a"
primitive = "solid_sphere"
radius = 0.1
mass = 1
[simulation]
t_end = 1
)toml";
  EXPECT_RIGID_ERROR((void)parse_scene(kFree, "f.toml"),
                     "f.toml:10:10: body 'b' is free, so it hangs from nothing: 'parent' is for "
                     "bodies posed by [[coordinates]]");
  std::string joints(kFree);
  joints.replace(joints.find("parent = \"a\""), 12, "joints = [{turn = 0, axis = [0, 0, 1]}]");
  EXPECT_RIGID_ERROR((void)parse_scene(joints, "f.toml"),
                     "f.toml:10:10: body 'b' is free, so it "
                     "hangs from nothing: 'joints'");
  // a body posed by coordinates hanging from a free one
  std::string mixed(kFree);
  mixed.replace(mixed.find("free = true\nparent"), 11, "position = [0, 0, 0]");
  EXPECT_RIGID_ERROR((void)parse_scene(mixed, "f.toml"),
                     "f.toml:10:10: body 'b': parent 'a' is a free body; a body hangs only from a "
                     "body posed by [[coordinates]]");
}

TEST(SceneTreeErrors, JointsAreChecked) {
  EXPECT_RIGID_ERROR((void)parse_scene(tree_with(31, "anchr = [0, 0, 0.25]"), "t.toml"),
                     "t.toml:31:1: unknown key 'anchr' in body 'lower' joint 1; did you mean "
                     "'anchor'? (expected one of: turn, slide, axis, anchor)");
  EXPECT_RIGID_ERROR((void)parse_scene(tree_with(29, "turn = \"theta2\"\nslide = 0.1"), "t.toml"),
                     "t.toml:30:9: body 'lower' joint 1 has both 'turn' and 'slide'");
  EXPECT_RIGID_ERROR((void)parse_scene(tree_with(29, ""), "t.toml"),
                     "t.toml:28:1: body 'lower' joint 1 is missing 'turn' or 'slide'");
  EXPECT_RIGID_ERROR((void)parse_scene(tree_with(30, ""), "t.toml"),
                     "t.toml:28:1: body 'lower' joint 1 is missing 'axis'");
  EXPECT_RIGID_ERROR((void)parse_scene(tree_with(30, "axis = [0, 0, 0]"), "t.toml"),
                     "t.toml:30:8: body 'lower' joint 1 axis is zero; expected a non-zero vector");
  EXPECT_RIGID_ERROR((void)parse_scene(tree_with(29, "slide = \"theta2\""), "t.toml"),
                     "t.toml:31:10: body 'lower' joint 1 slides, and a slide has no anchor");
  EXPECT_RIGID_ERROR((void)parse_scene(tree_with(29, "turn = \"\""), "t.toml"),
                     "t.toml:29:8: body 'lower' joint 1 turn is an empty expression");
  std::string not_tables(kTree);
  const std::string lower_joint =
      "[[bodies.joints]]\nturn = \"theta2\"\naxis = [0, 1, 0]\nanchor = [0, 0, 0.25]";
  ASSERT_NE(not_tables.find(lower_joint), std::string::npos);
  not_tables.replace(not_tables.find(lower_joint), lower_joint.size(), "joints = 1");
  EXPECT_RIGID_ERROR((void)parse_scene(not_tables, "t.toml"),
                     "t.toml:28:10: body 'lower' joints must be an array of tables");
  // an undefined name inside the amount, at its column
  EXPECT_RIGID_ERROR((void)Model(parse_scene(tree_with(29, "turn = \"theta3\""), "t.toml")),
                     "t.toml:29:9:");
}

}  // namespace
}  // namespace rigid::scene
