#include "rigid/scene/model.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "rigid/mass/primitive_table.hpp"
#include "rigid/mass/primitives.hpp"
#include "support/expect_error.hpp"
#include "support/scenes.hpp"
#include "support/tolerance.hpp"

namespace rigid::scene {
namespace {

Model model_of(std::string_view toml, const std::filesystem::path& file = "scene.toml") {
  return Model(parse_scene(toml, file));
}

// Parameters are evaluated in file order, each from the ones before it; numbers in
// expressions are exact (0.1 is 1/10), so the results are the correctly rounded doubles.
TEST(Model, EvaluatesParametersInFileOrder) {
  const Model m = model_of(R"toml(
[parameters]
m = 2.0
r = 0.1
I = "0.5*m*r^2"
w = "sqrt(I/m)*2*pi"
[[coordinates]]
name = "x"
initial = "r/2"
velocity = "-w"
[[bodies]]
point_masses = [{mass = "m", position = [0, 0, 0]}]
position = ["x", 0, 0]
[simulation]
t_end = 1
)toml");
  ASSERT_EQ(m.parameters().size(), 4u);
  EXPECT_EQ(m.parameters()[2].name, "I");
  EXPECT_DOUBLE_EQ(m.parameters()[2].value, 0.01);
  EXPECT_NEAR(m.parameters()[3].value, std::sqrt(0.005) * 2 * M_PI, 1e-15);
  EXPECT_DOUBLE_EQ(m.system().initial_q()[0], 0.05);
  EXPECT_NEAR(m.system().initial_q_dot()[0], -std::sqrt(0.005) * 2 * M_PI, 1e-15);
  EXPECT_EQ(m.kind(), SceneKind::kCoordinates);
  EXPECT_EQ(m.integrator(), "dopri5");
}

TEST(Model, ParameterUsingALaterOneIsAnUndefinedSymbolAtItsColumn) {
  EXPECT_RIGID_ERROR(model_of(R"toml(
[parameters]
a = "2*b"
b = 1
[[coordinates]]
name = "x"
[[bodies]]
point_masses = [{mass = 1, position = [0, 0, 0]}]
[simulation]
t_end = 1
)toml"),
                     "scene.toml:3:8: parameter a: undefined symbol 'b'");
}

TEST(Model, PrimitiveBodiesMatchTheMassFactories) {
  const Model m = model_of(R"toml(
[parameters]
rho = 7800
[[coordinates]]
name = "x"
[[bodies]]
name = "tube"
primitive = "thick_tube"
inner_radius = 0.03
outer_radius = 0.05
height = 0.3
density = "rho"
[[bodies]]
name = "box"
primitive = "solid_box"
size = [0.1, 0.2, 0.3]
mass = 2
position = ["x", 0, 0]
[simulation]
t_end = 1
)toml");
  const MassProperties tube = mass::thick_tube_with_density(7800, 0.03, 0.05, 0.3);
  const MassProperties box = mass::solid_box_with_mass(2, 0.1, 0.2, 0.3);
  ASSERT_EQ(m.bodies().size(), 2u);
  EXPECT_DOUBLE_EQ(m.bodies()[0].mass.mass(), tube.mass());
  EXPECT_TRUE(m.bodies()[0].mass.inertia_com().isApprox(tube.inertia_com(), 1e-15));
  EXPECT_TRUE(m.bodies()[1].mass.inertia_com().isApprox(box.inertia_com(), 1e-15));
}

TEST(Model, InvalidBodiesAreRefusedWithTheirLocation) {
  const std::string head = "[[coordinates]]\nname = \"x\"\n[[bodies]]\nname = \"b\"\n";
  const std::string tail = "position = [\"x\", 0, 0]\n[simulation]\nt_end = 1\n";
  EXPECT_RIGID_ERROR(model_of(head + "primitive = \"solid_sphere\"\nradius = 0\nmass = 1\n" + tail),
                     "scene.toml:3:1: body 'b': ");
  EXPECT_RIGID_ERROR(model_of(head + "primitive = \"solid_sphere\"\nradius = 0\nmass = 1\n" + tail),
                     "radius");
  EXPECT_RIGID_ERROR(model_of(head + "primitive = \"solid_sphere\"\nheight = 1\nmass = 1\n" + tail),
                     "scene.toml:6:1: 'height' is not a size of primitive 'solid_sphere'; it takes radius (m)");
  EXPECT_RIGID_ERROR(model_of(head + "primitive = \"spere\"\nradius = 1\nmass = 1\n" + tail),
                     "scene.toml:5:13: body 'b' primitive: unknown primitive 'spere'; did you mean 'sphere'?");
  // the catalogue's aliases name the same shape (the command line's short names)
  const Model alias = model_of(head + "primitive = \"sphere\"\nradius = 1\nmass = 1\n" + tail);
  EXPECT_EQ(alias.scene().bodies[0].mass.primitive, "solid_sphere");
  // I_zz > I_xx + I_yy: no body has this inertia
  EXPECT_RIGID_ERROR(model_of(head + "inertia = {mass = 1, ixx = 1, iyy = 1, izz = 3}\n" + tail),
                     "no mass distribution has these moments");
  EXPECT_RIGID_ERROR(model_of(head + "point_masses = [{mass = -1, position = [0, 0, 0]}]\n" + tail),
                     "scene.toml:3:1: body 'b'");
  EXPECT_RIGID_ERROR(model_of(head + "inertia = {mass = \"sqrt(-1)\", ixx = 1, iyy = 1, izz = 1}\n" + tail),
                     "scene.toml:5:20: body 'b' inertia mass: sqrt(-1) is not real; expected a non-negative "
                     "argument");
  EXPECT_RIGID_ERROR(model_of(head + "inertia = {mass = \"log(-1)\", ixx = 1, iyy = 1, izz = 1}\n" + tail),
                     "scene.toml:5:20: body 'b' inertia mass: 'log(-1)' holds the complex number I; "
                     "expected a real expression");
}

TEST(Model, SimulationSettingsAreChecked) {
  const std::string body =
      "[[coordinates]]\nname = \"x\"\n[[bodies]]\npoint_masses = [{mass = 1, position = [0, 0, 0]}]\n"
      "position = [\"x\", 0, 0]\n";
  EXPECT_RIGID_ERROR(model_of(body + "[simulation]\nt_end = -1\n"),
                     "scene.toml:7:9: [simulation] t_end must be positive, got -1 s");
  EXPECT_RIGID_ERROR(model_of(body + "[simulation]\nt_end = 1\nintegrator = \"euler\"\n"),
                     "scene.toml:6:1: [simulation] integrator: ");
  EXPECT_RIGID_ERROR(model_of(body + "[simulation]\nt_end = 1\noutput_dt = 2\n"),
                     "output_dt = 2 s is longer than t_end = 1 s");
  // an output grid finer than a run may write is refused before anything runs
  EXPECT_RIGID_ERROR(model_of(body + "[simulation]\nt_end = 1e9\ndt = 1e-3\n"), "more than the 50000000 a run may write");
  // the one step rule: dt = 0.003 s with outputs every 0.01 s takes 4 steps of 0.0025 s each
  const Model m = model_of(body + "[simulation]\nt_end = 1\nintegrator = \"implicit_midpoint\"\n"
                                  "dt = 0.003\noutput_dt = 0.01\n");
  m.check();
  EXPECT_EQ(m.run().summary.steps, 400u);
}

// What a run would refuse, `check` refuses without integrating: a step far too small for the
// span (a free body with dt = 1e-300 took 0 steps in the past; TimeGrid::steps_in refuses it,
// now also in check and at the dt key), a trajectory larger than the memory limit, a dopri5
// tolerance below double precision (at its key).
TEST(Model, CheckFindsWhatARunWouldRefuseWithoutIntegrating) {
  const std::string free_body =
      "[[bodies]]\nfree = true\nprimitive = \"box\"\nsize = [1, 2, 3]\nmass = 1\n"
      "angular_velocity = [0, 1, 0.1]\n";
  const Model tiny = model_of(free_body + "[simulation]\nt_end = 1\ndt = 1e-300\noutput_dt = 0.5\n");
  EXPECT_RIGID_ERROR(tiny.check(), "scene.toml:9:6: [simulation] dt: 0.5 s in steps of at most 1e-300 s is 5e+299 steps");
  EXPECT_RIGID_ERROR((void)tiny.run(), "scene.toml:9:6: [simulation] dt: 0.5 s in steps of at most 1e-300 s");
  // 1e6 outputs × 18 columns (t, 7 of the pose, v, ω, L, energy) × 8 bytes = 144 MB: above a
  // 100 MB limit, below the 2 GiB default
  const Model big = model_of(free_body + "[simulation]\nt_end = 1000\ndt = 1e-3\n");
  RunOptions limited;
  limited.max_memory = 100'000'000;
  EXPECT_RIGID_ERROR(big.check(limited), "the trajectory would take 1000001 rows × 18 columns × 8 bytes = 144000144");
  EXPECT_RIGID_ERROR((void)big.run(limited), "more than the memory limit of 95.4 MiB");
  EXPECT_NO_THROW(big.check());
  // the scene's own limit
  EXPECT_RIGID_ERROR(model_of(free_body + "[simulation]\nt_end = 1000\ndt = 1e-3\n[output]\nmax_memory = \"1MiB\"\n").check(),
                     "more than the memory limit of 1 MiB");
  const std::string coords =
      "[[coordinates]]\nname = \"x\"\n[[bodies]]\npoint_masses = [{mass = 1, position = [0, 0, 0]}]\n"
      "position = [\"x\", 0, 0]\n";
  EXPECT_RIGID_ERROR(model_of(coords + "[simulation]\nt_end = 1\ntolerance = 1e-300\n"),
                     "scene.toml:8:13: [simulation] tolerance = 1e-300 is below what double precision can deliver");
}

// Runs of different scenes never share a default output directory.
TEST(Model, DefaultOutputDirectoryIsPerScene) {
  const std::string s =
      "[[coordinates]]\nname = \"x\"\n[[bodies]]\npoint_masses = [{mass = 1, position = [0, 0, 0]}]\n"
      "position = [\"x\", 0, 0]\n[simulation]\nt_end = 1\n";
  EXPECT_EQ(model_of(s, "dir/pendulum.toml").output_directory(), std::filesystem::path("out/pendulum"));
  EXPECT_EQ(model_of(s, "atwood.toml").output_directory("mine"), std::filesystem::path("mine"));
}

// A free body whose inertia is given in a frame B that is not principal moves exactly like
// the same body described in its principal frame P: R_WB(t) = R_WP(t) R_BPᵀ and
// ω_B = R_BP ω_P. The model diagonalises internally; the two runs must agree to round-off.
TEST(Model, FreeBodyInANonPrincipalFrameMovesLikeItsPrincipalTwin) {
  const Eigen::Quaterniond q_BP(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  const Eigen::Matrix3d R_BP = q_BP.toRotationMatrix();
  const Eigen::Matrix3d I_B = R_BP * Eigen::Vector3d(1, 2, 3).asDiagonal() * R_BP.transpose();
  const Eigen::Vector3d w_P(0.01, 1, 0.01);
  const Eigen::Vector3d w_B = R_BP * w_P;
  const Eigen::Quaterniond q_WB0 = q_BP.conjugate();  // so that R_WP(0) = 1 in both runs
  const std::string rotated = fmt::format(
      "[[bodies]]\nname = \"b\"\nfree = true\n"
      "inertia = {{mass = 1, ixx = {:.17g}, iyy = {:.17g}, izz = {:.17g}, ixy = {:.17g}, ixz = {:.17g}, iyz = {:.17g}}}\n"
      "angular_velocity = [{:.17g}, {:.17g}, {:.17g}]\n"
      "initial_quaternion = [{:.17g}, {:.17g}, {:.17g}, {:.17g}]\n"
      "[simulation]\nt_end = 20\ndt = 0.01\noutput_dt = 1\n",
      I_B(0, 0), I_B(1, 1), I_B(2, 2), I_B(0, 1), I_B(0, 2), I_B(1, 2), w_B.x(), w_B.y(), w_B.z(),
      q_WB0.w(), q_WB0.x(), q_WB0.y(), q_WB0.z());
  const std::string principal =
      "[[bodies]]\nname = \"b\"\nfree = true\ninertia = {mass = 1, ixx = 1, iyy = 2, izz = 3}\n"
      "angular_velocity = [0.01, 1, 0.01]\n[simulation]\nt_end = 20\ndt = 0.01\noutput_dt = 1\n";
  const RunResult a = model_of(rotated).run();
  const RunResult b = model_of(principal).run();
  ASSERT_EQ(a.trajectory.rows(), 21u);
  ASSERT_EQ(b.trajectory.rows(), 21u);
  const auto& T = a.trajectory;
  for (std::size_t k = 0; k < T.rows(); ++k) {
    const auto col = [&](const RunResult& r, const char* name) { return r.trajectory(k, r.trajectory.column(name)); };
    const Eigen::Quaterniond qa(col(a, "b.qw"), col(a, "b.qx"), col(a, "b.qy"), col(a, "b.qz"));
    const Eigen::Quaterniond qb(col(b, "b.qw"), col(b, "b.qx"), col(b, "b.qy"), col(b, "b.qz"));
    // qa = R_WB = R_WP R_BPᵀ and qb = R_WP
    const Eigen::Matrix3d Ra = qa.toRotationMatrix(), Rb = qb.toRotationMatrix();
    // 20 s near the separatrix amplifies the round-off of the diagonalisation (1e-16) by
    // the motion's sensitivity (about 1e5 here): 1e-10 leaves room above that
    EXPECT_LT((Ra - Rb * R_BP.transpose()).cwiseAbs().maxCoeff(), 1e-10) << "t = " << k;
    const Eigen::Vector3d wa(col(a, "b.wx"), col(a, "b.wy"), col(a, "b.wz"));
    const Eigen::Vector3d wb(col(b, "b.wx"), col(b, "b.wy"), col(b, "b.wz"));
    EXPECT_LT((wa - R_BP * wb).cwiseAbs().maxCoeff(), 1e-10) << "t = " << k;
    EXPECT_NEAR(col(a, "energy"), col(b, "energy"), 1e-13);
  }
}

// A free body in gravity: its COM follows the parabola exactly whatever it spins like.
TEST(Model, FreeBodyComFollowsTheParabola) {
  const RunResult r = model_of(R"toml(
gravity = [0, 0, -9.81]
[[bodies]]
name = "stone"
free = true
primitive = "solid_box"
size = [0.1, 0.2, 0.3]
mass = 1.5
initial_position = [1, 2, 3]
initial_velocity = [4, 0, 5]
angular_velocity = [3, -2, 1]
[simulation]
t_end = 1
dt = 1e-3
output_dt = 0.25
)toml").run();
  const auto& T = r.trajectory;
  ASSERT_EQ(T.rows(), 5u);
  for (std::size_t k = 0; k < T.rows(); ++k) {
    const double t = T(k, T.column("t"));
    // the box's COM is its frame's origin. The kick–drift–kick steps of rigid::body::RigidBody
    // are exact for a constant force, so only their rounding remains: a few ulps of |p| ≤ 6 m
    // (|v| ≤ 10 m/s) per step over n = 1000 steps
    const double n = 1000;
    EXPECT_NEAR(T(k, T.column("stone.x")), 1 + 4 * t, test::ulps(4 * n, 6.0));
    EXPECT_NEAR(T(k, T.column("stone.z")), 3 + 5 * t - 0.5 * 9.81 * t * t, test::ulps(4 * n, 6.0));
    EXPECT_NEAR(T(k, T.column("stone.vz")), 5 - 9.81 * t, test::ulps(4 * n, 10.0));
  }
  // kinetic + potential energy of the translation is exact, the rotation's is conserved
  // by the splitting to O(h⁴)
  EXPECT_NEAR(T(T.rows() - 1, T.column("energy")), T(0, T.column("energy")), 1e-9);
}

// A unit cube (in the file's units) as an ASCII STL.
void write_cube_stl(const std::filesystem::path& file) {
  {
    std::ofstream stl(file);
    const int f[12][3][3] = {
        {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}}, {{0, 0, 0}, {1, 1, 0}, {1, 0, 0}},
        {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}}, {{0, 0, 1}, {1, 1, 1}, {0, 1, 1}},
        {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}}, {{0, 0, 0}, {1, 0, 1}, {0, 0, 1}},
        {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}}, {{0, 1, 0}, {1, 1, 1}, {1, 1, 0}},
        {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}}, {{0, 0, 0}, {0, 1, 1}, {0, 1, 0}},
        {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}}, {{1, 0, 0}, {1, 1, 1}, {1, 0, 1}}};
    stl << "solid cube\n";
    for (const auto& tri : f) {
      stl << " facet normal 0 0 0\n  outer loop\n";
      for (const auto& v : tri) stl << "   vertex " << v[0] << " " << v[1] << " " << v[2] << "\n";
      stl << "  endloop\n endfacet\n";
    }
    stl << "endsolid cube\n";
  }
}

