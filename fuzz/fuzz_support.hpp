#pragma once

/// What every fuzz target shares: the one rule for outcomes and a scratch file for readers that
/// take a path.
///
/// Outcome rule: a target returns normally, or the library refuses the input with a
/// rigid::Error whose message is a rigid message. Anything else is a finding: another exception
/// type (std::bad_optional_access, std::bad_alloc, GiNaC's std::runtime_error …) escapes
/// LLVMFuzzerTestOneInput and terminates the process, a crash or sanitizer report stops it, and
/// a rigid::Error that is an internal-invariant failure or carries a library's raw text is
/// turned into an abort here.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include <unistd.h>

#include "rigid/common/error.hpp"
#include "rigid/common/escape.hpp"

namespace rigid::fuzz {

/// Raw texts of libraries that must never reach a user inside a rigid::Error (the message
/// must say what, where and what was expected in rigid's own words).
/// Each is specific enough not to match text a message quotes from the input.
inline constexpr std::string_view kRawLibraryText[] = {
    "bad optional access", "std::bad_alloc", "bad_variant_access", "basic_string::",
    "vector::_M_", "_eval(): ",
};

/// Aborts with the message when a refusal is not a proper rigid message: empty, an internal
/// invariant, or a library's raw text that the input does not contain (messages quote the
/// input, which may hold anything; the input need only hold the text without its trailing
/// punctuation, which the message may have added).
inline void check_refusal(const rigid::Error& e, std::string_view input) {
  const std::string_view what = e.what();
  // A quoted stretch of the input followed by the message's own punctuation can spell a raw
  // text ("<basic_string:" + ": it is cut short"), so the input need only hold the text
  // without its trailing ':', ' ', '(' and ')'. Messages quote the input escaped
  // (rigid::escaped), and an escape can spell the start of a raw text (the byte 0xba before
  // "d_variant_access" reads "\xbad_variant_access"), so the escaped input is searched too.
  const std::string escaped_input = rigid::escaped(input);
  const auto raw = [&](std::string_view text) {
    const std::string_view core = text.substr(0, text.find_last_not_of(":() ") + 1);
    return what.find(text) != std::string_view::npos && input.find(core) == std::string_view::npos &&
           escaped_input.find(core) == std::string_view::npos;
  };
  bool bad = what.empty() || raw("internal error");
  for (std::string_view text : kRawLibraryText) bad = bad || raw(text);
  if (bad) {
    std::fprintf(stderr, "rigid fuzz: improper refusal: %.*s\n", static_cast<int>(what.size()),
                 what.data());
    std::abort();
  }
}

/// Runs `f` on behalf of `input`; a rigid::Error is a normal outcome (checked by
/// check_refusal), anything else propagates.
template <class F>
void refuse_or_return(std::string_view input, F&& f) {
  try {
    f();
  } catch (const rigid::Cancelled&) {
    // a guard of the target itself (a step cap) stopped a run: a normal outcome
  } catch (const rigid::Error& e) {
    check_refusal(e, input);
  }
}

/// The input as text.
inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

/// A folder of this process for scratch files (readers that take a path).
inline const std::filesystem::path& scratch_dir() {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() /
             ("rigid-fuzz-" + std::to_string(static_cast<long>(::getpid())));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

/// Writes the input to scratch_dir()/name (replacing it) and returns the path.
inline std::string write_scratch(const std::uint8_t* data, std::size_t size, const std::string& name) {
  const auto path = scratch_dir() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) {
    std::fprintf(stderr, "rigid fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
  return path.string();
}

}  // namespace rigid::fuzz
