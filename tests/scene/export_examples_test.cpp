// The exported C++ of the examples with coordinates (generated at build time by
// rigid_export_examples_gen into exported/<example>.hpp and compiled here with the project's
// flags) against the engine: M, f, G and γ at several states; the inverse and forward dynamics
// of the models without constraints against their M and f and the engine's q̈.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "arm7.hpp"
#include "atwood.hpp"
#include "cart_arm.hpp"
#include "cone_pendulum.hpp"
#include "double_pendulum.hpp"
#include "physical_pendulum.hpp"
#include "rigid/lagrange/export.hpp"
#include "rigid/scene/export.hpp"
#include "rigid/scene/model.hpp"
#include "rolling_cylinder.hpp"
#include "rolling_sphere.hpp"
#include "rolling_tube.hpp"
#include "stiff_dumbbell.hpp"
#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid::scene {
namespace {

// One exported model, its functions with the scene's parameters (the defaults).
struct Exported {
  std::string example;
  int n, m;
  void (*mass_matrix)(const double* q, double t, double* M);
  void (*forces)(const double* q, const double* q_dot, double t, double* f);
  void (*mass_matrix_and_forces)(const double* q, const double* q_dot, double t, double* M, double* f);
  void (*constraint_jacobian)(const double* q, double t, double* G);
  void (*constraint_gamma)(const double* q, const double* q_dot, double t, double* gamma);
};

#define RIGID_EXPORTED(ns)                                                                          \
  Exported {                                                                                        \
    #ns, ns::kNumCoordinates, ns::kNumConstraints,                                                  \
        [](const double* q, double t, double* M) { ns::mass_matrix(q, t, M); },                     \
        [](const double* q, const double* qd, double t, double* f) { ns::forces(q, qd, t, f); },    \
        [](const double* q, const double* qd, double t, double* M, double* f) {                     \
          ns::mass_matrix_and_forces(q, qd, t, M, f);                                               \
        },                                                                                          \
        [](const double* q, double t, double* G) { ns::constraint_jacobian(q, t, G); },             \
        [](const double* q, const double* qd, double t, double* g) { ns::constraint_gamma(q, qd, t, g); } \
  }

std::vector<Exported> exported_examples() {
  return {RIGID_EXPORTED(atwood),           RIGID_EXPORTED(cone_pendulum),
          RIGID_EXPORTED(double_pendulum),  RIGID_EXPORTED(physical_pendulum),
          RIGID_EXPORTED(rolling_cylinder), RIGID_EXPORTED(rolling_sphere),
          RIGID_EXPORTED(rolling_tube),     RIGID_EXPORTED(stiff_dumbbell)};
}

// Entries of `a` and `b` agree to `k` ulps of the largest entry of `b` (and at least 1).
void expect_close(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double k, const std::string& what) {
  ASSERT_EQ(a.rows(), b.rows()) << what;
  ASSERT_EQ(a.cols(), b.cols()) << what;
  const double scale = std::max(1.0, b.cwiseAbs().maxCoeff());
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    EXPECT_NEAR(a.data()[i], b.data()[i], test::ulps(k, scale)) << what << " entry " << i;
  }
}

TEST(ExportExamples, CompiledCodeComputesTheEnginesMfGAndGamma) {
  for (const Exported& ex : exported_examples()) {
    SCOPED_TRACE(ex.example);
    const Model model = load_model(std::string(RIGID_EXAMPLES_DIR) + "/" + ex.example + ".toml");
    const lagrange::System& sys = model.system();
    ASSERT_EQ(sys.num_coordinates(), ex.n);
    ASSERT_EQ(sys.num_constraints(), ex.m);
    lagrange::Workspace w = sys.make_workspace();
    const auto n = static_cast<Eigen::Index>(ex.n), m = static_cast<Eigen::Index>(ex.m);
    for (int sample = 0; sample < 5; ++sample) {
      // states around the initial one: q0 + 0.4 sin(…), q̇ = 0.7 cos(…), t ≠ 0
      Eigen::VectorXd q = sys.initial_q(), qd(n);
      for (Eigen::Index i = 0; i < n; ++i) {
        q[i] += 0.4 * std::sin(1.3 * static_cast<double>(i) + 0.9 * sample + 0.2);
        qd[i] = 0.7 * std::cos(2.1 * static_cast<double>(i) - 0.5 * sample);
      }
      const double t = 0.37 * sample;
      Eigen::MatrixXd M, G;
      Eigen::VectorXd f, gamma;
      sys.mass_matrix_and_forces(w, t, q, qd, M, f);
      lagrange::constraint_terms(sys, w, t, q, qd, G, gamma);
      // exported: row-major arrays
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> Me(n, n), Me2(n, n), Ge(m, n);
      Eigen::VectorXd fe(n), fe2(n), gammae(m);
      ex.mass_matrix(q.data(), t, Me.data());
      ex.forces(q.data(), qd.data(), t, fe.data());
      ex.mass_matrix_and_forces(q.data(), qd.data(), t, Me2.data(), fe2.data());
      ex.constraint_jacobian(q.data(), t, Ge.data());
      ex.constraint_gamma(q.data(), qd.data(), t, gammae.data());
      // the same operations in the same order as the engine's tape: equal to the last bit on
      // this platform; 16 ulps of the largest entry leave room for a compiler that contracts
      // a·b + c into one fused multiply-add
      expect_close(Me, M, 16, "M");
      expect_close(Me2, M, 16, "M (with f)");
      expect_close(fe, f, 16, "f");
      expect_close(fe2, f, 16, "f (with M)");
      if (m > 0) {
        expect_close(Ge, G, 16, "G");
        expect_close(gammae, gamma, 16, "gamma");
        // and independently of the engine's G and γ: its q̈ and λ satisfy the exported
        // M q̈ = f + Gᵀλ and G q̈ = γ (a solve's round-off: 1e-9 of the scale)
        Eigen::VectorXd qdd, lambda;
        sys.accelerations(w, t, q, qd, qdd, lambda);
        const double scale = 1 + M.norm() * qdd.norm() + f.norm();
        EXPECT_LT((Me * qdd - fe - Ge.transpose() * lambda).norm(), 1e-9 * scale);
        EXPECT_LT((Ge * qdd - gammae).norm(), 1e-9 * (1 + Ge.norm() * qdd.norm() + gammae.norm()));
      }
    }
  }
}

