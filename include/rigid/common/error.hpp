#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

#include <fmt/format.h>

namespace rigid {

/// The one exception type of the library. Its message says what went wrong, where
/// (function, or file:line:column for input files), the offending value, what was
/// expected, and a remedy where one exists.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A run stopped on request (Ctrl-C on the command line, KeyboardInterrupt in Python, a
/// cancellation flag set by another thread). Nothing the run would have written is written.
class Cancelled : public Error {
 public:
  using Error::Error;
};

/// A position in a text input, for messages that start with `file:line:col: `.
/// line and column count from 1; 0 means unknown and is left out of the message.
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;
};

/// `file:line:col` (or `file:line`, or `file`) for the start of an error message.
[[nodiscard]] std::string to_string(const SourceLocation& where);

namespace detail {
/// Throws rigid::Error("<function>(): <message>").
[[noreturn]] void throw_error(std::string_view function, std::string message);
/// Throws rigid::Error("<file:line:col>: <message>").
[[noreturn]] void throw_error_at(const SourceLocation& where, std::string message);
/// Throws rigid::Error for a failed internal invariant (a bug in rigid, not bad input).
[[noreturn]] void throw_assertion(const char* condition, const char* file, int line,
                                  const char* function);
}  // namespace detail

}  // namespace rigid

/// Always-on check of user input at a public entry point: throws rigid::Error with
/// "<function>(): <formatted message>". Usage: RIGID_REQUIRE(r > 0, "radius must be
/// positive and finite, got {} m", r);
#define RIGID_REQUIRE(cond, ...)                                           \
  do {                                                                     \
    if (!(cond)) [[unlikely]] {                                            \
      ::rigid::detail::throw_error(__func__, ::fmt::format(__VA_ARGS__));  \
    }                                                                      \
  } while (false)

/// RIGID_REQUIRE for a check made in a helper on behalf of the public entry point `function`
/// (a string literal such as "integrate"), so that the message names what the caller called.
#define RIGID_REQUIRE_AS(function, cond, ...)                              \
  do {                                                                     \
    if (!(cond)) [[unlikely]] {                                            \
      ::rigid::detail::throw_error(function, ::fmt::format(__VA_ARGS__));  \
    }                                                                      \
  } while (false)

/// Unconditional throw with the same message format as RIGID_REQUIRE.
#define RIGID_THROW(...) ::rigid::detail::throw_error(__func__, ::fmt::format(__VA_ARGS__))

/// Internal invariant (never user input). On in Debug, RelWithDebInfo and whenever
/// RIGID_ENABLE_ASSERTS is defined; compiled out otherwise. Throws, never aborts, so
/// that the CLI and Python survive.
#ifdef RIGID_ENABLE_ASSERTS
#define RIGID_ASSERT(cond)                                                           \
  do {                                                                               \
    if (!(cond)) [[unlikely]] {                                                      \
      ::rigid::detail::throw_assertion(#cond, __FILE__, __LINE__, __func__);         \
    }                                                                                \
  } while (false)
#else
#define RIGID_ASSERT(cond) \
  do {                     \
  } while (false)
#endif