// A 1 cm cube (cube.stl, written beside the scene) of density `rho` sliding along x.
constexpr const char* kCubeOnX = R"toml(
[[coordinates]]
name = "x"
[[bodies]]
name = "cube"
mesh = "cube.stl"
units = "cm"
density = "rho"
position = ["x", 0, 0]
[simulation]
t_end = 1
)toml";

// A mesh body: a unit cube written as STL, whose inertia the mesh module computes, against
// the box primitive.
TEST(Model, MeshBodyFromAFileNextToTheScene) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "rigid_model_test";
  std::filesystem::create_directories(dir);
  write_cube_stl(dir / "cube.stl");
  const Model m = model_of(std::string("[parameters]\nrho = 1000\n") + kCubeOnX, dir / "scene.toml");
  const MassProperties box = mass::solid_box_with_density(1000, 0.01, 0.01, 0.01);
  EXPECT_NEAR(m.bodies()[0].mass.mass(), box.mass(), 1e-15);
  EXPECT_TRUE(m.bodies()[0].mass.com().isApprox(Eigen::Vector3d::Constant(0.005), 1e-13));
  EXPECT_TRUE(m.bodies()[0].mass.inertia_com().isApprox(box.inertia_com(), 1e-12));
  std::filesystem::remove_all(dir);
}

