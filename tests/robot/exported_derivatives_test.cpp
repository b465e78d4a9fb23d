// The flat C++ export's derivatives (`rigid eom MODEL --emit c++ --flat`) against MuJoCo's
// finite-difference transition derivatives (mjd_transitionFD) on the same file: cart_arm (a
// slide, two hinges, a welded link) without its joint damping, generated at build time. The
// exported header declares its functions at global scope, so it has this translation unit to
// itself.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include "cart_arm_undamped_flat.hpp"
#include "support/mujoco_model.hpp"

namespace rigid {
namespace {

double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

// MuJoCo's semi-implicit Euler step (no damping: nothing implicit) has
//   v' = v + h q̈(q, v, τ),  q' = q + h v',
// so the rows of v' in A = ∂(q', v')/∂(q, v) are h ∂q̈/∂q and I + h ∂q̈/∂v. mjd_transitionFD
// takes centered differences with step ε = 1e-6 on q and v: the truncation error is
// ~ε² |q̈'''| (~1e-12) and the rounding ~1e-16 |v'|/ε ~1e-10 in A, ~1e-7 in ∂q̈/∂x after the
// division by h = 1e-3; the tolerance 1e-5 relative to the largest entry leaves a factor 100.
TEST(ExportedDerivatives, MatchMuJoCoTransitionDerivatives) {
  auto m = test::load_mujoco(RIGID_UNDAMPED_CART_ARM);
  ASSERT_EQ(m->nv, nv);
  ASSERT_EQ(m->nq, nq);
  m->opt.timestep = 1e-3;
  m->opt.integrator = mjINT_EULER;
  m->opt.disableflags |= mjDSBL_CONSTRAINT | mjDSBL_CONTACT;  // the joint limits and contacts
  test::MjDataPtr d(mj_makeData(m.get()));
  const double h = m->opt.timestep;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  const int n = nv;
  for (int sample = 0; sample < 10; ++sample) {
    double q[nq], v[nv], tau[nv];
    for (int i = 0; i < n; ++i) {
      q[i] = d->qpos[i] = u(rng);
      v[i] = d->qvel[i] = u(rng);
      tau[i] = d->qfrc_applied[i] = u(rng);
    }
    std::vector<double> A(static_cast<std::size_t>(4 * n * n));
    mjd_transitionFD(m.get(), d.get(), 1e-6, 1, A.data(), nullptr, nullptr, nullptr);
    double a[nv];
    std::vector<double> dq(static_cast<std::size_t>(n * n)), dv(dq.size()), dtau(dq.size());
    forward_dynamics_derivatives(q, v, tau, a, dq.data(), dv.data(), dtau.data());
    // the accelerations themselves: MuJoCo's qacc of mj_forward
    mj_forward(m.get(), d.get());
    for (int i = 0; i < n; ++i) EXPECT_NEAR(a[i], d->qacc[i], 1e-12 * (1 + std::abs(a[i])));
    std::vector<double> err_q(dq.size()), err_v(dq.size());
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        const auto row = static_cast<std::size_t>((n + i) * 2 * n);
        const double mj_dq = A[row + static_cast<std::size_t>(j)] / h;
        const double mj_dv = (A[row + static_cast<std::size_t>(n + j)] - (i == j ? 1.0 : 0.0)) / h;
        err_q[static_cast<std::size_t>(i * n + j)] = mj_dq - dq[static_cast<std::size_t>(i * n + j)];
        err_v[static_cast<std::size_t>(i * n + j)] = mj_dv - dv[static_cast<std::size_t>(i * n + j)];
      }
    }
    EXPECT_LT(max_abs(err_q), 1e-5 * max_abs(dq)) << "sample " << sample;
    EXPECT_LT(max_abs(err_v), 1e-5 * std::max(max_abs(dv), 1.0)) << "sample " << sample;
  }
}

}  // namespace
}  // namespace rigid
