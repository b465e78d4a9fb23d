#include "rigid/spring/network.hpp"

#include <cmath>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "rigid/body/free_body_integrators.hpp"
#include "rigid/lie/so3.hpp"
#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid::spring {
namespace {

using test::ulps;

Eigen::Matrix3d second_moment_inertia(const Network& net) {
  Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
  for (Eigen::Index i = 0; i < net.position.cols(); ++i) {
    const Eigen::Vector3d x = net.position.col(i);
    I += net.mass(i) * (x.squaredNorm() * Eigen::Matrix3d::Identity() - x * x.transpose());
  }
  return I;
}

MassProperties principal_body(double m, const Eigen::Vector3d& I) {
  return MassProperties(m, Eigen::Vector3d::Zero(), I.asDiagonal().toDenseMatrix());
}

TEST(SpringNetwork, HasTheRequestedInertia) {
  const Network net = network_with_inertia(principal_body(3.0, Eigen::Vector3d(1, 2, 2.5)), 1e3);
  const Eigen::Matrix3d I = second_moment_inertia(net);
  EXPECT_LT((I - Eigen::Vector3d(1, 2, 2.5).asDiagonal().toDenseMatrix()).lpNorm<Eigen::Infinity>(), ulps(16, 3));
  EXPECT_EQ(net.springs.size(), 15u);
  EXPECT_NEAR(spring_forces(net).norm(), 0.0, ulps(16));
}

TEST(SpringNetwork, HasTheMassPropertiesOfABodyInAnyFrame) {
  // a full inertia tensor about a COM away from the origin: the particles sit along the
  // principal axes around the COM, and their mass, COM and inertia about the COM are the body's
  const Eigen::Matrix3d R = SO3d::exp(Eigen::Vector3d(0.3, 0.8, -0.5)).matrix();
  const Eigen::Matrix3d I_C = R * Eigen::Vector3d(1, 2, 2.5).asDiagonal() * R.transpose();
  const Eigen::Vector3d c(0.5, -1.0, 2.0);
  const Network net = network_with_inertia(MassProperties(3.0, c, I_C), 1e3);
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < 6; ++i) com += net.mass(i) * net.position.col(i);
  com /= net.mass.sum();
  EXPECT_NEAR(net.mass.sum(), 3.0, ulps(8, 3));
  EXPECT_LT((com - c).norm(), ulps(16, 3));
  Network centred = net;
  for (Eigen::Index i = 0; i < 6; ++i) centred.position.col(i) -= c;
  // eigenvectors are accurate to ~10 ε and the particles sit ~1 m out: 1e-13 kg·m²
  EXPECT_LT((second_moment_inertia(centred) - I_C).lpNorm<Eigen::Infinity>(), 1e-13);
}

// Orientation of the network: the rotation best mapping rest positions to current ones
// (mass-weighted Kabsch fit about the COM).
Eigen::Matrix3d fit_rotation(const Network& rest, const Network& now) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < now.position.cols(); ++i) c += now.mass(i) * now.position.col(i);
  c /= now.mass.sum();
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for (Eigen::Index i = 0; i < now.position.cols(); ++i)
    H += now.mass(i) * rest.position.col(i) * (now.position.col(i) - c).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return svd.matrixV() * D * svd.matrixU().transpose();
}

struct Deviation {
  double angle = 0, com = 0;
};

Deviation deviation_from_rigid(double k) {
  // Tennis-racket-like (a lamina's I = (1, 2, 3) has no out-of-plane extent, which a
  // six-particle network cannot represent): rotation near the unstable middle axis.
  const Eigen::Vector3d I(1, 2, 2.8), w0(0.01, 1, 0.01);
  const Network rest = network_with_inertia(principal_body(1.0, I), k);
  Network net = rest;
  for (Eigen::Index i = 0; i < net.position.cols(); ++i) net.velocity.col(i) = w0.cross(net.position.col(i));
  body::FreeBodyState rigid;
  rigid.w_B = w0;
  // h resolves the stiffest spring mode at k = 1e6 (√(k/m_i) ≈ 2.4e3 rad/s, h·ω ≈ 0.6),
  // so the discretisation error stays below the 1/k deviation being measured.
  const double h = 2.5e-4;
  Deviation d;
  for (int step = 1; step <= 8000; ++step) {  // 2 s
    step_implicit_midpoint(net, h);
    rigid = body::step_free_body(body::FreeBodyMethod::kSplitting6, I, rigid, h);
    if (step % 200 == 0) {
      const Eigen::AngleAxisd diff(fit_rotation(rest, net).transpose() * rigid.R_WB.matrix());
      d.angle = std::max(d.angle, std::abs(diff.angle()));
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (Eigen::Index i = 0; i < net.position.cols(); ++i) c += net.mass(i) * net.position.col(i);
      d.com = std::max(d.com, c.norm());
    }
  }
  return d;
}

TEST(SpringNetwork, ConvergesToTheRigidBodyAsStiffnessGrows) {
  // Centrifugal stretching and the oscillation it excites scale like m ω² a / k, so the
  // orientation deviation should fall like 1/k: slope −1 per decade of k, measured.
  const Deviation d2 = deviation_from_rigid(1e2), d4 = deviation_from_rigid(1e4), d6 = deviation_from_rigid(1e6);
  const double slope1 = std::log10(d2.angle / d4.angle) / 2.0;
  const double slope2 = std::log10(d4.angle / d6.angle) / 2.0;
  EXPECT_NEAR(slope1, 1.0, 0.2) << d2.angle << " " << d4.angle;
  EXPECT_NEAR(slope2, 1.0, 0.2) << d4.angle << " " << d6.angle;
  EXPECT_LT(d6.angle, 1e-4);
  // COM: the network's momentum is zero and the midpoint rule keeps it; round-off only.
  for (const Deviation& d : {d2, d4, d6}) EXPECT_LT(d.com, 1e-12);
}