// A model built like another (a sweep's run) takes the other's mesh as read: with the file gone,
// it still builds, for another density, the very numbers a model reading the file gives.
TEST(Model, BuiltLikeAnotherReadsNoMeshFile) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "rigid_model_like_mesh";
  std::filesystem::create_directories(dir);
  write_cube_stl(dir / "cube.stl");
  const Scene scene = parse_scene(R"toml(
[parameters]
rho = 1000
[[bodies]]
name = "cube"
free = true
mesh = "cube.stl"
units = "cm"
density = "rho"
angular_velocity = [0.1, 2, 0.1]
[simulation]
t_end = 0.1
)toml",
                                  dir / "scene.toml");
  const Model like(scene);
  Scene denser = scene;
  apply_overrides(denser, {"rho=2500"});
  const Model read(denser);  // reads the file
  std::filesystem::remove(dir / "cube.stl");
  EXPECT_RIGID_ERROR((void)Model(denser), "cube.stl");
  const Model shared(denser, like);
  const MassProperties& a = shared.bodies()[0].mass;
  const MassProperties& b = read.bodies()[0].mass;
  EXPECT_EQ(a.mass(), b.mass());  // the same operations on the same mesh: bit for bit
  EXPECT_EQ(a.com(), b.com());
  EXPECT_EQ(a.inertia_com(), b.inertia_com());
  // ρV against 2.5 (1000 V): two roundings apart at most
  EXPECT_DOUBLE_EQ(a.mass(), 2.5 * like.bodies()[0].mass.mass());
  EXPECT_EQ(shared.run().trajectory.data(), read.run().trajectory.data());
  std::filesystem::remove_all(dir);
}

