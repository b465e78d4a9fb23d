#include "rigid/body/euler_arnold.hpp"

#include "rigid/common/error.hpp"

namespace rigid::body {

Eigen::MatrixXd euler_arnold_velocity(const Eigen::VectorXd& J, const Eigen::MatrixXd& M) {
  const Eigen::Index n = J.size();
  RIGID_REQUIRE(n >= 2 && M.rows() == n && M.cols() == n,
                "M must be {}×{} to match J of size {} (n ≥ 2), got {}×{}", n, n, n, M.rows(), M.cols());
  RIGID_REQUIRE(J.allFinite() && (J.array() > 0).all(), "mass matrix entries J must be finite and > 0");
  RIGID_REQUIRE((M + M.transpose()).lpNorm<Eigen::Infinity>() <= 1e-12 * (1.0 + M.lpNorm<Eigen::Infinity>()),
                "M must be skew-symmetric; ‖M + Mᵀ‖_max = {}",
                (M + M.transpose()).lpNorm<Eigen::Infinity>());
  Eigen::MatrixXd W(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) W(i, j) = M(i, j) / (J(i) + J(j));
  return W;
}

Eigen::MatrixXd euler_arnold_rhs(const Eigen::VectorXd& J, const Eigen::MatrixXd& M) {
  const Eigen::MatrixXd W = euler_arnold_velocity(J, M);
  return M * W - W * M;
}

Eigen::MatrixXd euler_arnold_rk4_step(const Eigen::VectorXd& J, const Eigen::MatrixXd& M, double h) {
  const Eigen::MatrixXd k1 = euler_arnold_rhs(J, M);
  const Eigen::MatrixXd k2 = euler_arnold_rhs(J, M + 0.5 * h * k1);
  const Eigen::MatrixXd k3 = euler_arnold_rhs(J, M + 0.5 * h * k2);
  const Eigen::MatrixXd k4 = euler_arnold_rhs(J, M + h * k3);
  return M + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
}

}  // namespace rigid::body