TEST(ExportExamples, ParametersAreNamedArgumentsWithTheScenesDefaults) {
  // the double pendulum with g doubled: f doubles where q̇ = 0 (f = −∂V/∂q, V ∝ g)
  const Model model = load_model(std::string(RIGID_EXAMPLES_DIR) + "/double_pendulum.toml");
  const double q[] = {0.3, -0.2}, qd[] = {0.0, 0.0};
  double f1[2], f2[2];
  double_pendulum::forces(q, qd, 0.0, f1);
  double_pendulum::forces(q, qd, 0.0, f2, {.g = 2 * 9.81});
  EXPECT_EQ(double_pendulum::Parameters{}.g, 9.81);
  // doubling is exact in binary: the products scale by 2 exactly
  EXPECT_EQ(f2[0], 2 * f1[0]);
  EXPECT_EQ(f2[1], 2 * f1[1]);
  // and the engine with the same value
  lagrange::Workspace w = model.system().make_workspace();
  w.set_parameter("g", 2 * 9.81);
  Eigen::MatrixXd M;
  Eigen::VectorXd f;
  model.system().mass_matrix_and_forces(w, 0.0, Eigen::Vector2d(0.3, -0.2), Eigen::Vector2d::Zero(), M, f);
  EXPECT_NEAR(f[0], f2[0], test::ulps(16, std::abs(f[0])));
  EXPECT_NEAR(f[1], f2[1], test::ulps(16, std::abs(f[1])));
}

// The inverse and forward dynamics of one exported model without constraints, with M and f.
struct ExportedDynamics {
  std::string scene;  // file in examples/
  int n;
  void (*mass_matrix_and_forces)(const double* q, const double* q_dot, double t, double* M, double* f);
  void (*inverse_dynamics)(const double* q, const double* q_dot, const double* q_ddot, double t, double* tau);
  bool (*forward_dynamics)(const double* q, const double* q_dot, const double* tau, double t, double* q_ddot);
};

#define RIGID_EXPORTED_DYNAMICS(ns, file)                                                          \
  ExportedDynamics {                                                                               \
    file, ns::kNumCoordinates,                                                                     \
        [](const double* q, const double* qd, double t, double* M, double* f) {                    \
          ns::mass_matrix_and_forces(q, qd, t, M, f);                                              \
        },                                                                                         \
        [](const double* q, const double* qd, const double* qdd, double t, double* tau) {          \
          ns::inverse_dynamics(q, qd, qdd, t, tau);                                                \
        },                                                                                         \
        [](const double* q, const double* qd, const double* tau, double t, double* qdd) {          \
          return ns::forward_dynamics(q, qd, tau, t, qdd);                                         \
        }                                                                                          \
  }