TEST(Model, FreeBodySceneEquationsNameThePrincipalMoments) {
  const Model m = model_of(R"toml(
[[bodies]]
name = "r"
free = true
inertia = {mass = 1, ixx = 3, iyy = 1, izz = 2}
[simulation]
t_end = 1
)toml");
  const std::string eq = m.equations(false);
  // the equations in the body frame B with the inertia as written (the term order of the
  // printout is GiNaC's; tests/lagrange checks the equations themselves), and the principal
  // moments sorted ascending by the principal-axes routine: (1, 2, 3)
  EXPECT_NE(eq.find("[3, 0, 0]"), std::string::npos) << eq;
  EXPECT_NE(eq.find("3*w1_dot = "), std::string::npos) << eq;
  EXPECT_NE(eq.find("principal moments about the COM (ascending) I = (1, 2, 3)"), std::string::npos) << eq;
  EXPECT_NE(m.equations(true).find("\\dot\\omega_1"), std::string::npos);
}

}  // namespace
}  // namespace rigid::scene

namespace rigid::scene {
namespace {

// The issue's case: two free bodies, I = (1, 2, 3), one at rest and one spinning at
// (1e3, 1e3, 1e3) rad/s, RK4 at dt = 0.1 s (h|ω| ≈ 170, far outside its stability region).
// Whichever body is listed first, the run is refused naming the spinning body.
std::string two_bodies(bool spinning_first) {
  const std::string rest = "[[bodies]]\nname = \"still\"\nfree = true\ninertia = {mass = 1, ixx = 1, iyy = 2, izz = 3}\n";
  const std::string spin = "[[bodies]]\nname = \"spin\"\nfree = true\ninertia = {mass = 1, ixx = 1, iyy = 2, izz = 3}\n"
                           "angular_velocity = [1e3, 1e3, 1e3]\n";
  return (spinning_first ? spin + rest : rest + spin) +
         "[simulation]\nt_end = 10\nintegrator = \"rk4\"\ndt = 0.1\n";
}

TEST(Model, DivergingFreeBodyIsRefusedWhicheverItsPlace) {
  for (const bool first : {true, false}) {
    SCOPED_TRACE(first ? "spinning body first" : "spinning body second");
    const Model m = model_of(two_bodies(first));
    EXPECT_RIGID_ERROR((void)m.run(), "non-finite state at step 2, t = 0.2 s: body 'spin' R_WB.");
  }
}

TEST(Model, DivergingHeavyTopIsRefused) {
  // a spin whose angular momentum overflows a double (I ω ≈ 1e308 · 0.0x kg·m² is finite, but
  // its kinetic energy and the sub-flows' angles are not): the first step's state is not finite
  const Model m = model_of(R"toml(
gravity = [0, 0, -9.81]
[[bodies]]
name = "top"
free = true
primitive = "solid_cone"
radius = 0.05
height = 0.2
mass = 1.0
pivot = [0, 0, 0.2]
angular_velocity = [1e308, 1e308, 1e308]
[simulation]
t_end = 1
dt = 1e-3
)toml");
  EXPECT_RIGID_ERROR((void)m.run(), "body 'top'");
}

TEST(Model, EquationsKeepTheSceneParameterNames) {
  // a cylinder of mass M and radius R, gravity g: the inertia M R²/2 prints with the names
  const Model m = model_of(R"toml(
gravity = [0, 0, "-g"]
[parameters]
g = 9.81
M = 2.0
R = 0.1
[[coordinates]]
name = "phi"
[[bodies]]
name = "wheel"
primitive = "cylinder"
radius = "R"
height = 0.02
mass = "M"
rotation = [{axis = [0, 0, 1], angle = "phi"}]
[simulation]
t_end = 1
)toml");
  // ½ M R² φ̈ = 0 in canonical order: the names, no evaluated inertia (0.01 kg·m²)
  const std::string eq = m.equations(false);
  EXPECT_NE(eq.find("\n  1/2*M*R^2*phi_ddot = 0\n"), std::string::npos) << eq;
  EXPECT_EQ(eq.find("0.01"), std::string::npos) << eq;
}

}  // namespace
}  // namespace rigid::scene

