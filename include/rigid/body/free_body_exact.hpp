#pragma once

/// Exact solution of the torque-free Euler equations (the free rigid body), body
/// angular velocity ω_B(t) in Jacobi elliptic functions [Landau1976, §37].
///
/// Cases: asymmetric body on either side of the separatrix (L² > 2E·I2: the dn
/// component is ω3; L² < 2E·I2: it is ω1), the separatrix itself (modulus 1,
/// sn → tanh), the symmetric top (uniform precession of the transverse part) and
/// the sphere (constant ω). Principal moments may be given in any order; they are
/// sorted internally with a proper (det = +1) relabelling of the axes.
///
/// `FreeBodyMotion` adds the orientation R_WB(t) in closed form [Landau1976, §37;
/// Celledoni2008]: R_WB(t) = M · R_e3(ψ(t)) · Q(L_B(t))ᵀ, where Q(L_B) is a rotation
/// built from the body angular momentum that takes e3 to L_B/|L|, M is constant and
/// ψ(t) is a linear term plus an elliptic integral of the third kind.

#include <array>

#include <Eigen/Core>

#include "rigid/body/free_body_integrators.hpp"
#include "rigid/body/jacobi_elliptic.hpp"
#include "rigid/lie/so3.hpp"
#include "rigid/mass/mass_properties.hpp"

namespace rigid::body {

/// Which closed form `FreeBodyExact` uses.
enum class FreeBodyCase { kSphere, kSymmetric, kAsymmetric };

class FreeBodyExact {
 public:
  /// `I_B`: principal moments about the COM (kg·m², any order); `w0_B`: body angular velocity
  /// at t = 0 (rad/s).
  /// @throws rigid::Error if I_B fails rigid::check_rotational_moments, w0_B is not finite, or
  /// the kinetic energy or |L| overflows.
  FreeBodyExact(const Eigen::Vector3d& I_B, const Eigen::Vector3d& w0_B);

  /// Body angular velocity at time t (s), any sign of t.
  /// @throws rigid::Error if t is not finite or the phase of the motion at t exceeds kMaxAngle
  /// (rad; there rounding has lost the fraction of a period): |t| ≤ max_time().
  [[nodiscard]] Eigen::Vector3d omega_body(double t) const;
  /// The largest |t| (s) that omega_body accepts: kMaxAngle over the rate of the phase
  /// (infinite when ω is constant).
  [[nodiscard]] double max_time() const;

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
  friend class FreeBodyMotion;
  /// Jacobi functions at u reduced to u_r ∈ [−K, K], u = u_r + 2K·half_periods
  /// (sn, cn at u are (−1)^half_periods times those at u_r; dn is 2K-periodic).
  /// With a `shift`, also theta_arg = arg Θ(u_r + iβ) (JacobiElliptic::eval).
  struct Phase {
    double sn = 0, cn = 1, dn = 1, u_r = 0;
    double half_periods = 0;
    double theta_arg = 0;
  };
  [[nodiscard]] Phase phase(double u, const JacobiElliptic::ThetaShift* shift = nullptr) const;
  [[nodiscard]] Eigen::Vector3d omega_sorted_at(const Phase& ph) const;

  FreeBodyCase case_ = FreeBodyCase::kSphere;
  bool steady_ = false;               // ω ∥ L (a permanent rotation): ω constant
  std::array<int, 3> perm_{0, 1, 2};  // sorted axis s ↔ user axis perm_[s]
  double flip_ = 1.0;                 // −1 when the relabelling is improper (ω → −ω)
  Eigen::Vector3d I_sorted_ = Eigen::Vector3d::Ones();
  Eigen::Vector3d w0_sorted_ = Eigen::Vector3d::Zero();
  // Asymmetric: ω_c = a_c cn u, ω_2 = s a_2 sn u, ω_d = s a_d dn u, u = λ t + u0.
  int axis_cn_ = 0, axis_dn_ = 2;
  double a_cn_ = 0, a_sn_ = 0, a_dn_ = 0, sign_ = 1, lambda_ = 0, u0_ = 0, k_ = 0;
  double k2_ = 0, kc2_ = 1;  // k² and k'² = 1 − k², each without cancellation
  double K_ = 0;    // K(k); 0 on the separatrix (no reduction there)
  double sep_sign_ = 1;  // separatrix only: −1 when ω_c(0) < 0 (ω_c, ω2 → −ω_c, −ω2)
  JacobiElliptic jacobi_;
  // Symmetric: rotation of the transverse plane at rate Omega_ about axis sym_axis_.
  int sym_axis_ = 2;
  double Omega_ = 0;
  double energy_ = 0, L_norm_ = 0;
  double phase_rate_ = 0;  // rad/s of the phase of ω(t): λ (asymmetric), |Ω| (symmetric), else 0

