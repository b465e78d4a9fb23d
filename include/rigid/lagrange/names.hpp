#pragma once

#include <string>

namespace rigid::lagrange {

/// Whether `name` is reserved in expressions: t (time), pi and the function names (sin, cos,
/// tan, asin, acos, atan, exp, log, sqrt, abs, sinh, cosh, tanh); a parameter, coordinate or
/// body may not take one.
[[nodiscard]] bool is_reserved_name(const std::string& name);

}  // namespace rigid::lagrange
