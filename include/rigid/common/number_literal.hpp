#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace rigid {

/// The smallest and largest magnitudes a decimal literal may have: the smallest positive normal
/// double, 2^-1022 ≈ 2.2250738585072014e-308, and the largest finite double,
/// (2 − 2^-52)·2^1023 ≈ 1.7976931348623157e308 (IEEE 754 binary64). A non-zero literal below
/// the first is stored as 0 or as a subnormal with fewer than 53 significant bits; one above
/// the second as infinity.
inline constexpr double kSmallestLiteral = 2.2250738585072014e-308;
inline constexpr double kLargestLiteral = 1.7976931348623157e308;

/// Why the decimal literal `literal` ([sign] digits [. digits] [e|E [sign] digits], '_' between
/// digits allowed as in TOML) is not held by a double at its value: a non-zero literal whose
/// double is 0 or subnormal (it underflows), or one whose double is infinite (it overflows).
/// The sentence says what was written, what it would become and the representable range,
/// e.g. "'1e-400' underflows: a double would hold 0; expected 0 or a magnitude from
/// 2.2250738585072014e-308 to 1.7976931348623157e+308". Nothing for a literal in range, for 0
/// written as 0, and for text that is not a decimal literal (inf, nan, hexadecimal, a name):
/// the caller's own checks say what those are.
[[nodiscard]] std::optional<std::string> literal_range_problem(std::string_view literal);

/// The decimal literal at the start of `text` (as literal_range_problem reads one), or an empty
/// view: for a literal whose position in a larger text is known but not its end.
[[nodiscard]] std::string_view leading_literal(std::string_view text);

}  // namespace rigid
