// The flat C++ export of MuJoCo's humanoid on its free root (`rigid eom humanoid.xml --emit c++
// --flat`: nq = 28, nv = 27, the root's ω in its body frame, generated at build time) against
// MuJoCo on the same file: M = mj_fullM, inverse dynamics = M a + qfrc_bias − qfrc_passive, and
// forward dynamics = mj_forward's qacc with constraints and contacts off; coordinate_rates
// against the quaternion product ½ q ⊗ (0, ω). The derivatives of the humanoid's export and of
// a tree with ball joints inside it (data/ball_tree.xml), whose columns for a ball are along its
// tangent q ⊗ exp(δθ), against central differences along MuJoCo's tangent (mj_integratePos)
// and against MuJoCo's transition derivatives (mjd_transitionFD). The exported headers declare
// their functions at global scope, as does exported_derivatives_test.cpp's: they are included
// into namespaces of this translation unit (after <cmath>, the one header they include), so that
// the exports' inline functions of one name do not meet at link time.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include "support/mujoco_model.hpp"

namespace {
namespace humanoid {
#include "humanoid_flat.hpp"
}  // namespace humanoid
namespace ball_tree {
#include "ball_tree_flat.hpp"
}  // namespace ball_tree
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
  ASSERT_EQ(m->nq, humanoid::nq);
  ASSERT_EQ(m->nv, humanoid::nv);
  m->opt.disableflags |= mjDSBL_CONSTRAINT | mjDSBL_CONTACT;  // the joint limits and contacts
  test::MjDataPtr d(mj_makeData(m.get()));
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(-2, 2);
  double worst_M = 0, worst_id = 0, worst_fd = 0, worst_rate = 0;
  constexpr int nq = humanoid::nq, nv = humanoid::nv;
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
    humanoid::mass_matrix(q.data(), M.data());
    worst_M = std::max(worst_M, relative(Eigen::Map<const Eigen::VectorXd>(M.data(), nv * nv),
                                         Eigen::Map<const Eigen::VectorXd>(dense.data(), nv * nv)));
    EXPECT_LT((M - M_ref).cwiseAbs().maxCoeff(), 1e-12 * M_ref.cwiseAbs().maxCoeff());
    Eigen::VectorXd id(nv), fd(nv), rate(nq);
    humanoid::inverse_dynamics(q.data(), v.data(), a.data(), id.data());
    worst_id = std::max(worst_id, relative(id, M_ref * a + bias));
    humanoid::forward_dynamics(q.data(), v.data(), tau.data(), fd.data());
    worst_fd = std::max(worst_fd, relative(fd, Eigen::Map<const Eigen::VectorXd>(d->qacc, nv)));
    humanoid::coordinate_rates(q.data(), v.data(), rate.data());
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

// ----------------------------------------------------------------------------------------
// the derivatives

using Rows = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// One exported model's functions, by name, and the MJCF it was exported from.
struct Flat {
  const char* name;
  const char* path;
  int nq, nv;
  std::function<void(const double*, double*)> mass_matrix;
  std::function<void(const double*, const double*, const double*, double*)> inverse_dynamics,
      forward_dynamics;
  std::function<void(const double*, const double*, const double*, double*, double*, double*)>
      inverse_dynamics_derivatives;
  std::function<void(const double*, const double*, const double*, double*, double*, double*, double*)>
      forward_dynamics_derivatives;
};

#define RIGID_FLAT(ns, path)                                                                       \
  Flat {                                                                                           \
    #ns, path, ns::nq, ns::nv, [](const double* q, double* M) { ns::mass_matrix(q, M); },          \
        [](const double* q, const double* v, const double* a, double* t) {                         \
          ns::inverse_dynamics(q, v, a, t);                                                        \
        },                                                                                         \
        [](const double* q, const double* v, const double* t, double* a) {                         \
          ns::forward_dynamics(q, v, t, a);                                                        \
        },                                                                                         \
        [](const double* q, const double* v, const double* a, double* dq, double* dv, double* da) { \
          ns::inverse_dynamics_derivatives(q, v, a, dq, dv, da);                                   \
        },                                                                                         \
        [](const double* q, const double* v, const double* t, double* a, double* dq, double* dv,    \
           double* dt) { ns::forward_dynamics_derivatives(q, v, t, a, dq, dv, dt); }                \
  }

std::vector<Flat> flat_models() {
  return {RIGID_FLAT(humanoid, RIGID_HUMANOID), RIGID_FLAT(ball_tree, RIGID_BALL_TREE)};
}

// The largest entry of a − b relative to b's largest (at least 1).
double relative(const Rows& a, const Rows& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(1.0, b.cwiseAbs().maxCoeff());
}

// x(q ⊕ h e_j) − x(q ⊖ h e_j) over 2h for each velocity j, q ⊕ δ = mj_integratePos(q, δ):
// a ball's quaternion turned by q ⊗ exp(δθ), δθ in its body's frame, the other entries moved
// by δ; and the same along each velocity of v. `x(q, v)` fills n values.
void central_differences(const mjModel* m, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                         double h, int n,
                         const std::function<void(const double*, const double*, double*)>& x,
                         Rows& dq, Rows& dv) {
  const int nv = m->nv;
  dq.resize(n, nv);
  dv.resize(n, nv);
  Eigen::VectorXd plus(n), minus(n);
  for (int j = 0; j < nv; ++j) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(nv);
    e(j) = 1;
    Eigen::VectorXd qp = q, qm = q;
    mj_integratePos(m, qp.data(), e.data(), h);
    mj_integratePos(m, qm.data(), e.data(), -h);
    x(qp.data(), v.data(), plus.data());
    x(qm.data(), v.data(), minus.data());
    dq.col(j) = (plus - minus) / (2 * h);
    const Eigen::VectorXd vp = v + h * e, vm = v - h * e;
    x(q.data(), vp.data(), plus.data());
    x(q.data(), vm.data(), minus.data());
    dv.col(j) = (plus - minus) / (2 * h);
  }
}

