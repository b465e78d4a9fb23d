#pragma once

/// The stiff body: point masses joined by linear springs, the physical model of a rigid
/// body as the stiffness k → ∞. Positions p_i (m) and velocities v_i (m/s) in world W.

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rigid/integrate/march.hpp"
#include "rigid/mass/mass_properties.hpp"

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

/// Six particles of mass m/6 at C ± a_i e_i along the principal axes e_i of `mass_B` (in its
/// body frame B, which is taken as the world frame at t = 0), whose mass, COM C and inertia
/// about the COM are those of `mass_B`, joined by all 15 springs of stiffness k at their rest
/// lengths. From J_i = Σ m x_i² = (I_j + I_k − I_i)/2 = 2 (m/6) a_i².
/// @throws rigid::Error if the stiffness is not positive and finite, or a principal moment
/// reaches the sum of the other two (a_i = 0: six particles cannot span a flat body; it needs
/// I_i < I_j + I_k strictly).
[[nodiscard]] Network network_with_inertia(const MassProperties& mass_B, double stiffness);

/// Spring forces on every particle (N).
[[nodiscard]] Eigen::Matrix3Xd spring_forces(const Network& net);

/// Iterations and tolerance of the Newton solve of one implicit-midpoint step.
struct MidpointOptions {
  int max_iterations = 50;
  /// Converged when the last correction is at most this times (1 + max |p|) (m).
  double tolerance = 1e-15;
};

/// One implicit-midpoint step (Newton on the 3N stage positions with the exact stiffness
/// matrix): A-stable, so h is not limited by √(m/k); keeps the linear and angular momentum of
/// the network exactly (they are linear/quadratic invariants) up to the Newton tolerance.
/// @throws rigid::Error if Newton does not converge (the message gives h, the last correction,
/// the tolerance and the residual of the implicit equation at the last iterate) or the
/// iteration turns non-finite; the network is left unchanged. simulate_network's march puts
/// the step number and t in front.
void step_implicit_midpoint(Network& net, double h, const MidpointOptions& options = {});

/// Total energy (J): kinetic + spring potential.
[[nodiscard]] double network_energy(const Network& net);

/// The first non-finite position or velocity component ("particle 3 position.y").
[[nodiscard]] std::optional<integrate::NonFinite> find_nonfinite(const Network& net,
                                                                 std::string_view owner = {});

/// Sampled positions, velocities and energies of a network.
struct NetworkTrajectory {
  std::vector<double> t;                  ///< s
  std::vector<Eigen::Matrix3Xd> position; ///< m
  std::vector<Eigen::Matrix3Xd> velocity; ///< m/s
  std::vector<double> energy;             ///< J
};

/// Integrates from t = 0 to every entry of `output_times` by implicit-midpoint steps through
/// rigid::integrate::march (the fewest equal steps ≤ h_max between outputs, every step checked
/// for a non-finite state).
/// @throws rigid::Error for a malformed network (masses not positive, spring indices out of
/// range, non-finite state), bad output times or step, a Newton solve that does not converge;
/// rigid::Cancelled from `control`.
[[nodiscard]] NetworkTrajectory simulate_network(const Network& initial, double h_max,
                                                 const std::vector<double>& output_times,
                                                 const integrate::MarchControl& control = {},
                                                 const MidpointOptions& options = {});

}  // namespace rigid::spring
