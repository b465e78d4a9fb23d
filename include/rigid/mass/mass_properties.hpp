#pragma once

#include <optional>
#include <span>
#include <string>

#include <Eigen/Core>
#include <fmt/format.h>

namespace rigid {

template <typename Scalar>
class SO3;
template <typename Scalar>
class SE3;

/// Principal moments and axes of an inertia tensor I_C_B (about the COM C, in frame B).
/// I_C_B = R_BP · diag(moments) · R_BPᵀ, with moments ascending and R_BP a proper rotation
/// whose columns are the principal axes expressed in B.
struct PrincipalAxes {
  Eigen::Vector3d moments;  ///< ascending principal moments (kg·m²)
  Eigen::Matrix3d R_BP;     ///< columns: principal axes in B; det = +1
};

/// Mass properties of a 3D rigid body expressed in a frame B with origin O:
/// mass m (kg), center of mass p_OC_B (m) and inertia tensor I_C_B about the COM (kg·m²).
///
/// The inertia tensor is the physical tensor I = ∫ρ (|r|² 1 − r rᵀ) dV: positive diagonal,
/// off-diagonal elements −∫ρ x y dV.
///
/// Class invariant (checked by the constructor, trusted afterwards): m is positive and
/// finite, p_OC_B and I_C_B are finite, I_C_B is symmetric, positive semidefinite and its
/// principal moments satisfy the triangle inequalities I₁ + I₂ ≥ I₃, each within
/// kRelativeTolerance · tr(I_C_B); the stored tensor is exactly symmetric. Semidefinite (not definite) because thin rods and point
/// masses are legitimate bodies with a zero moment.
class MassProperties {
 public:
  /// Relative tolerance of the validity checks: 1e-10 · tr(I). Round-off of the formulas
  /// and of combine/shift is a few ε·(m·|p|² + tr I); 1e-10 leaves room for bodies built
  /// from ~10⁴ parts or shifted ~10³ body lengths while still catching sign/order mistakes.
  static constexpr double kRelativeTolerance = 1e-10;

  /// Builds and validates mass properties.
  /// @param mass kg; @param p_OC_B COM position from O, in B (m);
  /// @param I_C_B inertia about the COM, in B (kg·m²).
  /// @throws rigid::Error naming the failed condition and its margin (see invalidity_report).
  MassProperties(double mass, const Eigen::Vector3d& p_OC_B, const Eigen::Matrix3d& I_C_B);

  /// Why (mass, p_OC_B, I_C_B) would not be physical, or nullopt when it is. The text names
  /// the first failed condition and by how much it fails, e.g. "principal moments (1, 2, 4)
  /// kg·m² violate I₁ + I₂ ≥ I₃ by 1 kg·m²".
  [[nodiscard]] static std::optional<std::string> check(double mass, const Eigen::Vector3d& p_OC_B,
                                                        const Eigen::Matrix3d& I_C_B);

  /// invalidity_report() of this (always nullopt after construction; kept for symmetry with
  /// data read from files, which goes through check()).
  [[nodiscard]] std::optional<std::string> invalidity_report() const {
    return check(mass_, p_OC_B_, I_C_B_);
  }

  [[nodiscard]] double mass() const { return mass_; }
  /// Center of mass p_OC_B (m).
  [[nodiscard]] const Eigen::Vector3d& com() const { return p_OC_B_; }
  /// Inertia about the COM, expressed in B (kg·m²).
  [[nodiscard]] const Eigen::Matrix3d& inertia_com() const { return I_C_B_; }

  /// Inertia about the point Q (p_OQ_B from the origin, m), expressed in B, by the
  /// parallel-axis theorem: I_Q = I_C + m (|d|² 1 − d dᵀ), d = p_QC = p_OC − p_OQ.
  /// @throws rigid::Error if p_OQ_B is not finite or I_Q overflows a double.
  [[nodiscard]] Eigen::Matrix3d inertia_about(const Eigen::Vector3d& p_OQ_B) const;

  /// Moment of inertia about the line through Q (p_OQ_B) along unit_B: uᵀ I_Q u (kg·m²).
  /// @throws rigid::Error if |unit_B| is not within 1e-12 of 1.
  [[nodiscard]] double inertia_about_axis(const Eigen::Vector3d& p_OQ_B,
                                          const Eigen::Vector3d& unit_B) const;

