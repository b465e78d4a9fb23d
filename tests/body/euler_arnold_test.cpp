#include "rigid/body/euler_arnold.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "rigid/body/free_body_exact.hpp"
#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid::body {
namespace {

Eigen::Matrix3d hat(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v(2), v(1), v(2), 0, -v(0), -v(1), v(0), 0;
  return m;
}

TEST(EulerArnold, ThreeDimensionsReproduceTheExactFreeBody) {
  // I = (J2+J3, J3+J1, J1+J2): J = (2, 1, 0.5) gives I = (1.5, 2.5, 3).
  const Eigen::VectorXd J = Eigen::Vector3d(2.0, 1.0, 0.5);
  const Eigen::Vector3d I(J(1) + J(2), J(2) + J(0), J(0) + J(1));
  const Eigen::Vector3d w0(0.3, 0.8, -0.4);
  Eigen::MatrixXd M = hat(I.cwiseProduct(w0));
  const double h = 1e-3;
  for (int i = 0; i < 5000; ++i) M = euler_arnold_rk4_step(J, M, h);
  const Eigen::Vector3d L(M(2, 1), M(0, 2), M(1, 0));
  const Eigen::Vector3d w = L.cwiseQuotient(I);
  const Eigen::Vector3d exact = FreeBodyExact(I, w0).omega_body(5.0);
  // RK4 at h = 1e-3 over 5 s: global error ~ h⁴ ≈ 1e-12.
  EXPECT_LT((w - exact).lpNorm<Eigen::Infinity>(), 1e-10);
}

TEST(EulerArnold, CasimirsConservedForNUpTo8) {
  for (int n = 3; n <= 8; ++n) {
    Eigen::VectorXd J(n);
    for (int i = 0; i < n; ++i) J(i) = 1.0 + 0.37 * i + 0.05 * i * i;
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) A(i, j) = std::sin(1.0 + 3.0 * i + 7.0 * j);
    Eigen::MatrixXd M = A - A.transpose();
    Eigen::MatrixXd P = M * M;
    const double c2 = P.trace(), c4 = (P * P).trace();
    const double E0 = -0.5 * (M * euler_arnold_velocity(J, M)).trace();
    for (int i = 0; i < 2000; ++i) M = euler_arnold_rk4_step(J, M, 1e-3);
    P = M * M;
    // tr(M²), tr(M⁴) and the energy −½ tr(MΩ) are exact invariants; RK4 keeps them
    // to its local error O(h⁵)·steps ≈ 1e-12 relative here.
    EXPECT_NEAR(P.trace(), c2, 1e-10 * std::abs(c2)) << "n = " << n;
    EXPECT_NEAR((P * P).trace(), c4, 1e-10 * std::abs(c4)) << "n = " << n;
    EXPECT_NEAR(-0.5 * (M * euler_arnold_velocity(J, M)).trace(), E0, 1e-10 * std::abs(E0)) << "n = " << n;
    // The flow actually moved M (the check above is not vacuous).
    EXPECT_GT((euler_arnold_rhs(J, M)).norm(), 1e-3) << "n = " << n;
  }
}

TEST(EulerArnold, RejectsBadInput) {
  const Eigen::VectorXd J = Eigen::Vector3d(1, 2, 3);
  EXPECT_RIGID_ERROR((void)euler_arnold_velocity(J, Eigen::MatrixXd::Zero(4, 4)),
                     "M must be 3×3 to match J of size 3");
  EXPECT_RIGID_ERROR((void)euler_arnold_velocity(J, Eigen::MatrixXd::Identity(3, 3)),
                     "M must be skew-symmetric; ‖M + Mᵀ‖_max = 2");
  EXPECT_RIGID_ERROR((void)euler_arnold_velocity(Eigen::Vector3d(1, 0, 3), Eigen::MatrixXd::Zero(3, 3)),
                     "mass matrix entries J must be finite and > 0");
}

}  // namespace
}  // namespace rigid::body
