#include "detail/xml_numbers.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <string_view>

#include <fmt/format.h>

namespace rigid::io::detail {

XmlNumbers read_xml_numbers(const char* text, std::size_t expected, const std::string& what, bool finite) {
  XmlNumbers out;
  const std::string_view s = text == nullptr ? std::string_view{} : std::string_view(text);
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    if (i >= s.size()) break;
    std::size_t j = i;
    while (j < s.size() && !std::isspace(static_cast<unsigned char>(s[j]))) ++j;
    const std::string_view token = s.substr(i, j - i);  // not empty: s[i] is not a space
    // std::from_chars takes no leading '+', which XML writers may put
    const char* first = token.front() == '+' ? token.data() + 1 : token.data();
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(first, token.data() + token.size(), v);
    if (ec != std::errc() || ptr != token.data() + token.size() || (finite && !std::isfinite(v))) {
      out.problem = fmt::format("{}: expected a {}number, got '{}'", what, finite ? "finite " : "", token);
      return out;
    }
    out.values.push_back(v);
    i = j;
  }
  if (expected != 0 && out.values.size() != expected) {
    out.problem = fmt::format("{}: expected {} number{}, got {} ('{}')", what, expected, expected == 1 ? "" : "s",
                              out.values.size(), s);
  }
  return out;
}

}  // namespace rigid::io::detail