namespace rigid::scene {
namespace {

// A model built with `like` shares like's derived equations but runs with its own parameter
// values, initial state and settings (what a sweep does for each run). Checked against the closed
// form of the initial energy (test::kRodPendulum: E = ½ (m L²/3) θ̇² − m g (L/2) cos θ), which
// like's values would miss, and against a model derived afresh: rk4 at
// a fixed step with equations derived twice differs only by the order of floating-point
// operations (GiNaC orders terms by symbol serial numbers), 1e-12 over 1500 steps of O(1) angles.
TEST(Model, SharesTheEquationsOfALikeModelAndRunsWithItsOwnValues) {
  const Model like(parse_scene(test::kRodPendulum, "rod.toml"));
  Scene changed = parse_scene(test::kRodPendulum, "rod.toml");
  apply_overrides(changed, {"L=1.7", "m=2.5", "theta.initial=0.3", "theta.velocity=0.2", "simulation.t_end=1.5"});
  const Model shared(changed, like);
  const Model fresh(changed);
  const RunResult a = shared.run();
  const RunResult b = fresh.run();
  ASSERT_EQ(a.trajectory.rows(), b.trajectory.rows());
  EXPECT_EQ(a.trajectory.rows(), 151u);  // t_end 1.5 s at output_dt 0.01 s, not like's 2 s
  const double g = 9.81, l = 1.7, m = 2.5, th = 0.3, thd = 0.2;
  const double e0 = 0.5 * (m * l * l / 3) * thd * thd - m * g * (l / 2) * std::cos(th);
  double e_initial = std::nan("");
  for (const auto& [name, value] : a.summary.diagnostics) {
    if (name == "energy_initial") e_initial = value;
  }
  EXPECT_NEAR(e_initial, e0, 1e-12 * std::abs(e0));
  ASSERT_EQ(a.trajectory.data().size(), b.trajectory.data().size());
  double largest = 0;
  for (std::size_t k = 0; k < a.trajectory.data().size(); ++k) {
    largest = std::max(largest, std::abs(a.trajectory.data()[k] - b.trajectory.data()[k]));
  }
  EXPECT_LE(largest, 1e-12);
  // like is untouched: its own run still starts from θ = 1 with its 2 s
  EXPECT_EQ(like.run().trajectory.rows(), 201u);
}

TEST(Model, ALikeModelOfAnotherStructureIsRefused) {
  const Model like = model_of(R"toml(
[[coordinates]]
name = "x"
[[bodies]]
point_masses = [{mass = 1, position = [0, 0, 0]}]
position = ["x", 0, 0]
[simulation]
t_end = 1
)toml");
  const Scene other = parse_scene(R"toml(
[[coordinates]]
name = "y"
[[bodies]]
point_masses = [{mass = 1, position = [0, 0, 0]}]
position = ["y", 0, 0]
[simulation]
t_end = 1
)toml",
                                   "other.toml");
  EXPECT_RIGID_ERROR(Model(other, like), "differs from the model's it should share equations with");
}

// The schema a model publishes before any run is what its runs produce, for every example
// shipped: the same columns in the same order, the same diagnostics and metrics, and the units
// of docs/scene-format.md (checked here by quantity, independently of the names).
TEST(ModelSchema, EveryExampleRunsWhatItsSchemaSays) {
  const std::filesystem::path examples = std::filesystem::path(RIGID_EXAMPLES_DIR);
  std::size_t scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(examples)) {
    if (entry.path().extension() != ".toml") continue;
    ++scenes;
    SCOPED_TRACE(entry.path().filename().string());
    const Model m = load_model(entry.path());
    const io::RunSchema& schema = m.schema();
    const RunResult r = m.run();
    EXPECT_EQ(r.schema, schema);
    EXPECT_EQ(schema.kind, m.kind());
    EXPECT_EQ(schema.column_names(), r.trajectory.columns());
    ASSERT_EQ(schema.diagnostics.size(), r.summary.diagnostics.size());
    for (std::size_t k = 0; k < schema.diagnostics.size(); ++k) {
      EXPECT_EQ(schema.diagnostics[k].name, r.summary.diagnostics[k].first);
    }
    ASSERT_EQ(schema.metrics.size(), r.summary.metrics.size());
    for (std::size_t k = 0; k < schema.metrics.size(); ++k) {
      EXPECT_EQ(schema.metrics[k].name, r.summary.metrics[k].name);
      // a drift reported as an absolute change says so in its note and carries the change's unit
      if (r.summary.metrics[k].note.empty()) {
        EXPECT_EQ(schema.metrics[k].unit, r.summary.metrics[k].unit);
      }
    }
    ASSERT_EQ(schema.parameters.size(), m.parameters().size());
    for (std::size_t k = 0; k < schema.parameters.size(); ++k) {
      EXPECT_EQ(schema.parameters[k].name, m.parameters()[k].name);
    }
    for (const io::Column& c : schema.columns) {
      using Q = io::Quantity;
      const std::string expected = c.quantity == Q::kTime                                              ? "s"
                                   : c.quantity == Q::kPosition                                        ? "m"
                                   : c.quantity == Q::kVelocity                                        ? "m/s"
                                   : c.quantity == Q::kAngularVelocity                                 ? "rad/s"
                                   : c.quantity == Q::kAngularMomentum                                 ? "kg·m²/s"
                                   : c.quantity == Q::kEnergy || c.quantity == Q::kJacobi              ? "J"
                                                                                                       : "";
      EXPECT_EQ(c.unit, expected) << c.name;
      if (c.quantity == Q::kCoordinateRate) {
        EXPECT_EQ(c.name, c.owner + "_dot");
      }
      if (c.quantity == Q::kPosition || c.quantity == Q::kOrientation) {
        EXPECT_TRUE(std::any_of(m.bodies().begin(), m.bodies().end(), [&](const ModelBody& b) { return b.name == c.owner; }))
            << c.name;
      }
    }
  }
  EXPECT_GE(scenes, 10u);
}

