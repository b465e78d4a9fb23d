#pragma once

#include <string>
#include <string_view>

namespace rigid::test {

/// `xml` with every <inertial> element removed, together with the blank space before it back to
/// and including the line break (so an inserted line disappears whole). What is left of a
/// rewritten file must equal what is left of the original, byte for byte. A plain text scan,
/// independent of the rewriter (it assumes no "<inertial" inside comments or attribute values).
inline std::string without_inertials(std::string_view xml) {
  std::string out;
  std::size_t i = 0;
  while (true) {
    const std::size_t at = xml.find("<inertial", i);
    if (at == std::string_view::npos) break;
    std::size_t from = at;
    while (from > i && (xml[from - 1] == ' ' || xml[from - 1] == '\t')) --from;
    if (from > i && xml[from - 1] == '\n') --from;
    if (from > i && xml[from - 1] == '\r') --from;
    const std::size_t tag_end = xml.find('>', at);
    std::size_t end = tag_end + 1;
    if (xml[tag_end - 1] != '/') end = xml.find("</inertial>", at) + std::string_view("</inertial>").size();
    out.append(xml.substr(i, from - i));
    i = end;
  }
  out.append(xml.substr(i));
  return out;
}

}  // namespace rigid::test
