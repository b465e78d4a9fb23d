#include "rigid/body/euler.hpp"

namespace rigid::body {

template <typename Scalar>
Eigen::Matrix<Scalar, 3, 1> euler_rhs(const Eigen::Vector3d& I_B,
                                      const Eigen::Matrix<Scalar, 3, 1>& w_B,
                                      const Eigen::Matrix<Scalar, 3, 1>& tau_B) {
  // I_i ω̇_i = (I_j − I_k) ω_j ω_k + τ_i for (i, j, k) cyclic.
  Eigen::Matrix<Scalar, 3, 1> wdot;
  wdot(0) = ((I_B(1) - I_B(2)) * w_B(1) * w_B(2) + tau_B(0)) / I_B(0);
  wdot(1) = ((I_B(2) - I_B(0)) * w_B(2) * w_B(0) + tau_B(1)) / I_B(1);
  wdot(2) = ((I_B(0) - I_B(1)) * w_B(0) * w_B(1) + tau_B(2)) / I_B(2);
  return wdot;
}

template <typename Scalar>
Scalar rotational_energy(const Eigen::Vector3d& I_B, const Eigen::Matrix<Scalar, 3, 1>& w_B) {
  return 0.5 * (I_B(0) * w_B(0) * w_B(0) + I_B(1) * w_B(1) * w_B(1) + I_B(2) * w_B(2) * w_B(2));
}

template Eigen::Vector3d euler_rhs<double>(const Eigen::Vector3d&, const Eigen::Vector3d&,
                                           const Eigen::Vector3d&);
template Eigen::Matrix<AutoDiffXd, 3, 1> euler_rhs<AutoDiffXd>(
    const Eigen::Vector3d&, const Eigen::Matrix<AutoDiffXd, 3, 1>&,
    const Eigen::Matrix<AutoDiffXd, 3, 1>&);
template double rotational_energy<double>(const Eigen::Vector3d&, const Eigen::Vector3d&);
template AutoDiffXd rotational_energy<AutoDiffXd>(const Eigen::Vector3d&,
                                                  const Eigen::Matrix<AutoDiffXd, 3, 1>&);

}  // namespace rigid::body
