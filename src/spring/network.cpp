#include "rigid/spring/network.hpp"

#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"
#include <fmt/format.h>

namespace rigid::spring {

Network network_with_inertia(const MassProperties& mass_B, double stiffness) {
  RIGID_REQUIRE(std::isfinite(stiffness) && stiffness > 0, "stiffness must be finite and > 0 N/m, got {}",
                stiffness);
  const double mass = mass_B.mass();
  // principal axes from rigid::MassProperties; B's own when the inertia is already diagonal
  const Eigen::Matrix3d& I_C = mass_B.inertia_com();
  const bool diagonal = I_C(0, 1) == 0 && I_C(0, 2) == 0 && I_C(1, 2) == 0;
  const PrincipalAxes pa = diagonal ? PrincipalAxes{I_C.diagonal(), Eigen::Matrix3d::Identity()}
                                    : mass_B.principal_axes();
  const Eigen::Vector3d& I = pa.moments;
  // Second moments J_i = Σ m x_i² from I1 = J2 + J3 (cyclic): J_i = (I_j + I_k − I_i)/2,
  // and 2·(m/6)·a_i² = J_i.
  Eigen::Vector3d a;
  for (int i = 0; i < 3; ++i) {
    const double J = 0.5 * (I((i + 1) % 3) + I((i + 2) % 3) - I(i));
    RIGID_REQUIRE(J > MassProperties::kRelativeTolerance * I.sum(),
                  "principal moments {} kg·m² need I{} < I{} + I{} strictly for a six-particle "
                  "network (a flat body has no extent along one axis)",
                  rigid::to_string(I.transpose()), i + 1, (i + 1) % 3 + 1, (i + 2) % 3 + 1);
    a(i) = std::sqrt(3.0 * J / mass);
  }
  Network net;
  net.mass = Eigen::VectorXd::Constant(6, mass / 6.0);
  net.position = Eigen::Matrix3Xd::Zero(3, 6);
  for (int i = 0; i < 3; ++i) {
    net.position.col(2 * i) = mass_B.com() + a(i) * pa.R_BP.col(i);
    net.position.col(2 * i + 1) = mass_B.com() - a(i) * pa.R_BP.col(i);
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

void step_implicit_midpoint(Network& net, double h, const MidpointOptions& options) {
  // Unknown: midpoint positions P = p0 + ½h v̄, v̄ = v0 + ½h M⁻¹ f(P):
  // G(P) = P − p0 − ½h v0 − ¼h² M⁻¹ f(P) = 0, solved by Newton with the exact ∂f/∂p.
  const Eigen::Index n = net.position.size();
  const Eigen::Map<const Eigen::VectorXd> p0(net.position.data(), n);
  const Eigen::Map<const Eigen::VectorXd> v0(net.velocity.data(), n);
  Eigen::VectorXd minv(n);
  for (Eigen::Index i = 0; i < n; ++i) minv(i) = 1.0 / net.mass(i / 3);
  Eigen::VectorXd P = p0 + 0.5 * h * v0;
  const double scale = p0.lpNorm<Eigen::Infinity>() + 1.0;
  double last = std::numeric_limits<double>::infinity();
  bool converged = false;
  for (int it = 0; it < options.max_iterations; ++it) {
    const Eigen::Matrix3Xd Pm = Eigen::Map<const Eigen::Matrix3Xd>(P.data(), 3, n / 3);
    const Eigen::VectorXd G = P - p0 - 0.5 * h * v0 - 0.25 * h * h * minv.cwiseProduct(forces_flat(net, Pm));
    const Eigen::MatrixXd J =
        Eigen::MatrixXd::Identity(n, n) - 0.25 * h * h * minv.asDiagonal() * stiffness_matrix(net, Pm);
    const Eigen::VectorXd dP = J.partialPivLu().solve(G);
    P -= dP;
    last = dP.lpNorm<Eigen::Infinity>();
    if (!std::isfinite(last)) break;
    if (last <= options.tolerance * scale) {
      converged = true;
      break;
    }
  }
  if (!converged) [[unlikely]] {
    // how far from a solution the last iterate is: the residual of G(P) = 0
    const Eigen::Matrix3Xd Pm = Eigen::Map<const Eigen::Matrix3Xd>(P.data(), 3, n / 3);
    const double residual =
        (P - p0 - 0.5 * h * v0 - 0.25 * h * h * minv.cwiseProduct(forces_flat(net, Pm)))
            .lpNorm<Eigen::Infinity>();
    RIGID_THROW(
        "the Newton iteration of the implicit midpoint did not converge in {} iterations at "
        "h = {} s: last correction {} m, tolerance {} m; residual of the implicit equation "
        "|P − p0 − ½h v0 − ¼h² M⁻¹ f(P)| = {:.3g} m at the last iterate; use a smaller step",
        options.max_iterations, h, last, options.tolerance * scale, residual);
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

std::optional<integrate::NonFinite> find_nonfinite(const Network& net, std::string_view owner) {
  for (const auto* m : {&net.position, &net.velocity}) {
    if (auto i = integrate::first_nonfinite({m->data(), static_cast<std::size_t>(m->size())})) [[unlikely]] {
      const char axis = "xyz"[*i % 3];
      return integrate::NonFinite{std::string(owner),
                                  fmt::format("particle {} {}.{}", *i / 3,
                                              m == &net.position ? "position" : "velocity", axis),
                                  m->data()[*i]};
    }
  }
  return std::nullopt;
}

NetworkTrajectory simulate_network(const Network& initial, double h_max,
                                   const std::vector<double>& output_times,
                                   const integrate::MarchControl& control, const MidpointOptions& options) {
  const Eigen::Index np = initial.position.cols();
  RIGID_REQUIRE(np > 0 && initial.mass.size() == np && initial.velocity.cols() == np,
                "a network needs one mass, position and velocity per particle; got {} masses, {} "
                "positions and {} velocities",
                initial.mass.size(), np, initial.velocity.cols());
  for (Eigen::Index i = 0; i < np; ++i) {
    RIGID_REQUIRE(std::isfinite(initial.mass(i)) && initial.mass(i) > 0,
                  "particle {} has mass {} kg; expected positive and finite", i, initial.mass(i));
  }
  for (std::size_t k = 0; k < initial.springs.size(); ++k) {
    const Spring& sp = initial.springs[k];
    RIGID_REQUIRE(sp.i >= 0 && sp.j >= 0 && sp.i < np && sp.j < np && sp.i != sp.j,
                  "spring {} joins particles {} and {}; expected two different particles of 0 … {}", k,
                  sp.i, sp.j, np - 1);
    RIGID_REQUIRE(std::isfinite(sp.stiffness) && sp.stiffness > 0 && std::isfinite(sp.rest_length) &&
                      sp.rest_length >= 0,
                  "spring {} has stiffness {} N/m and rest length {} m; expected a positive stiffness "
                  "and a non-negative rest length",
                  k, sp.stiffness, sp.rest_length);
  }
  if (auto bad = find_nonfinite(initial)) {
    RIGID_THROW("the initial state is not finite: {} = {}", bad->component, bad->value);
  }
  Network net = initial;
  NetworkTrajectory traj;
  (void)integrate::march(
      integrate::TimeGrid::from_times(0.0, output_times), h_max,
      [&](double, double h) { step_implicit_midpoint(net, h, options); }, [&] { return find_nonfinite(net); },
      [&](std::size_t, double t) {
        traj.t.push_back(t);
        traj.position.push_back(net.position);
        traj.velocity.push_back(net.velocity);
        traj.energy.push_back(network_energy(net));
      },
      control);
  return traj;
}

}  // namespace rigid::spring
