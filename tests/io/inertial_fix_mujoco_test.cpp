// fix_inertials against MuJoCo's own compiler (libmujoco, an independent implementation): the
// inertials rigid writes, loaded by MuJoCo, equal what MuJoCo computes from the same geoms.
#include <filesystem>
#include <functional>
#include <sstream>
#include <fstream>
#include <memory>
#include <string>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include "rigid/io/inertial_fix.hpp"
#include "support/mujoco_model.hpp"
#include "support/inertial_text.hpp"

namespace rigid::io {
namespace {

namespace fs = std::filesystem;

// the models Debian's libmujoco-samples installs (a build dependency of the tests)
const fs::path kModels = "/usr/share/mujoco/model";

using Model = test::MjModelPtr;
Model load(const fs::path& path) { return test::load_mujoco(path); }

// a body's compiled inertia as a full tensor in the body frame: R(iquat) diag(inertia) Rᵀ
// (principal axes of equal moments are not unique, the tensor is)
Eigen::Matrix3d tensor(const mjModel* m, int b) {
  const mjtNum* q = m->body_iquat + 4 * b;  // w x y z
  const Eigen::Matrix3d R = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
  const Eigen::Vector3d d(m->body_inertia[3 * b], m->body_inertia[3 * b + 1], m->body_inertia[3 * b + 2]);
  return R * d.asDiagonal() * R.transpose();
}

struct Compiled {
  double mass;
  Eigen::Vector3d com;
  Eigen::Matrix3d inertia;
};

Compiled compiled(const mjModel* m, int b) {
  return {m->body_mass[b], Eigen::Vector3d(m->body_ipos + 3 * b), tensor(m, b)};
}

// Relative 1e-9 (the acceptance bound) for bodies whose compiled tensor MuJoCo leaves near
// diagonal (the humanoid's). MuJoCo diagonalises each body's tensor and stores principal
// moments and iquat; the round trip tensor → eig → R diag Rᵀ loses ~1e-13 of tr I there.
constexpr double kRelative = 1e-9;
// MuJoCo 2.2's own combination of several rotated geoms into one body loses up to ~5e-8 of
// tr I (measured: the body "a" below is 5.3e-8 from the exact tensor, while each of its geoms
// compiled alone agrees with rigid to 1e-16 and those three tensors combined by the
// parallel-axis theorem in double agree with rigid to 1e-16): 1e-7 for such bodies.
constexpr double kRelativeCombined = 1e-7;
// A mesh's vertices are stored as float32 by MuJoCo (2⁻²⁴ ≈ 6e-8 relative per coordinate):
// its volume and moments carry a few float ulps.
constexpr double kRelativeMesh = 1e-6;

void expect_close(const Compiled& a, const Compiled& b, const std::string& what, double tol) {
  SCOPED_TRACE(what);
  EXPECT_NEAR(a.mass, b.mass, tol * a.mass);
  // the COM at the scale of the body's own size (its radius of gyration) near the origin
  const double size = std::sqrt(a.inertia.trace() / a.mass);
  EXPECT_LE((a.com - b.com).norm(), tol * std::max(a.com.norm(), size))
      << a.com.transpose() << " vs " << b.com.transpose();
  EXPECT_LE((a.inertia - b.inertia).cwiseAbs().maxCoeff(), tol * a.inertia.trace())
      << a.inertia << "\nvs\n" << b.inertia;
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("rigid_fix_mujoco_{}_{}", name, ::getpid());
  fs::create_directories(dir);
  return dir;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void write(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// fix `model`, write it next to it as fixed.xml, load both in MuJoCo and compare every body:
// (1) rigid's own numbers (the result) with MuJoCo compiling the original from its geoms, the
// independent check; (2) the fixed file as MuJoCo reads it with the original.
void compare_with_mujoco(const fs::path& model, const fs::path& out, int expected_fixed,
                         const std::function<double(const std::string&)>& tolerance) {
  const InertialFixResult r = fix_inertials_file(model.string());
  ASSERT_TRUE(r.ok()) << fmt::format("{}", fmt::join(r.errors(), "\n"));
  write(out, r.text);
  const Model original = load(model);
  const Model fixed = load(out);
  ASSERT_TRUE(original && fixed);
  ASSERT_EQ(original->nbody, fixed->nbody);
  int n_fixed = 0;
  for (const auto& link : r.links) {
    if (!link.fixed) continue;
    ++n_fixed;
    const int b = mj_name2id(original.get(), mjOBJ_BODY, link.name.c_str());
    ASSERT_GT(b, 0) << link.name;
    const Compiled mine{link.fixed->mass(), link.fixed->com(), link.fixed->inertia_com()};
    const double tol = tolerance(link.name);
    expect_close(compiled(original.get(), b), mine, link.name + ": rigid vs MuJoCo's compiler", tol);
    expect_close(compiled(original.get(), b), compiled(fixed.get(), b),
                 link.name + ": fixed file vs original, both compiled by MuJoCo", tol);
  }
  EXPECT_EQ(n_fixed, expected_fixed);
}

TEST(InertialFixMujoco, HumanoidMatchesMujocoCompiler) {
  const fs::path model = kModels / "humanoid" / "humanoid.xml";
  ASSERT_TRUE(fs::exists(model)) << "install libmujoco-samples (scripts/install-deps.sh)";
  const fs::path dir = scratch("humanoid");
  // every one of its 16 bodies has geoms and no <inertial>
  compare_with_mujoco(model, dir / "humanoid.xml", 16, [](const std::string&) { return kRelative; });
  // only the inertials were added: every other byte is the original's
  EXPECT_EQ(test::without_inertials(read_text(dir / "humanoid.xml")), test::without_inertials(read_text(model)));
  fs::remove_all(dir);
}

// humanoid100.xml brings its humanoid in with <include file="humanoid_body.xml"/>: fix follows
// it as MuJoCo does and writes one file. Its 116 bodies (16 of the humanoid, 100 unnamed free
// objects) have no <inertial>; MuJoCo numbers bodies in document order through the include,
// which is the order of the report (body k + 1; 0 is the world).
TEST(InertialFixMujoco, Humanoid100ThroughItsIncludeMatchesMujocoCompiler) {
  const fs::path model = kModels / "humanoid100" / "humanoid100.xml";
  ASSERT_TRUE(fs::exists(model)) << "install libmujoco-samples (scripts/install-deps.sh)";
  const InertialFixResult r = fix_inertials_file(model.string());
  ASSERT_TRUE(r.ok()) << fmt::format("{}", fmt::join(r.errors(), "\n"));
  ASSERT_EQ(r.links.size(), 116u);
  EXPECT_EQ(r.links[0].file, (kModels / "humanoid100" / "humanoid_body.xml").string());
  EXPECT_EQ(r.links[16].file, model.string());
  const fs::path dir = scratch("humanoid100");
  write(dir / "humanoid100.xml", r.text);  // no include left: loads on its own
  const Model original = load(model);
  const Model fixed = load(dir / "humanoid100.xml");
  ASSERT_TRUE(original && fixed);
  ASSERT_EQ(original->nbody, 117);
  ASSERT_EQ(fixed->nbody, 117);
  for (int k = 0; k < 116; ++k) {
    const auto& link = r.links[static_cast<std::size_t>(k)];
    ASSERT_TRUE(link.fixed) << k;
    const Compiled mine{link.fixed->mass(), link.fixed->com(), link.fixed->inertia_com()};
    const std::string what = fmt::format("body {} '{}'", k + 1, link.name);
    expect_close(compiled(original.get(), k + 1), mine, what + ": rigid vs MuJoCo's compiler", kRelative);
    expect_close(compiled(original.get(), k + 1), compiled(fixed.get(), k + 1),
                 what + ": fixed file vs original, both compiled by MuJoCo", kRelative);
  }
  fs::remove_all(dir);
}

// Every rule the reader follows, in one generated model: default classes (nested, childclass,
// class=), each primitive type, fromto on capsule/cylinder/box/ellipsoid, every orientation
// attribute under angle="radian" and a fixed-axis eulerseq, density and mass attributes, a
// massless geom, a scaled mesh in meshdir, and a body whose own <inertial> "auto" keeps.
TEST(InertialFixMujoco, EveryGeomRuleMatchesMujocoCompiler) {
  const fs::path dir = scratch("rules");
  fs::create_directories(dir / "meshes");
  // a closed tetrahedron-free convex mesh: an octahedron with an off-centre apex pair
  write(dir / "meshes" / "octa.obj",
        "v 1 0 0\nv -1 0 0\nv 0 2 0\nv 0 -1 0\nv 0 0 1.5\nv 0.2 0.1 -1\n"
        "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n");
  write(dir / "model.xml", R"(<mujoco model="rules">
  <compiler angle="radian" eulerseq="ZYX" meshdir="meshes" exactmeshinertia="true"/>
  <asset>
    <mesh name="octa" file="octa.obj" scale="0.1 0.05 0.08"/>
  </asset>
  <default>
    <geom density="800"/>
    <default class="light">
      <geom density="300" type="box"/>
      <default class="lighter"><geom density="120"/></default>
    </default>
  </default>
  <worldbody>
    <geom type="plane" size="1 1 0.1"/>
    <body name="a" pos="0 0 1" childclass="light">
      <geom size="0.1 0.2 0.05" pos="0.1 0 0" euler="0.3 -0.4 1.1"/>
      <geom class="lighter" type="ellipsoid" size="0.05 0.07 0.09" axisangle="1 2 3 0.7"/>
      <geom type="capsule" fromto="0 0 0 0.2 -0.1 0.3" size="0.03" mass="0.7"/>
      <body name="b" pos="0.3 0 0">
        <geom type="cylinder" fromto="0 0 0 0 0 -0.4" size="0.04"/>
        <geom type="box" fromto="0.1 0.1 0 0.2 -0.1 0.1" size="0.02 0.03 0"/>
        <geom type="ellipsoid" fromto="0 0 0 0.1 0 0" size="0.02 0.03 0" quat="1 0 0 0"/>
        <geom type="sphere" size="0.05" pos="0 0.1 0" density="0"/>
        <geom type="sphere" size="0.05" pos="0 -0.1 0" class="main"/>
      </body>
      <body name="c" pos="0 0.4 0">
        <geom type="mesh" mesh="octa" pos="0.01 0.02 0.03" xyaxes="0 1 0 -1 0.2 0"/>
        <geom type="cylinder" size="0.02 0.1" zaxis="1 1 0"/>
      </body>
      <body name="d">
        <inertial pos="0 0 0" mass="1" diaginertia="0.01 0.02 0.025"/>
        <geom size="0.1 0.1 0.1"/>
      </body>
    </body>
  </worldbody>
</mujoco>
)");
  // a, b, c are computed; d keeps its own inertial (inertiafromgeom="auto")
  compare_with_mujoco(dir / "model.xml", dir / "fixed.xml", 3, [](const std::string& body) {
    return body == "c" ? kRelativeMesh : kRelativeCombined;
  });
  const InertialFixResult r = fix_inertials_file((dir / "model.xml").string());
  ASSERT_EQ(r.links.size(), 4u);
  EXPECT_EQ(r.links[3].reason, "kept");
  fs::remove_all(dir);
}

// The mug is a mesh (a non-convex solid: a cup and a handle). With exactmeshinertia="true"
// MuJoCo's compiler agrees with rigid to its float32 vertices (measured: mass 2.2e-8, COM
// 3e-10 m, inertia 1.2e-8 of tr I). Its default ("legacy") sums |pyramid volumes| from the
// surface centroid, which counts the cup's hollow: 0.508 kg instead of the solid's 0.263 kg.
TEST(InertialFixMujoco, MugMeshMatchesMujocoExactMeshInertia) {
  const fs::path original = kModels / "mug" / "mug.xml";
  ASSERT_TRUE(fs::exists(original)) << "install libmujoco-samples (scripts/install-deps.sh)";
  const fs::path dir = scratch("mug");
  fs::copy(kModels / "mug", dir, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
  std::string text = read_text(dir / "mug.xml");
  const std::size_t root = text.find("<mujoco");
  ASSERT_NE(root, std::string::npos);
  text.insert(text.find('>', root) + 1, "\n  <compiler exactmeshinertia=\"true\"/>");
  write(dir / "exact.xml", text);
  compare_with_mujoco(dir / "exact.xml", dir / "fixed.xml", 2,
                      [](const std::string& body) { return body == "mug" ? kRelativeMesh : kRelative; });

  // the legacy default: MuJoCo's mug is far from the solid's mass, and rigid says so
  const Model legacy = load(original);
  const InertialFixResult r = fix_inertials_file(original.string());
  ASSERT_TRUE(legacy && r.ok() && r.links[0].fixed);
  const int b = mj_name2id(legacy.get(), mjOBJ_BODY, "mug");
  EXPECT_GT(legacy->body_mass[b], 1.5 * r.links[0].fixed->mass());
  ASSERT_FALSE(r.links[0].warnings.empty());
  EXPECT_NE(r.links[0].warnings.back().find("MuJoCo's legacy mesh inertia"), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rigid::io
