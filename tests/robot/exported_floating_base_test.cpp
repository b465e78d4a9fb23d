// The flat C++ export of MuJoCo's humanoid on its free root (`rigid eom humanoid.xml --emit c++
// --flat`: nq = 28, nv = 27, the root's ω in its body frame, generated at build time) against
// MuJoCo on the same file: M = mj_fullM, inverse dynamics = M a + qfrc_bias − qfrc_passive, and
// forward dynamics = mj_forward's qacc with constraints and contacts off; coordinate_rates
// against the quaternion product ½ q ⊗ (0, ω). The exported header declares its functions at
// global scope, as does exported_derivatives_test.cpp's: it is included into an unnamed
// namespace here (after <cmath>, the one header it includes), so that the two exports' inline
// functions of one name do not meet at link time.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include "support/mujoco_model.hpp"

namespace {
#include "humanoid_flat.hpp"
}  // namespace

namespace rigid {
namespace {

// Relative to the largest entry of the reference (at least 1). M and the forces are sums of a
// few hundred products of the entries' scale, rounded in another order than MuJoCo's: 1e-12;
// forward dynamics divides by pivots of M, whose condition reaches ~1e4 on the humanoid
// (light hands on a heavy torso): 1e-9.
double relative(const Eigen::VectorXd& a, const Eigen::VectorXd& ref) {
  return (a - ref).cwiseAbs().maxCoeff() / std::max(1.0, ref.cwiseAbs().maxCoeff());
}

TEST(ExportedFloatingBase, HumanoidMatchesMuJoCo) {
  auto m = test::load_mujoco(RIGID_HUMANOID);
  ASSERT_NE(m, nullptr);
  ASSERT_EQ(m->nq, nq);
  ASSERT_EQ(m->nv, nv);
  m->opt.disableflags |= mjDSBL_CONSTRAINT | mjDSBL_CONTACT;  // the joint limits and contacts
  test::MjDataPtr d(mj_makeData(m.get()));
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(-2, 2);
  double worst_M = 0, worst_id = 0, worst_fd = 0, worst_rate = 0;
  for (int s = 0; s < 20; ++s) {
    Eigen::VectorXd q, v;
    test::random_state(m.get(), rng, q, v);
    Eigen::VectorXd a(nv), tau(nv);
    for (int i = 0; i < nv; ++i) {
      a(i) = u(rng);
      tau(i) = u(rng);
    }
    for (int i = 0; i < nq; ++i) d->qpos[i] = q(i);
    for (int i = 0; i < nv; ++i) {
      d->qvel[i] = v(i);
      d->qfrc_applied[i] = tau(i);
    }
    mj_forward(m.get(), d.get());
    std::vector<mjtNum> dense(static_cast<std::size_t>(nv * nv));
    mj_fullM(m.get(), dense.data(), d->qM);
    const Eigen::MatrixXd M_ref = Eigen::Map<const Eigen::MatrixXd>(dense.data(), nv, nv).transpose();
    const Eigen::VectorXd bias = Eigen::Map<const Eigen::VectorXd>(d->qfrc_bias, nv) -
                                 Eigen::Map<const Eigen::VectorXd>(d->qfrc_passive, nv);
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> M(nv, nv);
    mass_matrix(q.data(), M.data());
    worst_M = std::max(worst_M, relative(Eigen::Map<const Eigen::VectorXd>(M.data(), nv * nv),
                                         Eigen::Map<const Eigen::VectorXd>(dense.data(), nv * nv)));
    EXPECT_LT((M - M_ref).cwiseAbs().maxCoeff(), 1e-12 * M_ref.cwiseAbs().maxCoeff());
    Eigen::VectorXd id(nv), fd(nv), rate(nq);
    inverse_dynamics(q.data(), v.data(), a.data(), id.data());
    worst_id = std::max(worst_id, relative(id, M_ref * a + bias));
    forward_dynamics(q.data(), v.data(), tau.data(), fd.data());
    worst_fd = std::max(worst_fd, relative(fd, Eigen::Map<const Eigen::VectorXd>(d->qacc, nv)));
    coordinate_rates(q.data(), v.data(), rate.data());
    const Eigen::Quaterniond Q(q(3), q(4), q(5), q(6));
    const Eigen::Quaterniond W(0, v(3), v(4), v(5));
    const Eigen::Quaterniond dQ = Q * W;
    Eigen::VectorXd expected(nq);
    expected << v.head<3>(), 0.5 * dQ.w(), 0.5 * dQ.x(), 0.5 * dQ.y(), 0.5 * dQ.z(), v.tail(nv - 6);
    worst_rate = std::max(worst_rate, relative(rate, expected));
  }
  std::printf("exported humanoid (free root), 20 states: M %.2e, inverse %.2e, forward %.2e, rates %.2e\n",
              worst_M, worst_id, worst_fd, worst_rate);
  EXPECT_LT(worst_M, 1e-12);
  EXPECT_LT(worst_id, 1e-12);
  EXPECT_LT(worst_fd, 1e-9);
  EXPECT_LT(worst_rate, 1e-15);
}

}  // namespace
}  // namespace rigid
