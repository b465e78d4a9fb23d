#include "rigid/spring/network.hpp"

#include <cmath>

#include <Eigen/Dense>

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"

namespace rigid::spring {

Network network_with_inertia(double mass, const Eigen::Vector3d& I_B, double stiffness) {
  RIGID_REQUIRE(std::isfinite(mass) && mass > 0, "mass must be finite and > 0 kg, got {}", mass);
  RIGID_REQUIRE(std::isfinite(stiffness) && stiffness > 0, "stiffness must be finite and > 0 N/m, got {}",
                stiffness);
  // Second moments J_i = Σ m x_i² from I1 = J2 + J3 (cyclic): J_i = (I_j + I_k − I_i)/2,
  // and 2·(m/6)·a_i² = J_i.
  Eigen::Vector3d a;
  for (int i = 0; i < 3; ++i) {
    const double J = 0.5 * (I_B((i + 1) % 3) + I_B((i + 2) % 3) - I_B(i));
    RIGID_REQUIRE(J > 0, "principal moments {} need I{} < I{} + I{} strictly for a six-particle network",
                  rigid::to_string(I_B.transpose()), i + 1, (i + 1) % 3 + 1, (i + 2) % 3 + 1);
    a(i) = std::sqrt(3.0 * J / mass);
  }
  Network net;
  net.mass = Eigen::VectorXd::Constant(6, mass / 6.0);
  net.position = Eigen::Matrix3Xd::Zero(3, 6);
  for (int i = 0; i < 3; ++i) {
    net.position(i, 2 * i) = a(i);
    net.position(i, 2 * i + 1) = -a(i);
  }
  net.velocity = Eigen::Matrix3Xd::Zero(3, 6);
  for (int i = 0; i < 6; ++i)
    for (int j = i + 1; j < 6; ++j)
      net.springs.push_back({i, j, stiffness, (net.position.col(i) - net.position.col(j)).norm()});
  return net;
}

namespace {

Eigen::VectorXd forces_flat(const Network& net, const Eigen::Matrix3Xd& p) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(p.size());
  for (const Spring& s : net.springs) {
    const Eigen::Vector3d d = p.col(s.j) - p.col(s.i);
    const double len = d.norm();
    const Eigen::Vector3d fi = s.stiffness * (len - s.rest_length) / len * d;
    f.segment<3>(3 * s.i) += fi;
    f.segment<3>(3 * s.j) -= fi;
  }
  return f;
}

// ∂f/∂p (symmetric 3N×3N).
Eigen::MatrixXd stiffness_matrix(const Network& net, const Eigen::Matrix3Xd& p) {
  const Eigen::Index n = p.size();
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  for (const Spring& s : net.springs) {
    const Eigen::Vector3d d = p.col(s.j) - p.col(s.i);
    const double len = d.norm();
    const Eigen::Vector3d u = d / len;
    // ∂(force on i)/∂p_j = k [u uᵀ + (1 − L0/len)(1 − u uᵀ)]
    const Eigen::Matrix3d B = s.stiffness * (u * u.transpose() +
                                             (1.0 - s.rest_length / len) * (Eigen::Matrix3d::Identity() - u * u.transpose()));
    K.block<3, 3>(3 * s.i, 3 * s.j) += B;
    K.block<3, 3>(3 * s.j, 3 * s.i) += B;
    K.block<3, 3>(3 * s.i, 3 * s.i) -= B;
    K.block<3, 3>(3 * s.j, 3 * s.j) -= B;
  }
  return K;
}

}  // namespace

Eigen::Matrix3Xd spring_forces(const Network& net) {
  const Eigen::VectorXd f = forces_flat(net, net.position);
  return Eigen::Map<const Eigen::Matrix3Xd>(f.data(), 3, net.position.cols());
}

void step_implicit_midpoint(Network& net, double h) {
  // Unknown: midpoint positions P = p0 + ½h v̄, v̄ = v0 + ½h M⁻¹ f(P):
  // G(P) = P − p0 − ½h v0 − ¼h² M⁻¹ f(P) = 0.
  const Eigen::Index n = net.position.size();
  const Eigen::Map<const Eigen::VectorXd> p0(net.position.data(), n);
  const Eigen::Map<const Eigen::VectorXd> v0(net.velocity.data(), n);
  Eigen::VectorXd minv(n);
  for (Eigen::Index i = 0; i < n; ++i) minv(i) = 1.0 / net.mass(i / 3);
  Eigen::VectorXd P = p0 + 0.5 * h * v0;
  const double scale = p0.lpNorm<Eigen::Infinity>() + 1.0;
  for (int it = 0; it < 50; ++it) {
    const Eigen::Matrix3Xd Pm = Eigen::Map<const Eigen::Matrix3Xd>(P.data(), 3, n / 3);
    const Eigen::VectorXd G = P - p0 - 0.5 * h * v0 - 0.25 * h * h * minv.cwiseProduct(forces_flat(net, Pm));
    const Eigen::MatrixXd J =
        Eigen::MatrixXd::Identity(n, n) - 0.25 * h * h * minv.asDiagonal() * stiffness_matrix(net, Pm);
    const Eigen::VectorXd dP = J.partialPivLu().solve(G);
    P -= dP;
    if (dP.lpNorm<Eigen::Infinity>() <= 1e-15 * scale) break;
  }
  const Eigen::Matrix3Xd Pm = Eigen::Map<const Eigen::Matrix3Xd>(P.data(), 3, n / 3);
  const Eigen::VectorXd vbar = v0 + 0.5 * h * minv.cwiseProduct(forces_flat(net, Pm));
  const Eigen::VectorXd p1 = p0 + h * vbar;
  const Eigen::VectorXd v1 = 2.0 * vbar - v0;
  Eigen::Map<Eigen::VectorXd>(net.position.data(), n) = p1;
  Eigen::Map<Eigen::VectorXd>(net.velocity.data(), n) = v1;
}

double network_energy(const Network& net) {
  double E = 0;
  for (Eigen::Index i = 0; i < net.position.cols(); ++i) E += 0.5 * net.mass(i) * net.velocity.col(i).squaredNorm();
  for (const Spring& s : net.springs) {
    const double e = (net.position.col(s.j) - net.position.col(s.i)).norm() - s.rest_length;
    E += 0.5 * s.stiffness * e * e;
  }
  return E;
}

}  // namespace rigid::spring
