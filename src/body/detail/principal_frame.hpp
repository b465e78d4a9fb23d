#pragma once

// The principal frame P in which a body's inertia is diagonal, for the free-body kernels of
// free_body_integrators.hpp (they take the principal moments and a state in P).

#include <cmath>
#include <limits>
#include <string_view>

#include <Eigen/Core>
#include <fmt/format.h>

#include "rigid/body/free_body_integrators.hpp"
#include "rigid/common/error.hpp"
#include "rigid/mass/mass_properties.hpp"

namespace rigid::body {

struct PrincipalFrame {
  Eigen::Vector3d moments;  ///< the diagonal of the inertia in P (kg·m²)
  SO3d R_BP = SO3d::identity();
  bool is_body = true;      ///< P = B: the inertia is already diagonal in B
};

/// P = B when I_B is diagonal, else the principal axes of rigid::MassProperties (ascending
/// moments, right-handed). Diagonal means off-diagonal entries at most 16 ε tr(I): a tensor
/// re-expressed in its own principal frame carries products of inertia of that size from the
/// rounding of the rotation alone, and dropping them changes the dynamics by no more than the
/// rounding of the tensor did. The tensor passes the one validity check of MassProperties and
/// its moments check_rotational_moments; an error starts with "<who>: inertia <about>: ".
inline PrincipalFrame principal_frame(const Eigen::Matrix3d& I_B, std::string_view who,
                                      std::string_view about) {
  if (auto report = MassProperties::check(1.0, Eigen::Vector3d::Zero(), I_B)) {
    throw Error(fmt::format("{}: inertia {}: {}", who, about, *report));
  }
  PrincipalFrame f;
  const double roundoff = 16.0 * std::numeric_limits<double>::epsilon() * std::abs(I_B.trace());
  if (std::abs(I_B(0, 1)) <= roundoff && std::abs(I_B(0, 2)) <= roundoff && std::abs(I_B(1, 2)) <= roundoff &&
      std::abs(I_B(1, 0)) <= roundoff && std::abs(I_B(2, 0)) <= roundoff && std::abs(I_B(2, 1)) <= roundoff) {
    f.moments = I_B.diagonal();
  } else {
    const PrincipalAxes pa = MassProperties(1.0, Eigen::Vector3d::Zero(), I_B).principal_axes();
    f.moments = pa.moments;
    f.R_BP = SO3d::from_matrix(pa.R_BP);
    f.is_body = false;
  }
  if (auto report = check_rotational_moments(f.moments)) {
    throw Error(fmt::format("{}: inertia {}: {}", who, about, *report));
  }
  return f;
}

/// (R_WB, ω_B) → (R_WP, ω_P) = (R_WB R_BP, R_BPᵀ ω_B).
inline FreeBodyState to_principal(const FreeBodyState& s_B, const SO3d& R_BP) {
  return {s_B.R_WB * R_BP, R_BP.inverse() * s_B.w_B};
}

/// (R_WP, ω_P) → (R_WB, ω_B) = (R_WP R_BPᵀ, R_BP ω_P).
inline FreeBodyState from_principal(const FreeBodyState& s_P, const SO3d& R_BP) {
  return {s_P.R_WB * R_BP.inverse(), R_BP * s_P.w_B};
}

}  // namespace rigid::body
