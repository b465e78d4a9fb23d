#pragma once

#include <limits>

namespace rigid::test {

/// Machine epsilon of double: 2^-52 ≈ 2.22e-16.
inline constexpr double kEps = std::numeric_limits<double>::epsilon();

/// k units of round-off at magnitude `scale`: k·ε·scale. Every tolerance in the tests
/// is either built from this or carries a comment on where its number comes from.
constexpr double ulps(double k, double scale = 1.0) { return k * kEps * scale; }

/// How much slower the sanitizer builds run the same code: Parser.LongSumsAreLinear takes
/// 92 ms in the ci build and 2.1 s under ASan + UBSan (-O1) on a busy 2-core machine.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr double kSlowdown = 25.0;
#else
inline constexpr double kSlowdown = 1.0;
#endif

/// The wall-clock bound of a hang guard (an input that once ran for minutes or forever must
/// end within `seconds` in an optimised build), scaled for the sanitizer builds. Speed itself
/// is measured in bench/, never here.
constexpr double hang_bound(double seconds) { return seconds * kSlowdown; }

}  // namespace rigid::test