  [[nodiscard]] Eigen::Vector3d omega_sorted(double t) const;
  /// rigid::Error "<function>(): time t = … s …" unless t is finite and |phase_rate_ t| ≤
  /// kMaxAngle.
  void require_time(const char* function, double t) const;
};

/// Exact motion of the torque-free rigid body: orientation R_WB(t) and body angular
/// velocity ω_B(t) in closed form, for every case of `FreeBodyExact`.
///
/// Construction [Landau1976, §37, eqs. 37.13–37.16; Celledoni2008, §2]: with L_W the
/// constant world angular momentum and l_B(t) = I ω_B(t)/|L|, choose a body-fixed
/// right-handed frame (a, b, d) whose d axis is the dn axis of the elliptic solution
/// (the symmetry axis of a symmetric top) and let Q(t) be the rotation with columns
///   ( l_b/s, −l_a/s, 0 ),  ( l_a l_d/s, l_b l_d/s, −s ),  l,    s = √(l_a² + l_b²)
/// (Q = R_z(−ψ_L) R_x(−θ) of Landau's Euler angles). Then
///   R_WB(t) = M · R_e3(ψ(t)) · Q(t)ᵀ,   M = R_WB(0) Q(0) (so M e3 = L_W/|L|),
///   ψ̇ = |L| (2E − L_d²/I_d) / (|L|² − L_d²)
///   ψ(t) = |L| t / I_d + |L| (I_d − I_c)/(I_c I_d λ) · [Π(n; am u, k) − Π(n; am u0, k)],
///   n = −I_d (I_2 − I_c) / (I_c (I_d − I_2)) < 0,  u = λ t + u0,
/// Π(n; φ, k) = ∫₀^φ dθ / ((1 − n sin²θ) √(1 − k² sin²θ)) (Boost.Math `ellint_3(k, n, φ)`).
/// Symmetric top: ψ̇ = |L|/I_t (transverse moment I_t); sphere and permanent rotations
/// (ω ∥ L): R_WB(t) = R_WB(0) exp(t ω̂).
///
/// Long times: u is reduced to [−K, K] and ψ gains 2Π(n, k) per half period, so the
/// error grows only with the rounding of λ t (relative ε). Near the separatrix
/// (k' = √(1 − k²) → 0) k' is computed without cancellation (from L² − 2E I_2), but
/// the motion itself is ill-conditioned there: relative input errors δ are amplified
/// to ≈ δ·t·λ / k'² in ω. On the separatrix itself (k = 1) the closed form uses
/// sn = tanh, cn = dn = sech and Π(n; am u, 1) = (u + √−n · atan(√−n · tanh u)) / (1 − n).
///
/// Class invariant: built from finite, physical inputs (checked by the constructor).
class FreeBodyMotion {
 public:
  /// `I_B`: principal moments (kg·m², any order; B is a principal frame);
  /// `R0_WB`: initial orientation; `w0_B`: initial body angular velocity (rad/s).
  /// @throws rigid::Error as FreeBodyExact's constructor.
  FreeBodyMotion(const Eigen::Vector3d& I_B, const SO3d& R0_WB, const Eigen::Vector3d& w0_B);