// ∂τ/∂(q, q̇) and ∂q̈/∂(q, q̇) against central differences of inverse_dynamics and
// forward_dynamics along the same tangent, at steps 1e-2 … 1e-5. The truncation error is
// h² |x'''|/6 and the rounding ~1e-16 |x|/h: second order down to h ~ 1e-4 (each tenfold step
// cuts the error ~100-fold), ~1e-9 relative at the best step, where a wrong column would stay
// at its own size. The acceptance bound is 1e-6 relative to the largest entry. Also
// ∂τ/∂q̈ = mass_matrix's M (the same expressions), q̈ = forward_dynamics' and ∂q̈/∂τ M = 1.
TEST(ExportedFloatingBase, DerivativesAreCentralDifferencesAlongTheTangent) {
  for (const Flat& f : flat_models()) {
    SCOPED_TRACE(f.name);
    auto m = test::load_mujoco(f.path);
    ASSERT_NE(m, nullptr);
    ASSERT_EQ(m->nq, f.nq);
    ASSERT_EQ(m->nv, f.nv);
    const int nv = f.nv;
    std::mt19937 rng(31);
    std::uniform_real_distribution<double> u(-2, 2);
    const std::vector<double> steps = {1e-2, 1e-3, 1e-4, 1e-5};
    std::vector<double> worst_id(steps.size()), worst_fd(steps.size());
    double worst_identity = 0;
    for (int sample = 0; sample < 5; ++sample) {
      Eigen::VectorXd q, v, a(nv), tau(nv);
      test::random_state(m.get(), rng, q, v);
      for (int i = 0; i < nv; ++i) {
        a(i) = u(rng);
        tau(i) = u(rng);
      }
      Rows dq(nv, nv), dv(nv, nv), da(nv, nv), M(nv, nv);
      f.inverse_dynamics_derivatives(q.data(), v.data(), a.data(), dq.data(), dv.data(), da.data());
      f.mass_matrix(q.data(), M.data());
      EXPECT_LE(relative(da, M), 1e-15);
      Rows fq(nv, nv), fv(nv, nv), ft(nv, nv);
      Eigen::VectorXd acc(nv), acc_alone(nv);
      f.forward_dynamics_derivatives(q.data(), v.data(), tau.data(), acc.data(), fq.data(),
                                     fv.data(), ft.data());
      f.forward_dynamics(q.data(), v.data(), tau.data(), acc_alone.data());
      EXPECT_LE((acc - acc_alone).cwiseAbs().maxCoeff(),
                1e-12 * std::max(1.0, acc.cwiseAbs().maxCoeff()));
      // M's condition on the humanoid reaches ~1e4: ∂q̈/∂τ M = 1 to 1e-16 × that, with room
      worst_identity = std::max(worst_identity, (ft * M - Rows::Identity(nv, nv)).cwiseAbs().maxCoeff());
      for (std::size_t k = 0; k < steps.size(); ++k) {
        Rows nq_id, nv_id, nq_fd, nv_fd;
        central_differences(
            m.get(), q, v, steps[k], nv,
            [&](const double* qq, const double* vv, double* out) { f.inverse_dynamics(qq, vv, a.data(), out); },
            nq_id, nv_id);
        central_differences(
            m.get(), q, v, steps[k], nv,
            [&](const double* qq, const double* vv, double* out) { f.forward_dynamics(qq, vv, tau.data(), out); },
            nq_fd, nv_fd);
        worst_id[k] = std::max({worst_id[k], relative(nq_id, dq), relative(nv_id, dv)});
        worst_fd[k] = std::max({worst_fd[k], relative(nq_fd, fq), relative(nv_fd, fv)});
      }
    }
    std::printf("%s: derivatives against central differences along the tangent, step 1e-2 ... 1e-5:\n"
                "  inverse %.1e %.1e %.1e %.1e, forward %.1e %.1e %.1e %.1e; |dqdd/dtau M - 1| %.1e\n",
                f.name, worst_id[0], worst_id[1], worst_id[2], worst_id[3], worst_fd[0], worst_fd[1],
                worst_fd[2], worst_fd[3], worst_identity);
    EXPECT_LT(worst_identity, 1e-10);
    for (const std::vector<double>* worst : {&worst_id, &worst_fd}) {
      EXPECT_LT(*std::min_element(worst->begin(), worst->end()), 1e-6);
      // second order where truncation dominates
      EXPECT_LT((*worst)[1], (*worst)[0] / 30);
      EXPECT_LT((*worst)[2], (*worst)[1] / 30);
    }
  }
}

