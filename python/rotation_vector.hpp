#pragma once
// SO3d::exp of a rotation vector given from Python, refused (rather than returned as NaN) when
// it is not finite or so long that |ω|² overflows: shared by rigid.SO3.exp and rigid.so3.exp
// so that the scalar and the batch refuse alike, in the same words.
#include <fmt/format.h>

#include <Eigen/Core>
#include <cmath>
#include <string_view>

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"
#include "rigid/lie/so3.hpp"

namespace rigid::python {

/// rigid::Error "<what> [0, nan, 0] has a non-finite component" (out of line: the loops that
/// check stay small).
[[noreturn, gnu::cold, gnu::noinline]] inline void refuse_non_finite(const Eigen::Vector3d& v,
                                                                     std::string_view what) {
  throw rigid::Error(
      fmt::format("{} {} has a non-finite component", what, rigid::to_string(v.transpose())));
}

/// rigid::Error "rotation vector [0, nan, 0] has a non-finite component" unless v is finite
/// (`what` names the vector).
inline void require_finite_vector(const Eigen::Vector3d& v, std::string_view what) {
  if (!v.allFinite()) [[unlikely]]
    refuse_non_finite(v, what);
}

/// SO3d::exp(omega), or rigid::Error (without a function name: the caller names the function,
/// the argument and the row) for a non-finite omega or one whose |ω|² overflows.
/// A vector longer than kMaxAngle rad (but whose |ω|² is finite) is refused by SO3d::exp in its
/// words ("is too long: angle |ω| = … rad, expected at most kMaxAngle …").
inline SO3d exp_of_rotation_vector(const Eigen::Vector3d& omega) {
  require_finite_vector(omega, "rotation vector");
  if (!std::isfinite(omega.squaredNorm())) [[unlikely]] {
    throw rigid::Error(fmt::format("rotation vector {} is too long: |ω|² overflows",
                                   rigid::to_string(omega.transpose())));
  }
  return SO3d::exp(omega);
}

}  // namespace rigid::python
