#include "rigid/common/number_literal.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>

#include <fmt/format.h>

namespace rigid {
namespace {

bool is_digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

}  // namespace

std::string_view leading_literal(std::string_view text) {
  std::size_t i = 0;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  const std::size_t mantissa = i;
  while (i < text.size() && (is_digit(text[i]) || text[i] == '.' || text[i] == '_')) ++i;
  if (i == mantissa) return {};
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    std::size_t p = i + 1;
    if (p < text.size() && (text[p] == '+' || text[p] == '-')) ++p;
    if (p < text.size() && is_digit(text[p])) {
      while (p < text.size() && (is_digit(text[p]) || text[p] == '_')) ++p;
      i = p;
    }
  }
  return text.substr(0, i);
}

std::optional<std::string> literal_range_problem(std::string_view literal) {
  if (leading_literal(literal).size() != literal.size() || literal.empty()) return std::nullopt;
  // the digits without TOML's '_' separators, for strtod
  std::string clean;
  bool nonzero = false, in_exponent = false;
  for (const char c : literal) {
    if (c == '_') continue;
    if (c == 'e' || c == 'E') in_exponent = true;
    if (!in_exponent && c >= '1' && c <= '9') nonzero = true;
    clean += c;
  }
  if (!nonzero) return std::nullopt;                     // 0, 0.0, 0e999: zero as written
  const double v = std::strtod(clean.c_str(), nullptr);  // rounds to nearest (ERANGE not needed)
  const auto range = fmt::format(
      "expected 0 or a magnitude from {:.17g} to {:.17g} (the normal "
      "range of a double)",
      kSmallestLiteral, kLargestLiteral);
  if (std::isinf(v)) {
    return fmt::format("'{}' overflows: a double would hold {}infinity; {}", literal,
                       v < 0 ? "-" : "", range);
  }
  if (v == 0) return fmt::format("'{}' underflows: a double would hold 0; {}", literal, range);
  if (std::fpclassify(v) == FP_SUBNORMAL) {
    return fmt::format(
        "'{}' underflows: a double would hold the subnormal {:.17g}, with fewer "
        "than 53 significant bits; {}",
        literal, v, range);
  }
  return std::nullopt;
}

}  // namespace rigid
