#pragma once
// The refusals of every group's interpolate(b, s) = a · exp(s · log(a⁻¹ b)), in the same words.

#include <cmath>

#include <fmt/format.h>

#include "rigid/common/error.hpp"
#include "rigid/lie/angle_limit.hpp"

namespace rigid::detail {

/// rigid::Error "<function>(): fraction s = nan is not finite, …" unless s is finite.
inline void require_finite_fraction(const char* function, double s) {
  RIGID_REQUIRE_AS(function, std::isfinite(s),
                   "fraction s = {} is not finite, expected a finite s (0 gives this element, 1 "
                   "the other)",
                   s);
}

/// rigid::Error unless the tangent s · log(a⁻¹ b), whose largest entry in magnitude is
/// `largest` and whose rotation angle is `turn` (rad), is finite and turns by at most kMaxAngle.
inline void require_interpolated_turn(const char* function, double s, double largest,
                                      double turn) {
  RIGID_REQUIRE_AS(function, std::isfinite(largest) && turn <= kMaxAngle,
                   "fraction s = {} gives the tangent s · log(a⁻¹ b) with largest entry {:.6g} "
                   "and turn {:.6g} rad, expected a finite tangent turning by at most kMaxAngle = "
                   "{:.0e} rad (beyond, rounding has lost the fraction of a turn)",
                   s, largest, turn, kMaxAngle);
}

}  // namespace rigid::detail
