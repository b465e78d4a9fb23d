#pragma once

/// The stiff body: point masses joined by linear springs, the physical model of a rigid
/// body as the stiffness k → ∞. Positions p_i (m) and velocities v_i (m/s) in world W.

#include <vector>

#include <Eigen/Core>

namespace rigid::spring {

struct Spring {
  int i = 0, j = 0;
  double stiffness = 0;     ///< N/m
  double rest_length = 0;   ///< m
};

struct Network {
  Eigen::VectorXd mass;        ///< kg, one per particle
  Eigen::Matrix3Xd position;   ///< m, columns are particles
  Eigen::Matrix3Xd velocity;   ///< m/s
  std::vector<Spring> springs;
};

/// Six particles of mass m/6 at ±a_i e_i (COM at the origin) whose inertia about the COM is
/// diag(I_B), joined by all 15 springs of stiffness k at their rest lengths. Requires the
/// triangle inequality I_i < I_j + I_k strictly (each a_i > 0).
[[nodiscard]] Network network_with_inertia(double mass, const Eigen::Vector3d& I_B, double stiffness);

/// Spring forces on every particle (N).
[[nodiscard]] Eigen::Matrix3Xd spring_forces(const Network& net);

/// One implicit-midpoint step (Newton on the 3N stage positions): A-stable, so h is not
/// limited by √(m/k); keeps the linear and angular momentum of the network exactly
/// (they are linear/quadratic invariants) up to the Newton tolerance.
void step_implicit_midpoint(Network& net, double h);

/// Total energy (J): kinetic + spring potential.
[[nodiscard]] double network_energy(const Network& net);

}  // namespace rigid::spring
