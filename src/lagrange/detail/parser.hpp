#pragma once

#include <exception>
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

/// log10 of the number of symbols, numbers and operations of e multiplied out, written as a
/// tree (an upper estimate, from e's graph without expanding it): the larger of the result and
/// the largest part that multiplying out creates on the way.
[[nodiscard]] double expanded_size_log10(const GiNaC::ex& e);

/// What a failure inside GiNaC or CLN (pole_error, CLN's floating-point and runtime exceptions,
/// std::domain_error, std::bad_alloc) means for the user, as the end of a sentence whose
/// subject is the expression ("has a pole here (…); expected a finite value"): the libraries'
/// own texts ("log_eval(): log(0)", "Not a 32-bit integer") name internals.
[[nodiscard]] std::string reason_of_library_failure(const std::exception& e);

/// Throws rigid::Error for `expression` at character `offset`.
[[noreturn]] void throw_at(const Expression& expression, std::size_t offset,
                           std::string_view context, const std::string& reason);

}  // namespace rigid::lagrange::detail
