#pragma once

// Group properties shared by the Lie-group tests: each takes a group G (SO3d, SE3d, …) with
// exp, log, inverse, operator*, adjoint, matrix and Jacobians, and checks identities that hold
// exactly in exact arithmetic.

#include <random>

#include <Eigen/Core>

namespace rigid::test {

/// Random tangent vector whose rotation part has angle below `max_angle` and translation
/// part (if any) in [−1, 1].
template <typename Tangent>
Tangent random_tangent(std::mt19937_64& rng, double max_angle) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Tangent xi;
  for (Eigen::Index i = 0; i < xi.size(); ++i) xi(i) = u(rng);
  auto omega = xi.template tail<3>();
  // Uniform direction, angle uniform in [0, max_angle).
  const double n = omega.norm();
  if (n > 1e-3) omega *= (max_angle * 0.5 * (u(rng) + 1.0)) / n;
  return xi;
}

/// max |A − B| over the entries of the homogeneous matrices.
template <typename G>
double matrix_distance(const G& a, const G& b) {
  return (a.matrix() - b.matrix()).cwiseAbs().maxCoeff();
}

}  // namespace rigid::test