  /// The same body moved by d_B (m): the COM becomes p_OC_B + d_B, the inertia is unchanged.
  /// Equivalently, the same body described from the origin O' = O − d_B.
  /// @throws rigid::Error if d_B is not finite or the new COM overflows.
  [[nodiscard]] MassProperties shifted(const Eigen::Vector3d& d_B) const;

  /// The same body re-expressed in frame A (common origin): p_OC_A = R_AB p_OC_B,
  /// I_C_A = R_AB I_C_B R_ABᵀ. @throws rigid::Error if R_AB is not a rotation within 1e-9
  /// (or the result overflows).
  [[nodiscard]] MassProperties rotated(const Eigen::Matrix3d& R_AB) const;

  /// The same body expressed in frame A where the pose of B in A is (R_AB, p_AB_A):
  /// p_AC_A = R_AB p_OC_B + p_AB_A, I_C_A = R_AB I_C_B R_ABᵀ. @throws rigid::Error if R_AB is
  /// not a rotation, p_AB_A is not finite or the result overflows.
  [[nodiscard]] MassProperties transformed(const Eigen::Matrix3d& R_AB,
                                           const Eigen::Vector3d& p_AB_A) const;

  /// rotated(R_AB.matrix()) for a rotation from the lie module.
  [[nodiscard]] MassProperties rotated(const SO3<double>& R_AB) const;

  /// transformed(X_AB.rotation().matrix(), X_AB.translation()): the body expressed in A,
  /// where X_AB is the pose of B in A.
  [[nodiscard]] MassProperties transformed(const SE3<double>& X_AB) const;

  /// Principal moments (ascending) and a right-handed principal frame. Repeated moments
  /// (within kRelativeTolerance·tr I) get a deterministic frame: identity for a spherical
  /// body, and for an axisymmetric body the in-plane axes closest to B's own axes.
  [[nodiscard]] PrincipalAxes principal_axes() const;

 private:
  struct Unchecked {};
  MassProperties(Unchecked, double mass, const Eigen::Vector3d& p, const Eigen::Matrix3d& I)
      : mass_(mass), p_OC_B_(p), I_C_B_(0.5 * (I + I.transpose())) {}
  /// MassProperties(Unchecked, …) of a computed result, refused (rigid::Error naming
  /// `function`) when a sum or product of finite inputs overflowed.
  static MassProperties finite_result(const char* function, double mass, const Eigen::Vector3d& p,
                                      const Eigen::Matrix3d& I);
  friend MassProperties combine(std::span<const MassProperties> parts);

  double mass_;
  Eigen::Vector3d p_OC_B_;
  Eigen::Matrix3d I_C_B_;
};

/// Why `moments` (principal moments about the COM or a pivot, kg·m², any order) cannot be those
/// of a body that turns, or nullopt when they can: the checks of MassProperties::check on
/// diag(moments) (finite, non-negative, I_i ≤ I_j + I_k within kRelativeTolerance·ΣI), and
/// every moment above kRelativeTolerance·ΣI, since a zero moment (a point mass, a thin rod)
/// leaves the rotation about that axis undefined (ω = L/I). The one check of principal moments
/// that the dynamics (rigid::body, rigid::spring) accept.
[[nodiscard]] std::optional<std::string> check_rotational_moments(const Eigen::Vector3d& moments);

/// Mass properties of the union of bodies expressed in the same frame: masses add, the COM
/// is the mass-weighted mean, inertias are shifted to the new COM and added.
/// @throws rigid::Error if parts is empty or a sum overflows a double.
[[nodiscard]] MassProperties combine(std::span<const MassProperties> parts);
/// combine of two bodies.
[[nodiscard]] MassProperties combine(const MassProperties& a, const MassProperties& b);

/// The body `whole` with the part `hole` removed (both in the same frame): m = m_w − m_h,
/// m c = m_w c_w − m_h c_h, I_O = I_O,w − I_O,h about the common origin, then back to the COM.
/// @throws rigid::Error if the remaining mass is not positive or the remaining inertia is
/// not physical (the message says which condition fails and by how much).
[[nodiscard]] MassProperties subtract(const MassProperties& whole, const MassProperties& hole);

}  // namespace rigid

/// "MassProperties{mass: 2 kg, com: [0, 0, 0.1] m, inertia_com: [a, b, c; ...] kg·m²}"
/// with shortest round-trip doubles.
template <>
struct fmt::formatter<rigid::MassProperties> : fmt::formatter<std::string_view> {
  auto format(const rigid::MassProperties& mp, fmt::format_context& ctx) const
      -> decltype(ctx.out());
};
