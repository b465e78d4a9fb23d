#include "rigid/mass/mass_properties.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"
#include "rigid/lie/se3.hpp"
#include "rigid/lie/so3.hpp"

namespace rigid {
namespace {

// Tolerance of every validity check: a fraction of the trace (the sum of the principal
// moments, which bounds each of them). A zero tensor (point mass) gets a zero tolerance.
double validity_tolerance(const Eigen::Matrix3d& I) {
  return MassProperties::kRelativeTolerance * std::abs(I.trace());
}

Eigen::Matrix3d parallel_axis_term(double mass, const Eigen::Vector3d& d) {
  // m (|d|² 1 − d dᵀ): the inertia of a point mass m at offset d.
  return mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
}

void require_rotation(const Eigen::Matrix3d& R, const char* function) {
  const double orthogonality = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  const double det = R.determinant();
  if (!(orthogonality <= 1e-9) || !(std::abs(det - 1.0) <= 1e-9)) {
    detail::throw_error(function,
                        fmt::format("R_AB must be a rotation matrix (|RᵀR − 1| ≤ 1e-9, det = +1), "
                                    "got |RᵀR − 1| = {} and det = {}",
                                    orthogonality, det));
  }
}

// Column j flipped so that its entry of largest magnitude is positive: a sign convention
// that makes eigenvectors reproducible.
Eigen::Vector3d canonical_sign(const Eigen::Vector3d& v) {
  Eigen::Index k = 0;
  v.cwiseAbs().maxCoeff(&k);
  return v(k) < 0 ? Eigen::Vector3d(-v) : v;
}

// The unit vector in the plane ⊥ n (unit) that is closest to one of the frame's own axes:
// the axis least aligned with n, projected onto the plane.
Eigen::Vector3d in_plane_axis(const Eigen::Vector3d& n) {
  Eigen::Index k = 0;
  n.cwiseAbs().minCoeff(&k);
  const Eigen::Vector3d e = Eigen::Vector3d::Unit(k);
  return (e - n.dot(e) * n).normalized();
}

// ½ (I + Iᵀ) as ½ I + ½ Iᵀ: the same value (halving is exact), without the overflow of I + Iᵀ
// for entries above half the largest double.
Eigen::Matrix3d symmetric_part(const Eigen::Matrix3d& I) {
  return 0.5 * I + 0.5 * I.transpose();
}

}  // namespace

MassProperties::MassProperties(double mass, const Eigen::Vector3d& p_OC_B,
                               const Eigen::Matrix3d& I_C_B)
    : mass_(mass), p_OC_B_(p_OC_B), I_C_B_(symmetric_part(I_C_B)) {
  if (auto report = check(mass, p_OC_B, I_C_B)) {
    detail::throw_error("MassProperties", *report);
  }
}

std::optional<std::string> MassProperties::check(double mass, const Eigen::Vector3d& p_OC_B,
                                                 const Eigen::Matrix3d& I_C_B) {
  if (!std::isfinite(mass) || !(mass > 0.0)) {
    return fmt::format("mass must be positive and finite, got {} kg", mass);
  }
  if (!p_OC_B.allFinite()) {
    return fmt::format("center of mass must be finite, got {} m", to_string(p_OC_B.transpose()));
  }
  if (!I_C_B.allFinite()) {
    return fmt::format("inertia tensor must be finite, got {} kg·m²", to_string(I_C_B));
  }
  // every tolerance is relative to the trace: one that overflows would accept anything
  if (!std::isfinite(I_C_B.trace())) {
    return fmt::format("inertia tensor is too large: the sum of its diagonal elements overflows "
                       "a double; tensor {} kg·m²",
                       to_string(I_C_B));
  }
  const double tol = validity_tolerance(I_C_B);
  // symmetry: the largest |I_ij − I_ji|
  const Eigen::Matrix3d asym = (I_C_B - I_C_B.transpose()).cwiseAbs();
  Eigen::Index i = 0;
  Eigen::Index j = 0;
  const double worst = asym.maxCoeff(&i, &j);
  if (i > j) std::swap(i, j);
  if (worst > tol) {
    return fmt::format(
        "inertia tensor is not symmetric: |I({},{}) − I({},{})| = {:.6g} kg·m² exceeds the "
        "tolerance {:.3g} kg·m² (1e-10·tr I); tensor {} kg·m²",
        i, j, j, i, worst, tol, to_string(I_C_B));
  }
  const Eigen::Matrix3d sym = symmetric_part(I_C_B);
  // fast path: I₁ + I₂ ≥ I₃ for every ordering ⇔ J = ½ tr(I) 1 − I is positive semidefinite
  // (its eigenvalues are (I₁ + I₂ − I₃)/2 and permutations). So both conditions hold with the
  // margin tol exactly when I + tol·1 and J + tol·1 have Cholesky factors; the eigenvalues
  // (for the message with the margin) are only computed when one of them fails.
  if (tol > 0.0) {
    const Eigen::Matrix3d shift = tol * Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d J = 0.5 * sym.trace() * Eigen::Matrix3d::Identity() - sym;
    if (Eigen::LLT<Eigen::Matrix3d>(sym + shift).info() == Eigen::Success &&
        Eigen::LLT<Eigen::Matrix3d>(J + 0.5 * shift).info() == Eigen::Success) {
      return std::nullopt;
    }
  }
  const Eigen::Vector3d moments =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(sym, Eigen::EigenvaluesOnly).eigenvalues();
  if (!moments.allFinite()) {  // a NaN would pass both comparisons below
    return fmt::format("inertia tensor has no finite principal moments; tensor {} kg·m²",
                       to_string(I_C_B));
  }
  if (moments(0) < -tol) {
    return fmt::format(
        "inertia tensor is not positive semidefinite: principal moments ({:.6g}, {:.6g}, {:.6g}) "
        "kg·m², the smallest is below 0 by {:.6g} kg·m² (tolerance {:.3g} kg·m² = 1e-10·|tr I|); check the signs of "
        "the products of inertia (the tensor's off-diagonal elements are −∫ρxy dV)",
        moments(0), moments(1), moments(2), -moments(0), tol);
  }
  const double excess = moments(2) - (moments(0) + moments(1));
  if (excess > tol) {
    return fmt::format(
        "principal moments ({:.6g}, {:.6g}, {:.6g}) kg·m² violate I₁ + I₂ ≥ I₃ by {:.6g} kg·m² "
        "(tolerance {:.3g} "
        "kg·m² = 1e-10·tr I); no mass distribution has these moments",
        moments(0), moments(1), moments(2), excess, tol);
  }
  return std::nullopt;
}

Eigen::Matrix3d MassProperties::inertia_about(const Eigen::Vector3d& p_OQ_B) const {
  RIGID_REQUIRE(p_OQ_B.allFinite(), "point must be finite, got {} m", to_string(p_OQ_B.transpose()));
  const Eigen::Matrix3d I_Q = I_C_B_ + parallel_axis_term(mass_, p_OC_B_ - p_OQ_B);
  RIGID_REQUIRE(I_Q.allFinite(),
                "the inertia about the point {} m overflows a double (mass {} kg, center of mass "
                "{} m); expected finite entries (a nearer point, or other units)",
                to_string(p_OQ_B.transpose()), mass_, to_string(p_OC_B_.transpose()));
  return I_Q;
}

double MassProperties::inertia_about_axis(const Eigen::Vector3d& p_OQ_B,
                                          const Eigen::Vector3d& unit_B) const {
  RIGID_REQUIRE(unit_B.allFinite() && std::abs(unit_B.norm() - 1.0) <= 1e-12,
                "axis direction must be a unit vector (|u| within 1e-12 of 1), got {} with |u| = {}",
                to_string(unit_B.transpose()), unit_B.norm());
  return unit_B.dot(inertia_about(p_OQ_B) * unit_B);
}

MassProperties MassProperties::shifted(const Eigen::Vector3d& d_B) const {
  RIGID_REQUIRE(d_B.allFinite(), "shift must be finite, got {} m", to_string(d_B.transpose()));
  const Eigen::Vector3d p = p_OC_B_ + d_B;
  RIGID_REQUIRE(p.allFinite(), "the shifted center of mass {} + {} m overflows a double",
                to_string(p_OC_B_.transpose()), to_string(d_B.transpose()));
  return MassProperties(Unchecked{}, mass_, p, I_C_B_);
}

MassProperties MassProperties::rotated(const Eigen::Matrix3d& R_AB) const {
  require_rotation(R_AB, "rotated");
  return finite_result("rotated", mass_, R_AB * p_OC_B_, R_AB * I_C_B_ * R_AB.transpose());
}

MassProperties MassProperties::rotated(const SO3<double>& R_AB) const {
  return rotated(R_AB.matrix());
}

MassProperties MassProperties::transformed(const SE3<double>& X_AB) const {
  return transformed(X_AB.rotation().matrix(), X_AB.translation());
}

MassProperties MassProperties::transformed(const Eigen::Matrix3d& R_AB,
                                           const Eigen::Vector3d& p_AB_A) const {
  require_rotation(R_AB, "transformed");
  RIGID_REQUIRE(p_AB_A.allFinite(), "translation must be finite, got {} m",
                to_string(p_AB_A.transpose()));
  return finite_result("transformed", mass_, R_AB * p_OC_B_ + p_AB_A,
                       R_AB * I_C_B_ * R_AB.transpose());
}

PrincipalAxes MassProperties::principal_axes() const {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(I_C_B_);
  const Eigen::Vector3d moments = eig.eigenvalues();  // ascending
  const Eigen::Matrix3d V = eig.eigenvectors();
  const double tol = validity_tolerance(I_C_B_);
  const bool low_pair = moments(1) - moments(0) <= tol;
  const bool high_pair = moments(2) - moments(1) <= tol;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  if (low_pair && high_pair) {
    // spherical: every frame is principal; keep B's own.
    R.setIdentity();
  } else if (low_pair || high_pair) {
    // axisymmetric: the distinct axis is well defined; in its plane take the axis closest
    // to one of B's axes so that the answer does not depend on round-off.
    const Eigen::Index distinct = low_pair ? 2 : 0;
    const Eigen::Vector3d n = canonical_sign(V.col(distinct).normalized());
    const Eigen::Vector3d a = in_plane_axis(n);
    if (low_pair) {
      R.col(0) = a;
      R.col(1) = n.cross(a);
      R.col(2) = n;
    } else {
      R.col(0) = n;
      R.col(1) = a;
      R.col(2) = n.cross(a);
    }
  } else {
    R.col(0) = canonical_sign(V.col(0).normalized());
    R.col(1) = canonical_sign(V.col(1).normalized());
    R.col(2) = R.col(0).cross(R.col(1));
  }
  return PrincipalAxes{moments, R};
}

MassProperties MassProperties::finite_result(const char* function, double mass,
                                             const Eigen::Vector3d& p, const Eigen::Matrix3d& I) {
  RIGID_REQUIRE_AS(function, std::isfinite(mass) && p.allFinite() && I.allFinite(),
                   "the result overflows a double (its {}); expected finite mass properties "
                   "(other units, or a nearer frame)",
                   !std::isfinite(mass) ? "mass" : !p.allFinite() ? "center of mass" : "inertia");
  return MassProperties(Unchecked{}, mass, p, I);
}

std::optional<std::string> check_rotational_moments(const Eigen::Vector3d& moments) {
  if (!moments.allFinite()) {
    return fmt::format("principal moments must be finite, got {} kg·m²", to_string(moments.transpose()));
  }
  // fast path (a batch checks every body): moments clear of every bound of the full check by
  // tol = 1e-10·ΣI or more, where round-off (1e-16·ΣI) cannot change its verdict, pass
  // without building the tensor; the others take the full check and its message
  {
    const double sum = moments(0) + moments(1) + moments(2);
    const double tol = MassProperties::kRelativeTolerance * sum;
    if (std::isfinite(sum) && moments.minCoeff() > 2.0 * tol &&
        (0.5 * sum - moments.array()).minCoeff() > tol) {
      return std::nullopt;
    }
  }
  if (auto report = MassProperties::check(1.0, Eigen::Vector3d::Zero(), moments.asDiagonal().toDenseMatrix())) {
    return report;
  }
  const double tol = MassProperties::kRelativeTolerance * moments.sum();
  if (!(moments.minCoeff() > tol)) {
    return fmt::format(
        "principal moments ({:.10g}, {:.10g}, {:.10g}) kg·m² include a zero moment (at most "
        "1e-10·tr I = {:.3g} kg·m²): the rotation about that axis is undefined, as for a point "
        "mass or a thin rod; give the body a finite size",
        moments(0), moments(1), moments(2), tol);
  }
  return std::nullopt;
}

MassProperties combine(std::span<const MassProperties> parts) {
  RIGID_REQUIRE(!parts.empty(), "needs at least one body, got none");
  double mass = 0.0;
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
  for (const auto& p : parts) {
    mass += p.mass();
    first_moment += p.mass() * p.com();
  }
  const Eigen::Vector3d com = first_moment / mass;
  Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
  for (const auto& p : parts) {
    I += p.inertia_com() + parallel_axis_term(p.mass(), p.com() - com);
  }
  // a sum of physical tensors is physical: no re-check needed, but the sums may overflow
  return MassProperties::finite_result("combine", mass, com, 0.5 * (I + I.transpose()));
}

MassProperties combine(const MassProperties& a, const MassProperties& b) {
  const MassProperties parts[] = {a, b};
  return combine(std::span<const MassProperties>(parts));
}

MassProperties subtract(const MassProperties& whole, const MassProperties& hole) {
  const double mass = whole.mass() - hole.mass();
  RIGID_REQUIRE(mass > whole.mass() * MassProperties::kRelativeTolerance,
                "the hole ({} kg) is at least as heavy as the body ({} kg): the remaining mass "
                "would be {} kg",
                hole.mass(), whole.mass(), mass);
  const Eigen::Vector3d com = (whole.mass() * whole.com() - hole.mass() * hole.com()) / mass;
  // both tensors about the new COM, then subtract.
  const Eigen::Matrix3d I = whole.inertia_about(com) - hole.inertia_about(com);
  if (auto report = MassProperties::check(mass, com, I)) {
    RIGID_THROW("the body minus the hole is not physical (is the hole inside the body?): {}",
                *report);
  }
  return MassProperties(mass, com, I);
}

}  // namespace rigid

auto fmt::formatter<rigid::MassProperties>::format(const rigid::MassProperties& mp,
                                                   fmt::format_context& ctx) const
    -> decltype(ctx.out()) {
  const std::string text =
      fmt::format("MassProperties{{mass: {} kg, com: {} m, inertia_com: {} kg·m²}}", mp.mass(),
                  rigid::to_string(mp.com().transpose()), rigid::to_string(mp.inertia_com()));
  return fmt::formatter<std::string_view>::format(text, ctx);
}