TEST(SpringNetwork, RejectsBadInput) {
  EXPECT_RIGID_ERROR((void)network_with_inertia(principal_body(1, Eigen::Vector3d(1, 2, 3)), 0.0),
                     "stiffness must be finite and > 0 N/m, got 0");
  EXPECT_RIGID_ERROR((void)network_with_inertia(principal_body(1, Eigen::Vector3d(1, 2, 3.0)), 1.0),
                     "need I3 < I1 + I2 strictly");
  Network net = network_with_inertia(principal_body(1, Eigen::Vector3d(1, 2, 2.5)), 1e3);
  net.springs[3].j = 9;
  EXPECT_RIGID_ERROR((void)simulate_network(net, 1e-3, {0.1}),
                     "spring 3 joins particles 0 and 9; expected two different particles of 0 … 5");
}

TEST(SpringNetwork, NewtonThatDoesNotConvergeIsRefused) {
  // two Newton iterations cannot reach 1e-15 from the explicit predictor of a spinning,
  // stiff network; the step is refused and the network left as it was
  Network net = network_with_inertia(principal_body(1, Eigen::Vector3d(1, 2, 2.5)), 1e6);
  for (Eigen::Index i = 0; i < 6; ++i) net.velocity.col(i) = Eigen::Vector3d(0, 0, 5).cross(net.position.col(i));
  const Network before = net;
  EXPECT_RIGID_ERROR(step_implicit_midpoint(net, 1e-2, {.max_iterations = 2}),
                     "the Newton iteration of the implicit midpoint did not converge in 2 iterations at h = 0.01 s");
  EXPECT_EQ(net.position, before.position);
  EXPECT_EQ(net.velocity, before.velocity);
}

TEST(SpringNetwork, StepTooLargeToConvergeIsRefusedNamingTheStep) {
  // a stiff (k = 1e6 N/m) network spinning at 5 rad/s, one step of 100 s: the default 50
  // Newton iterations end 1e4 m from a solution (measured), far from the tolerance; the
  // step is refused with h, the last correction, the tolerance and the residual, the march
  // puts the step and t in front, and a step taken directly leaves the network as it was
  Network net = network_with_inertia(principal_body(1, Eigen::Vector3d(1, 2, 2.5)), 1e6);
  for (Eigen::Index i = 0; i < 6; ++i)
    net.velocity.col(i) = Eigen::Vector3d(0.1, 0, 5).cross(net.position.col(i));
  EXPECT_RIGID_ERROR(
      (void)simulate_network(net, 100.0, {100.0}),
      "at step 1 from t = 0 s: step_implicit_midpoint(): the Newton iteration of the "
      "implicit midpoint did not converge in 50 iterations at h = 100 s: last correction ");
  const Network before = net;
  EXPECT_RIGID_ERROR(step_implicit_midpoint(net, 100.0),
                     "residual of the implicit equation |P − p0 − ½h v0 − ¼h² M⁻¹ f(P)| = ");
  EXPECT_RIGID_ERROR(step_implicit_midpoint(net, 100.0),
                     "m at the last iterate; use a smaller step");
  EXPECT_EQ(net.position, before.position);
  EXPECT_EQ(net.velocity, before.velocity);
  // the same network at h = 1 s converges (A-stable: h is not limited by √(m/k) = 4e-4 s)
  EXPECT_NO_THROW((void)simulate_network(net, 1.0, {1.0}));
}

TEST(SpringNetwork, SimulateSamplesAndRefusesNonFiniteState) {
  Network net = network_with_inertia(principal_body(1, Eigen::Vector3d(1, 2, 2.5)), 1e3);
  const NetworkTrajectory tr = simulate_network(net, 1e-3, {0.0, 0.05, 0.1});
  ASSERT_EQ(tr.t.size(), 3u);
  EXPECT_EQ(tr.t[2], 0.1);
  EXPECT_EQ(tr.position[0], net.position);
  net.velocity(1, 4) = std::nan("");
  EXPECT_RIGID_ERROR((void)simulate_network(net, 1e-3, {0.1}),
                     "the initial state is not finite: particle 4 velocity.y = nan");
}

}  // namespace
}  // namespace rigid::spring

namespace rigid::spring {
namespace {

TEST(SpringNetwork, DivergenceIsRefused) {
  // one particle thrown at 1e308 m/s: the springs' forces k·Δ overflow in the first step, the
  // Newton solve of the midpoint turns non-finite and the run stops naming the step size
  Network net = network_with_inertia(MassProperties(1.0, Eigen::Vector3d::Zero(),
                                                    Eigen::Vector3d(1, 2, 2.5).asDiagonal().toDenseMatrix()),
                                     1e3);
  net.velocity(0, 0) = 1e308;
  EXPECT_RIGID_ERROR((void)simulate_network(net, 0.1, {1.0}), "h = 0.1 s");
}

}  // namespace
}  // namespace rigid::spring
