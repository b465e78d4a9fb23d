#pragma once

#include <Eigen/Core>
#include <unsupported/Eigen/MatrixFunctions>

namespace rigid::detail {

/// φ(A) = Σₖ Aᵏ/(k+1)! = A⁻¹(e^A − I) for any square A, read off the top-right block of
/// exp([[A, I], [0, 0]]) = [[e^A, φ(A)], [0, I]] [Higham2008, §10.7]: the exponential of the
/// augmented matrix is computed by scaling and squaring with Padé [Higham2005], so φ needs
/// neither a truncated series nor an inverse of A (which is singular on so(n)).
inline Eigen::MatrixXd phi(const Eigen::MatrixXd& A) {
  const Eigen::Index m = A.rows();
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(2 * m, 2 * m);
  B.topLeftCorner(m, m) = A;
  B.topRightCorner(m, m).setIdentity();
  const Eigen::MatrixXd E = B.exp();
  return E.topRightCorner(m, m);
}

}  // namespace rigid::detail
