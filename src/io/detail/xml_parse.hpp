#pragma once
// The one place where an XML document of the io module is parsed: every reader (inertials,
// `rigid inertia fix`, robot models, MJCF <include>d files) calls parse_xml, so that a
// malformed file is refused in the same plain words, never with tinyxml2's own error text.

#include <cstddef>
#include <string>
#include <string_view>

namespace tinyxml2 {
class XMLDocument;
}  // namespace tinyxml2

namespace rigid::io::detail {

/// Parses `text` into `doc`.
/// @throws rigid::Error "source:line: malformed XML: <what is wrong, in plain words>" (a file
///   that ends inside an element says so, naming the element and the line it starts on), or
///   "source:1: the document has no root element".
void parse_xml(tinyxml2::XMLDocument& doc, const std::string& text, const std::string& source);

/// The position of the '>' that ends the start tag whose '<' is at `at`, skipping quoted
/// attribute values; s.size() when the text ends first.
[[nodiscard]] std::size_t start_tag_end(std::string_view s, std::size_t at);

}  // namespace rigid::io::detail
