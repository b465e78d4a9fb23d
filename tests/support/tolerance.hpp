#pragma once

#include <limits>

namespace rigid::test {

/// Machine epsilon of double: 2^-52 ≈ 2.22e-16.
inline constexpr double kEps = std::numeric_limits<double>::epsilon();

/// k units of round-off at magnitude `scale`: k·ε·scale. Every tolerance in the tests
/// is either built from this or carries a comment on where its number comes from.
constexpr double ulps(double k, double scale = 1.0) { return k * kEps * scale; }

}  // namespace rigid::test