// The tennis racket's first flip is a time (s), read from ω_y (rad/s); the heavy top's
// diagnostics are of L about the pivot's vertical; a mesh body's derived constants are kg, m,
// kg·m².
TEST(ModelSchema, UnitsOfMetricsDiagnosticsAndDerivedConstants) {
  const std::filesystem::path examples = std::filesystem::path(RIGID_EXAMPLES_DIR);
  const Model racket = load_model(examples / "tennis_racket.toml");
  ASSERT_FALSE(racket.schema().metrics.empty());
  EXPECT_EQ(racket.schema().metrics[0].name, "first_flip");
  EXPECT_EQ(racket.schema().metrics[0].unit, "s");
  EXPECT_EQ(racket.schema().find("racket.wy")->quantity, io::Quantity::kAngularVelocity);
  EXPECT_EQ(racket.schema().find("racket.wy")->owner, "racket");
  EXPECT_EQ(racket.schema().find("racket.wy")->component, "y");

  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "rigid_model_schema_test";
  std::filesystem::create_directories(dir);
  write_cube_stl(dir / "cube.stl");
  const Model cube = model_of(std::string("[parameters]\nrho = 1000\n") + kCubeOnX +
                                  "[output]\nquantities = [\"x*\", \"energy\"]\n",
                              dir / "scene.toml");
  std::filesystem::remove_all(dir);
  // the scene's parameter states no unit; a cube's products of inertia are 0 and get no name
  std::vector<std::pair<std::string, std::string>> units;
  for (const io::Scalar& p : cube.schema().parameters) units.emplace_back(p.name, p.unit);
  EXPECT_EQ(units, (std::vector<std::pair<std::string, std::string>>{{"rho", ""},
                                                                      {"cube_mass", "kg"},
                                                                      {"cube_com_x", "m"},
                                                                      {"cube_com_y", "m"},
                                                                      {"cube_com_z", "m"},
                                                                      {"cube_ixx", "kg·m²"},
                                                                      {"cube_iyy", "kg·m²"},
                                                                      {"cube_izz", "kg·m²"}}));
  // [output] quantities selects the schema's columns, and the run's
  EXPECT_EQ(cube.schema().column_names(), (std::vector<std::string>{"t", "x", "x_dot", "energy"}));
  EXPECT_EQ(cube.run().trajectory.columns(), cube.schema().column_names());
}

