#pragma once

/// Exact solution of the torque-free Euler equations (the free rigid body), body
/// angular velocity ω_B(t) in Jacobi elliptic functions [Landau1976, §37].
///
/// Cases: asymmetric body on either side of the separatrix (L² > 2E·I2: the dn
/// component is ω3; L² < 2E·I2: it is ω1), the separatrix itself (modulus 1,
/// sn → tanh), the symmetric top (uniform precession of the transverse part) and
/// the sphere (constant ω). Principal moments may be given in any order; they are
/// sorted internally with a proper (det = +1) relabelling of the axes.

#include <array>

#include <Eigen/Core>

namespace rigid::body {

/// Which closed form `FreeBodyExact` uses.
enum class FreeBodyCase { kSphere, kSymmetric, kAsymmetric };

class FreeBodyExact {
 public:
  /// `I_B`: principal moments about the COM (kg·m², all > 0, triangle inequality
  /// I_i ≤ I_j + I_k); `w0_B`: body angular velocity at t = 0 (rad/s).
  FreeBodyExact(const Eigen::Vector3d& I_B, const Eigen::Vector3d& w0_B);

  /// Body angular velocity at time t (s), any sign of t.
  [[nodiscard]] Eigen::Vector3d omega_body(double t) const;

  [[nodiscard]] FreeBodyCase solution_case() const { return case_; }
  /// Elliptic modulus k (0 for symmetric/sphere, 1 on the separatrix).
  [[nodiscard]] double modulus() const { return k_; }
  /// Period of ω_B(t) (s): 4K(k)/λ for the asymmetric body (infinite on the
  /// separatrix), 2π/|Ω| for the symmetric top, infinite for the sphere or rest.
  [[nodiscard]] double period() const;
  /// Kinetic energy (J) and |L| (kg·m²/s), constants of the motion.
  [[nodiscard]] double energy() const { return energy_; }
  [[nodiscard]] double angular_momentum_norm() const { return L_norm_; }

 private:
  FreeBodyCase case_ = FreeBodyCase::kSphere;
  std::array<int, 3> perm_{0, 1, 2};  // sorted axis s ↔ user axis perm_[s]
  double flip_ = 1.0;                 // −1 when the relabelling is improper (ω → −ω)
  Eigen::Vector3d I_sorted_ = Eigen::Vector3d::Ones();
  Eigen::Vector3d w0_sorted_ = Eigen::Vector3d::Zero();
  // Asymmetric: ω_c = a_c cn u, ω_2 = s a_2 sn u, ω_d = s a_d dn u, u = λ t + u0.
  int axis_cn_ = 0, axis_dn_ = 2;
  double a_cn_ = 0, a_sn_ = 0, a_dn_ = 0, sign_ = 1, lambda_ = 0, u0_ = 0, k_ = 0;
  // Symmetric: rotation of the transverse plane at rate Omega_ about axis sym_axis_.
  int sym_axis_ = 2;
  double Omega_ = 0;
  double energy_ = 0, L_norm_ = 0;

  [[nodiscard]] Eigen::Vector3d omega_sorted(double t) const;
};

}  // namespace rigid::body
