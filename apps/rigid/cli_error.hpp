#pragma once
// Errors of the command line itself: they speak of flags and files, so they carry no C++
// function name (unlike the library's RIGID_REQUIRE, which names the public entry point).
#include <fmt/format.h>

#include "rigid/common/error.hpp"

/// Throws rigid::Error(formatted message) when `cond` is false.
#define CLI_REQUIRE(cond, ...)                                  \
  do {                                                          \
    if (!(cond)) [[unlikely]] {                                 \
      throw ::rigid::Error(::fmt::format(__VA_ARGS__));         \
    }                                                           \
  } while (false)

/// Throws rigid::Error(formatted message).
#define CLI_THROW(...) throw ::rigid::Error(::fmt::format(__VA_ARGS__))

namespace rigid::cli {

/// The command line is wrong in itself: an option's value that is none of the option's forms
/// (an unknown name, a malformed list or size), a missing or conflicting option. main() prints it
/// as any rigid::Error and exits with the usage status 2, as for CLI11's own parse errors; a
/// value of the right form that the input refuses (a negative mass, a scene's unknown
/// coordinate) stays a rigid::Error, status 1.
class UsageError : public Error {
 public:
  using Error::Error;
};

}  // namespace rigid::cli

/// Throws rigid::cli::UsageError(formatted message) when `cond` is false.
#define CLI_USAGE_REQUIRE(cond, ...)                               \
  do {                                                             \
    if (!(cond)) [[unlikely]] {                                    \
      throw ::rigid::cli::UsageError(::fmt::format(__VA_ARGS__));  \
    }                                                              \
  } while (false)

/// Throws rigid::cli::UsageError(formatted message).
#define CLI_USAGE_THROW(...) throw ::rigid::cli::UsageError(::fmt::format(__VA_ARGS__))
