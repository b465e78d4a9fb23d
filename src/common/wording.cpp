#include "rigid/common/wording.hpp"

#include <cctype>

#include <fmt/format.h>

namespace rigid {

std::string setting(std::string_view key) { return fmt::format("`{} = true`", key); }

std::string setting(std::string_view key, std::string_view value) {
  return fmt::format("`{} = \"{}\"`", key, value);
}

std::string counted(std::size_t n, std::string_view singular, std::string_view plural) {
  if (n == 1) return fmt::format("1 {}", singular);
  if (plural.empty()) return fmt::format("{} {}s", n, singular);
  return fmt::format("{} {}", n, plural);
}

namespace {

bool is_key_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; }

// A setting reference `key = true` or `key = "value"` starting at text[0] (the opening
// backtick); on success `key`, `value` (empty for true) and the length are set.
bool parse_reference(std::string_view text, std::string_view& key, std::string_view& value,
                     bool& boolean, std::size_t& length) {
  std::size_t i = 1;
  while (i < text.size() && is_key_char(text[i])) ++i;
  if (i == 1 || std::isalpha(static_cast<unsigned char>(text[1])) == 0) return false;
  key = text.substr(1, i - 1);
  const std::string_view rest = text.substr(i);
  if (rest.starts_with(" = true`")) {
    boolean = true;
    value = {};
    length = i + 8;
    return true;
  }
  if (!rest.starts_with(" = \"")) return false;
  const std::size_t open = i + 4;
  const std::size_t close = text.find("\"`", open);
  if (close == std::string_view::npos || text.substr(open, close - open).find('`') != std::string_view::npos) {
    return false;
  }
  boolean = false;
  value = text.substr(open, close - open);
  length = close + 2;
  return true;
}

// The length of a leading "name(): " (a C++ function: letters, digits, '_' and "::"), or 0.
std::size_t function_prefix(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size() && (is_key_char(text[i]) || text[i] == ':')) ++i;
  if (i == 0 || std::isalpha(static_cast<unsigned char>(text[0])) == 0) return 0;
  return text.substr(i).starts_with("(): ") ? i + 4 : 0;
}

}  // namespace

std::string strip_function_names(std::string_view message) {
  // at the start, and after each "…: " that a front end put before the library's message
  // (file:line:col: body 'b': make_primitive(): …)
  std::string out;
  out.reserve(message.size());
  std::size_t i = 0;
  bool at_start = true;
  while (i < message.size()) {
    if (at_start) {
      if (const std::size_t n = function_prefix(message.substr(i)); n > 0) {
        i += n;
        continue;
      }
    }
    at_start = message.substr(i).starts_with(": ");
    if (at_start) {
      out += ": ";
      i += 2;
      continue;
    }
    out += message[i++];
  }
  return out;
}

namespace {

std::string word_settings(Surface surface, std::string_view message) {
  std::string out;
  out.reserve(message.size());
  std::size_t i = 0;
  while (i < message.size()) {
    std::string_view key, value;
    bool boolean = false;
    std::size_t length = 0;
    if (message[i] == '`' && parse_reference(message.substr(i), key, value, boolean, length)) {
      if (surface == Surface::kCli) {
        std::string flag(key);
        for (char& c : flag) c = c == '_' ? '-' : c;
        out += boolean ? fmt::format("--{}", flag) : fmt::format("--{} {}", flag, value);
      } else if (surface == Surface::kScene) {
        // a key of the body's table, quoted as the scene's messages quote keys (and no longer a
        // reference: a front end that shows a scene's error leaves it as the file spells it)
        out += boolean ? fmt::format("'{} = true'", key) : fmt::format("'{} = \"{}\"'", key, value);
      } else {
        out += boolean ? fmt::format("{}=True", key) : fmt::format("{}=\"{}\"", key, value);
      }
      i += length;
      continue;
    }
    out += message[i++];
  }
  return out;
}

}  // namespace

std::string word_for(Surface surface, std::string_view message) {
  if (surface == Surface::kLibrary) return std::string(message);
  return word_settings(surface, strip_function_names(message));
}

}  // namespace rigid