// MuJoCo's semi-implicit Euler step (mjd_transitionFD's A = ∂(q', v')/∂(q, v)) treats joint
// damping D implicitly: v' = v + h q̈_E with q̈_E = (M + h D)⁻¹ (f + τ) = (M + h D)⁻¹ M q̈. Its
// derivatives, with τ_ID(q, q̇, q̈) = M q̈ − f the inverse dynamics,
//   ∂q̈_E/∂x = −(M + h D)⁻¹ ∂τ_ID/∂x at q̈ = q̈_E,
// are what A's rows of v' hold (over h, less the identity for ∂v'/∂v), in MuJoCo's tangent for
// q. Centered differences with ε = 1e-6: rounding ~1e-16 |v'|/ε ~ 1e-9 in A, ~1e-6 over
// h = 1e-3; the tolerance, 1e-5 of the largest entry (at least 1), leaves a factor 10.
TEST(ExportedFloatingBase, DerivativesMatchMuJoCoTransitionDerivatives) {
  for (const Flat& f : flat_models()) {
    SCOPED_TRACE(f.name);
    auto m = test::load_mujoco(f.path);
    ASSERT_NE(m, nullptr);
    m->opt.timestep = 1e-3;
    m->opt.integrator = mjINT_EULER;
    m->opt.disableflags |= mjDSBL_CONSTRAINT | mjDSBL_CONTACT;  // the joint limits and contacts
    test::MjDataPtr d(mj_makeData(m.get()));
    const int nv = f.nv;
    const double h = m->opt.timestep;
    const Eigen::VectorXd damping = Eigen::Map<const Eigen::VectorXd>(m->dof_damping, nv);
    std::mt19937 rng(41);
    std::uniform_real_distribution<double> u(-1, 1);
    double worst_q = 0, worst_v = 0;
    for (int sample = 0; sample < 5; ++sample) {
      Eigen::VectorXd q, v, tau(nv);
      test::random_state(m.get(), rng, q, v);
      for (int i = 0; i < nv; ++i) tau(i) = u(rng);
      for (int i = 0; i < f.nq; ++i) d->qpos[i] = q(i);
      for (int i = 0; i < nv; ++i) {
        d->qvel[i] = v(i);
        d->qfrc_applied[i] = tau(i);
      }
      const int n2 = 2 * nv + m->na;
      std::vector<double> A(static_cast<std::size_t>(n2 * n2));
      mjd_transitionFD(m.get(), d.get(), 1e-6, 1, A.data(), nullptr, nullptr, nullptr);
      const Rows Amj = Eigen::Map<const Rows>(A.data(), n2, n2);
      Rows M(nv, nv), dq(nv, nv), dv(nv, nv), da(nv, nv);
      Eigen::VectorXd acc(nv);
      f.mass_matrix(q.data(), M.data());
      f.forward_dynamics(q.data(), v.data(), tau.data(), acc.data());
      const Eigen::MatrixXd implicit = M + h * Eigen::MatrixXd(damping.asDiagonal());
      const Eigen::PartialPivLU<Eigen::MatrixXd> lu(implicit);
      const Eigen::VectorXd acc_euler = lu.solve(M * acc);
      f.inverse_dynamics_derivatives(q.data(), v.data(), acc_euler.data(), dq.data(), dv.data(),
                                     da.data());
      const Rows expect_q = -lu.solve(Eigen::MatrixXd(dq));
      const Rows expect_v = -lu.solve(Eigen::MatrixXd(dv));
      const Rows mj_q = Amj.block(nv, 0, nv, nv) / h;
      const Rows mj_v = (Amj.block(nv, nv, nv, nv) - Rows::Identity(nv, nv)) / h;
      worst_q = std::max(worst_q, relative(mj_q, expect_q));
      worst_v = std::max(worst_v, relative(mj_v, expect_v));
    }
    std::printf("%s: against mjd_transitionFD, 5 states: d/dq %.1e, d/dv %.1e\n", f.name, worst_q,
                worst_v);
    EXPECT_LT(worst_q, 1e-5);
    EXPECT_LT(worst_v, 1e-5);
  }
}

}  // namespace
}  // namespace rigid
