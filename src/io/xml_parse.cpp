// XML documents parsed with their errors in plain words (detail/xml_parse.hpp). tinyxml2 gives
// an error kind and a line; its own text ("Error=XML_ERROR_PARSING_TEXT ErrorID=8 ...") is for
// its developers. A small scan of the text adds what a user needs to find the problem: the
// element a truncated file ends inside, or the start tag a wrong end tag meets. Names are
// quoted escaped (rigid::escaped): a tag may hold control characters and bytes that are not UTF-8.
#include "detail/xml_parse.hpp"

#include <algorithm>
#include <cstddef>
#include <optional>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <tinyxml2.h>

#include "rigid/common/error.hpp"
#include "rigid/common/escape.hpp"

namespace rigid::io::detail {
namespace {

constexpr std::string_view kSpace = " \t\r\n";

// tinyxml2's error kinds in plain words
std::string plain_words(tinyxml2::XMLError e) {
  switch (e) {
    case tinyxml2::XML_ERROR_PARSING_ELEMENT:
      return "a tag is badly formed or not closed (expected '>' or '/>' after its attributes)";
    case tinyxml2::XML_ERROR_PARSING_ATTRIBUTE:
      return "an attribute is badly formed or given twice (expected name=\"value\", each name "
             "once per element)";
    case tinyxml2::XML_ERROR_PARSING_TEXT:
      return "text where a tag was expected (text before or after the root element?)";
    case tinyxml2::XML_ERROR_PARSING_CDATA:
      return "a CDATA section is not closed (expected ]]>)";
    case tinyxml2::XML_ERROR_PARSING_COMMENT:
      return "a comment is not closed (expected -->)";
    case tinyxml2::XML_ERROR_PARSING_DECLARATION:
      return "a <?...?> declaration is badly formed or not closed (expected ?>)";
    case tinyxml2::XML_ERROR_PARSING_UNKNOWN:
      return "a <!...> declaration is badly formed or not closed (expected >)";
    case tinyxml2::XML_ERROR_EMPTY_DOCUMENT:
      return "the file is empty (expected an XML document with one root element)";
    case tinyxml2::XML_ERROR_MISMATCHED_ELEMENT:
      return "an end tag does not match its start tag (an element is not closed, or an end tag "
             "is misspelt)";
    case tinyxml2::XML_ELEMENT_DEPTH_EXCEEDED:
      return fmt::format("elements are nested more than {} levels deep",
                         TINYXML2_MAX_ELEMENT_DEPTH);
    default:
      return "a '<' that starts no tag, comment or declaration";
  }
}

struct Tag {
  std::string name;
  int line = 0;
};

// The markup of a text scanned up to its first problem: the elements open there, and why the
// scan stopped (an end tag that closes none of them, or the end of the text inside a tag,
// comment, CDATA section or declaration). It trusts nothing: what it finds is used only where
// tinyxml2 agrees (a wrong end tag) or a re-parse confirms it (a truncated file).
struct Scan {
  std::vector<Tag> open;
  std::optional<Tag> wrong_end_tag;
  std::size_t unfinished = std::string_view::npos;  // where the unfinished markup starts
  std::string unfinished_kind;                      // "the start tag <b", "a comment", ...
  bool unfinished_tag = false;                      // a start or end tag, not a comment ...
};

Scan scan(std::string_view s) {
  Scan out;
  std::size_t counted = 0;
  int line = 1;
  auto line_at = [&](std::size_t at) {
    line += static_cast<int>(std::count(s.begin() + static_cast<std::ptrdiff_t>(counted),
                                        s.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
    counted = at;
    return line;
  };
  auto name_at = [&](std::size_t from) {
    const std::size_t end = std::min(s.find_first_of(" \t\r\n/>", from), s.size());
    return std::string(s.substr(from, end - from));
  };
  std::size_t i = 0;
  while ((i = s.find('<', i)) != std::string_view::npos) {
    const std::string_view rest = s.substr(i);
    std::string_view close, kind;
    std::size_t skip = 0;
    if (rest.starts_with("<!--")) {
      close = "-->", kind = "a comment", skip = 4;
    } else if (rest.starts_with("<![CDATA[")) {
      close = "]]>", kind = "a CDATA section", skip = 9;
    } else if (rest.starts_with("<?")) {
      close = "?>", kind = "a <?...?> declaration", skip = 2;
    } else if (rest.starts_with("<!")) {
      close = ">", kind = "a <!...> declaration", skip = 2;
    }
    if (!close.empty()) {
      const std::size_t k = s.find(close, i + skip);
      if (k == std::string_view::npos) {
        out.unfinished = i;
        out.unfinished_kind = kind;
        return out;
      }
      i = k + close.size();
      continue;
    }
    if (rest.starts_with("</")) {
      const std::size_t k = s.find('>', i + 2);
      if (k == std::string_view::npos) {
        out.unfinished = i;
        out.unfinished_kind = fmt::format("the end tag </{}", escaped(name_at(i + 2)));
        out.unfinished_tag = true;
        return out;
      }
      std::string_view name = s.substr(i + 2, k - i - 2);
      name = name.substr(0, name.find_last_not_of(kSpace) + 1);
      if (out.open.empty() || out.open.back().name != name) {
        out.wrong_end_tag = Tag{std::string(name), line_at(i)};
        return out;
      }
      out.open.pop_back();
      i = k + 1;
      continue;
    }
    // a start tag: to the '>' outside quoted attribute values
    const std::size_t k = start_tag_end(s, i);
    if (k >= s.size()) {
      out.unfinished = i;
      out.unfinished_kind = fmt::format("the start tag <{}", escaped(name_at(i + 1)));
      out.unfinished_tag = true;
      return out;
    }
    if (s[k - 1] != '/') out.open.push_back({name_at(i + 1), line_at(i)});
    i = k + 1;
  }
  return out;
}

// the line of the text's last character that is not white space
int last_line(std::string_view s) {
  const std::size_t k = s.find_last_not_of(kSpace);
  if (k == std::string_view::npos) return 1;
  return 1 +
         static_cast<int>(std::count(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(k), '\n'));
}

// "the file ends inside <b> ..." when the text is well-formed up to its end, where elements
// (or a tag, comment ...) are left open: the text without its unfinished markup, with the
// open elements' end tags appended, parses
std::optional<std::string> truncation(std::string_view text, const Scan& s) {
  if (s.wrong_end_tag) return std::nullopt;
  if (s.open.empty() && s.unfinished == std::string_view::npos) return std::nullopt;
  // an unclosed comment, CDATA section or declaration takes the rest of the file: tinyxml2's
  // kind says that better than "the file ends inside <x>"
  if (s.unfinished != std::string_view::npos && !s.unfinished_tag) return std::nullopt;
  std::string completed(text.substr(0, std::min(s.unfinished, text.size())));
  for (auto it = s.open.rbegin(); it != s.open.rend(); ++it) completed += "</" + it->name + ">";
  tinyxml2::XMLDocument doc;
  const tinyxml2::XMLError e = doc.Parse(completed.c_str(), completed.size());
  if (e != tinyxml2::XML_SUCCESS && !(s.open.empty() && e == tinyxml2::XML_ERROR_EMPTY_DOCUMENT)) {
    return std::nullopt;
  }
  if (s.open.empty()) {
    return fmt::format("the file ends in the middle of {}: it is cut short", s.unfinished_kind);
  }
  const std::string middle =
      s.unfinished_kind.empty() ? "" : fmt::format(", in the middle of {}", s.unfinished_kind);
  const Tag& inner = s.open.back();
  return fmt::format(
      "the file ends inside the element <{}> of line {}{}: it is cut short, or "
      "</{}> is missing",
      escaped(inner.name), inner.line, middle, escaped(inner.name));
}

}  // namespace

std::size_t start_tag_end(std::string_view s, std::size_t at) {
  char quote = 0;
  for (std::size_t k = at + 1; k < s.size(); ++k) {
    if (quote != 0) {
      if (s[k] == quote) quote = 0;
    } else if (s[k] == '"' || s[k] == '\'') {
      quote = s[k];
    } else if (s[k] == '>') {
      return k;
    }
  }
  return s.size();
}

void parse_xml(tinyxml2::XMLDocument& doc, const std::string& text, const std::string& source) {
  if (const tinyxml2::XMLError e = doc.Parse(text.c_str(), text.size());
      e != tinyxml2::XML_SUCCESS) {
    int line = std::max(doc.ErrorLineNum(), 1);
    std::string what = plain_words(e);
    const Scan s = scan(text);
    if (auto cut = truncation(text, s)) {
      line = last_line(text);
      what = std::move(*cut);
    } else if (e == tinyxml2::XML_ERROR_MISMATCHED_ELEMENT && s.wrong_end_tag && !s.open.empty() &&
               s.open.back().line == line) {
      const Tag& open = s.open.back();
      what = fmt::format(
          "an end tag does not match its start tag: </{}> on line {} comes while "
          "<{}> of line {} is open (expected </{}> first, or <{} .../> for an "
          "element without content)",
          escaped(s.wrong_end_tag->name), s.wrong_end_tag->line, escaped(open.name), open.line,
          escaped(open.name), escaped(open.name));
    }
    rigid::detail::throw_error_at(SourceLocation{source, line, 0},
                                  fmt::format("malformed XML: {}", what));
  }
  if (doc.RootElement() == nullptr) {
    rigid::detail::throw_error_at(SourceLocation{source, 1, 0},
                                  "the document has no root element; expected one");
  }
}

}  // namespace rigid::io::detail