TEST(ExportExamples, InverseAndForwardDynamicsAgreeWithMfAndTheEngine) {
  // the 3-joint cart_arm.urdf (a prismatic and two hinges), the 7-joint arm7.urdf (derived by
  // the tree's recursions) and the unconstrained scenes
  const std::vector<ExportedDynamics> models = {
      RIGID_EXPORTED_DYNAMICS(cart_arm, "cart_arm.urdf"),
      RIGID_EXPORTED_DYNAMICS(arm7, "arm7.urdf"),
      RIGID_EXPORTED_DYNAMICS(double_pendulum, "double_pendulum.toml"),
      RIGID_EXPORTED_DYNAMICS(cone_pendulum, "cone_pendulum.toml"),
      RIGID_EXPORTED_DYNAMICS(physical_pendulum, "physical_pendulum.toml"),
      RIGID_EXPORTED_DYNAMICS(stiff_dumbbell, "stiff_dumbbell.toml")};
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  for (const ExportedDynamics& ex : models) {
    SCOPED_TRACE(ex.scene);
    const Model model = load_model(std::string(RIGID_EXAMPLES_DIR) + "/" + ex.scene);
    const lagrange::System& sys = model.system();
    ASSERT_EQ(sys.num_coordinates(), ex.n);
    ASSERT_EQ(sys.num_constraints(), 0);
    lagrange::Workspace w = sys.make_workspace();
    const auto n = static_cast<Eigen::Index>(ex.n);
    for (int sample = 0; sample < 8; ++sample) {
      // random states about the initial one: |Δq| ≤ 1, |q̇| ≤ 2, |q̈| ≤ 3, t in [0, 2]
      Eigen::VectorXd q = sys.initial_q(), qd(n), qdd(n);
      for (Eigen::Index i = 0; i < n; ++i) {
        q[i] += uniform(rng);
        qd[i] = 2 * uniform(rng);
        qdd[i] = 3 * uniform(rng);
      }
      const double t = 1 + uniform(rng);
      RowMajor Me(n, n);
      Eigen::VectorXd fe(n), tau(n), qdd_back(n), qdd_forward(n);
      ex.mass_matrix_and_forces(q.data(), qd.data(), t, Me.data(), fe.data());
      ex.inverse_dynamics(q.data(), qd.data(), qdd.data(), t, tau.data());
      // τ = M q̈ − f with the exported M and f: n products summed in another order, a few
      // ulps of |M||q̈| + |f|; 1e-12 of that leaves room for any order
      const double id_scale = Me.norm() * qdd.norm() + fe.norm();
      EXPECT_LT((tau - (Me * qdd - fe)).norm(), 1e-12 * id_scale);
      // q̈ back from τ: a Cholesky solve after τ + f, round-off of ε cond(M) (1 + ‖f‖/‖M q̈‖)
      // relative to q̈; cond(M) < 300 for these models at these states and the largest seen
      // is 5e-13 (stiff_dumbbell's spring force); 1e-10 leaves room
      ASSERT_TRUE(ex.forward_dynamics(q.data(), qd.data(), tau.data(), t, qdd_back.data()));
      EXPECT_LT((qdd_back - qdd).norm(), 1e-10 * qdd.norm());
      // the engine's q̈ (its own solve of M q̈ = f) from the exported forward dynamics at τ = 0
      Eigen::VectorXd qdd_engine, lambda;
      sys.accelerations(w, t, q, qd, qdd_engine, lambda);
      const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
      ASSERT_TRUE(ex.forward_dynamics(q.data(), qd.data(), zero.data(), t, qdd_forward.data()));
      EXPECT_LT((qdd_forward - qdd_engine).norm(), 1e-10 * std::max(1.0, qdd_engine.norm()));
    }
  }
}

TEST(ExportExamples, ForwardDynamicsRefusesAMassMatrixThatIsNotPositiveDefinite) {
  // the double pendulum's M = [[(m1 + m2) l1², m2 l1 l2 cos(θ1 − θ2)], [·, m2 l2²]]: with
  // massless bobs M = 0 (the first pivot 0), with m1 = −3 its first entry is −2 (a pivot < 0)
  const double q[] = {0.3, -0.2}, qd[] = {0.1, 0.4}, tau[] = {1.0, -1.0};
  double qdd[] = {7.0, 7.0};
  EXPECT_FALSE(double_pendulum::forward_dynamics(q, qd, tau, 0.0, qdd, {.m1 = 0.0, .m2 = 0.0}));
  EXPECT_FALSE(double_pendulum::forward_dynamics(q, qd, tau, 0.0, qdd, {.m1 = -3.0}));
  // q_ddot is left as it was
  EXPECT_EQ(qdd[0], 7.0);
  EXPECT_EQ(qdd[1], 7.0);
  // and the model's own masses solve
  EXPECT_TRUE(double_pendulum::forward_dynamics(q, qd, tau, 0.0, qdd));
  EXPECT_NE(qdd[0], 7.0);
}

TEST(ExportExamples, FreeBodiesAndUnknownLanguagesAreRefused) {
  const Model top = load_model(std::string(RIGID_EXAMPLES_DIR) + "/tennis_racket.toml");
  EXPECT_RIGID_ERROR((void)emit_code(top, "c++"), "code export needs generalized coordinates");
  const Model pendulum = load_model(std::string(RIGID_EXAMPLES_DIR) + "/double_pendulum.toml");
  EXPECT_RIGID_ERROR((void)emit_code(pendulum, "c+"), "did you mean 'c++'?");
}

}  // namespace
}  // namespace rigid::scene
