#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include <fmt/format.h>

namespace rigid {

/// `text` as a message or a JSON document may show it: printable ASCII and well-formed UTF-8
/// sequences of printable characters as they are; control characters (bytes below 0x20, 0x7f,
/// so ESC and BEL never reach a terminal) and bytes that are not UTF-8 (0xff in a file name) as
/// \xNN, and a backslash as \\ so that the escaped text reads back one way.
[[nodiscard]] inline std::string escaped(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  for (std::size_t i = 0; i < text.size();) {
    const unsigned char c = byte(i);
    if (c == '\\') {
      out += "\\\\";
      ++i;
      continue;
    }
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
      ++i;
      continue;
    }
    // a UTF-8 sequence: its length from the lead byte, continuation bytes 10xxxxxx, no overlong
    // form (the code point at least the length's smallest), no surrogate, at most U+10FFFF, and
    // not a C1 control (U+0080 … U+009F)
    std::size_t n = c >= 0xc2 && c <= 0xdf   ? 2
                    : c >= 0xe0 && c <= 0xef ? 3
                    : c >= 0xf0 && c <= 0xf4 ? 4
                                             : 0;
    char32_t cp = n == 2 ? c & 0x1fu : n == 3 ? c & 0x0fu : c & 0x07u;
    for (std::size_t k = 1; k < n; ++k) {
      if (i + k >= text.size() || (byte(i + k) & 0xc0u) != 0x80u) {
        n = 0;
        break;
      }
      cp = (cp << 6) | (byte(i + k) & 0x3fu);
    }
    const bool ok = n != 0 && !(n == 3 && cp < 0x800) &&
                    !(n == 4 && (cp < 0x10000 || cp > 0x10ffff)) &&
                    !(cp >= 0xd800 && cp <= 0xdfff) && !(cp >= 0x80 && cp <= 0x9f);
    if (ok) {
      out.append(text.substr(i, n));
      i += n;
    } else {
      out += fmt::format("\\x{:02x}", c);
      ++i;
    }
  }
  return out;
}

}  // namespace rigid