// A pattern of [output] quantities that matches nothing is the scene's error, found when the
// model is built (rigid check finds it), not after a run.
TEST(ModelSchema, AQuantityPatternMatchingNothingIsRefusedBeforeAnyRun) {
  EXPECT_RIGID_ERROR((void)model_of(R"toml(
[[coordinates]]
name = "theta"
[[bodies]]
name = "bob"
inertia = {mass = 1, ixx = 0, iyy = 0, izz = 0}
position = ["sin(theta)", 0, "-cos(theta)"]
[simulation]
t_end = 1
[output]
quantities = ["thta"]
)toml"),
                     "scene.toml:11:14: [output] quantities: 'thta' matches no column; did you mean 'theta'?");
}

// The point-mass closed forms as text (what a scene's equations are built from) evaluate to
// what rigid::mass::point_masses computes from the numbers, for three points in general
// position (relative 1e-14: a few roundings of sums of ~10 terms).
TEST(PointMassExpressions, EvaluateToTheNumericPointMasses) {
  const std::vector<lagrange::Parameter> params = {{"a", 0.3}, {"b", -0.7}};
  const std::vector<mass::PointMassText> texts = {
      {"2", {"a", "b", "0.1"}}, {"0.5", {"-b", "2*a", "1"}}, {"a", {"0", "0.25", "-a"}}};
  const std::array<std::string, 10> text = mass::point_mass_expressions(texts);
  Eigen::Matrix3Xd points(3, 3);
  points << 0.3, 0.7, 0.0, -0.7, 0.6, 0.25, 0.1, 1.0, -0.3;
  const std::vector<double> masses = {2.0, 0.5, 0.3};
  const MassProperties mp = mass::point_masses(masses, points);
  auto value = [&](std::size_t k) {
    return lagrange::evaluate_constant(lagrange::Expression(text[k]), params, "point masses");
  };
  EXPECT_NEAR(value(0), mp.mass(), 1e-14 * mp.mass());
  for (Eigen::Index k = 0; k < 3; ++k) EXPECT_NEAR(value(1 + static_cast<std::size_t>(k)), mp.com()[k], 1e-14);
  const Eigen::Matrix3d& I = mp.inertia_com();
  const double scale = I.norm();
  const double expected[6] = {I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2)};
  for (std::size_t k = 0; k < 6; ++k) EXPECT_NEAR(value(4 + k), expected[k], 1e-14 * scale) << k;
  EXPECT_RIGID_ERROR((void)mass::point_mass_expressions({}), "at least one point");
}

TEST(ModelThreads, OneModelRunsOnSeveralThreadsAtOnce) {
  // a coordinate scene and a free-body scene, each run by four threads at once: every run is
  // bitwise the run done alone (a Model is immutable; runs keep their state to themselves)
  const Model coordinates = model_of(test::kRodPendulum);
  const Model free = model_of(R"toml(
[[bodies]]
name = "racket"
free = true
inertia = {mass = 0.35, ixx = 1, iyy = 2, izz = 3}
angular_velocity = [0.01, 1, 0.01]
[simulation]
t_end = 20
dt = 0.01
output_dt = 0.1
)toml");
  for (const Model* m : {&coordinates, &free}) {
    const RunResult alone = m->run();
    std::vector<RunResult> together(4);
    std::vector<std::thread> threads;
    for (std::size_t k = 0; k < together.size(); ++k) threads.emplace_back([&, k] { together[k] = m->run(); });
    for (auto& t : threads) t.join();
    for (const RunResult& r : together) EXPECT_EQ(r.trajectory.data(), alone.trajectory.data());
  }
}

}  // namespace
}  // namespace rigid::scene
