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
