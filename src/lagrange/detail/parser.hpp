#pragma once

#include <map>
#include <string>
#include <string_view>

#include <ginac/ginac.h>

#include "rigid/lagrange/system.hpp"

namespace rigid::lagrange::detail {

/// Parses an expression (grammar in docs/lagrange.md) into GiNaC, looking names up in
/// `names`. Decimal numbers become exact rationals (0.1 = 1/10).
/// @throws rigid::Error "<context>: <reason>" at the offending column.
[[nodiscard]] GiNaC::ex parse_expression(const Expression& expression,
                                         const std::map<std::string, GiNaC::ex>& names,
                                         std::string_view context);

/// Throws rigid::Error for `expression` at character `offset`.
[[noreturn]] void throw_at(const Expression& expression, std::size_t offset,
                           std::string_view context, const std::string& reason);

}  // namespace rigid::lagrange::detail