  /// The motion of a body with mass properties `mass_B` in any body frame B (its inertia about
  /// the COM need not be diagonal): the closed form runs in the principal frame of
  /// MassProperties::principal_axes, and orientation()/omega_body() are those of B.
  /// @throws rigid::Error as above, for the principal moments of mass_B.
  FreeBodyMotion(const MassProperties& mass_B, const SO3d& R0_WB, const Eigen::Vector3d& w0_B);

  /// Orientation R_WB(t) (body to world) at time t (s), any sign of t.
  /// @throws rigid::Error if t is not finite or an angle of the motion at t (the phase of ω,
  /// the precession ψ, the turn t|ω| of a uniform rotation) exceeds kMaxAngle (rad).
  [[nodiscard]] SO3d orientation(double t) const;
  /// Body angular velocity ω_B(t) (rad/s). @throws rigid::Error as FreeBodyExact::omega_body.
  [[nodiscard]] Eigen::Vector3d omega_body(double t) const {
    return R_BP_is_identity() ? omega_.omega_body(t) : Eigen::Vector3d(R_BP_ * omega_.omega_body(t));
  }
  /// (R_WB(t), ω_B(t)). @throws rigid::Error as orientation.
  [[nodiscard]] FreeBodyState state(double t) const;
  /// Constant world angular momentum L_W = R_WB I ω_B (kg·m²/s).
  [[nodiscard]] const Eigen::Vector3d& angular_momentum_world() const { return L_W_; }
  /// The ω(t) solution in the principal frame (case, modulus, period, energy).
  [[nodiscard]] const FreeBodyExact& omega_solution() const { return omega_; }

 private:
  FreeBodyMotion(const Eigen::Vector3d& I_P, const SO3d& R0_WP, const Eigen::Vector3d& w0_P,
                 const SO3d& R_BP);

  SO3d R_BP_ = SO3d::identity();  // principal axes of the MassProperties form (else identity)
  [[nodiscard]] bool R_BP_is_identity() const { return R_BP_.w() == 1.0; }
  FreeBodyExact omega_;
  SO3d q_SB_ = SO3d::identity();  // proper relabelling: sorted axes from the (principal) body axes
  SO3d q0_WB_ = SO3d::identity();
  Eigen::Vector3d L_W_;
  bool uniform_ = false;     // ω constant (sphere, permanent rotation)
  std::array<int, 3> abd_{0, 1, 2};  // sorted-axis indices of the (a, b, d) frame
  SO3d q_M_ = SO3d::identity();      // M of the construction, world from the "L frame"
  SO3d q_PS_SB_ = SO3d::identity();  // Pᵀ R_SB: user body axes to the (a, b, d) axes as x, y, z
  double psi_rate_ = 0;      // |L|/I_d (asymmetric) or |L|/I_t (symmetric), rad/s
  double pi_coef_ = 0;       // |L| (I_d − I_c)/(I_c I_d λ)
  double n_ = 0;             // characteristic of Π
  double Pi_complete_ = 0;   // Π(n, k) (0 on the separatrix)
  double Pi_u0_ = 0;         // Π(n; am u0, k)
  // Theta form Π(n; am u_r, k) = u_r Π(n, k)/K + c · arg Θ(u_r + iβ), k² sn²(iβ) = n.
  JacobiElliptic::ThetaShift theta_shift_;
  double Pi_slope_ = 0;      // Π(n, k)/K
  double theta_coef_ = 0;    // c = sn cn / dn (β, k') = √(m / ((k² + m)(1 + m))), m = −n
  double Pi_u0_carlson_ = 0; // Π(n; am u0, k) by the Carlson reference path
  double inv_L_ = 0;         // 1/|L| (0 at rest)

  friend struct FreeBodyMotionPeer;  // tests and the benchmark reach the Carlson reference
  [[nodiscard]] double elliptic_pi(const FreeBodyExact::Phase& ph) const;
  [[nodiscard]] double elliptic_pi_carlson(const FreeBodyExact::Phase& ph) const;
  [[nodiscard]] SO3d orientation_impl(double t, bool carlson) const;
  [[nodiscard]] SO3d q_Q(const Eigen::Vector3d& w_S) const;
};

}  // namespace rigid::body
