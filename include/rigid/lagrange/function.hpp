#pragma once

/// A real function of named variables, compiled from an expression of the scene grammar
/// (docs/lagrange.md: + − * / ^, parentheses, numbers, pi, the elementary functions) into the
/// instruction tape the equations of motion run on: a density field ρ(x, y, z) is evaluated
/// some millions of times by a cubature, far too often for a symbolic evaluation each time.

#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rigid/lagrange/system.hpp"

namespace rigid::lagrange {

class CompiledFunction {
 public:
  /// The value at `x` (one value per variable, in the order they were named). Safe to call
  /// from several threads at once (each thread keeps its own scratch).
  /// @throws rigid::Error if x has the wrong size.
  [[nodiscard]] double operator()(std::span<const double> x) const;
  /// The variables' names, in order.
  [[nodiscard]] const std::vector<std::string>& variables() const;
  /// The expression as written.
  [[nodiscard]] const std::string& text() const;

  struct Impl;

 private:
  friend CompiledFunction compile_function(const Expression&, const std::vector<std::string>&,
                                           const std::vector<Parameter>&, std::string_view);
  std::shared_ptr<const Impl> impl_;
};

/// Compiles `expression` as a function of `variables` (identifiers, e.g. x, y, z), with the
/// `parameters` taken by value. Any other name, a syntax error, or a result that is not real
/// is refused at the expression's location, "<context>: …".
/// @throws rigid::Error as described, or for a variable name that is not an identifier, is a
///         parameter's too, or is reserved (pi, sin, …).
[[nodiscard]] CompiledFunction compile_function(const Expression& expression,
                                                const std::vector<std::string>& variables,
                                                const std::vector<Parameter>& parameters,
                                                std::string_view context);

}  // namespace rigid::lagrange
