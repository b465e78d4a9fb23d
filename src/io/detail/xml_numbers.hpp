#pragma once
// Whitespace-separated numbers in an XML attribute or element text, as URDF, SDF and MJCF write
// vectors ("0 0 1", "+1.5 2e-3"). Shared by the inertial reader and `rigid inertia fix`.
#include <cstddef>
#include <string>
#include <vector>

namespace rigid::io::detail {

struct XmlNumbers {
  std::vector<double> values;
  /// Empty when the text was read; else what was wrong, worded with `what` (the caller throws
  /// it as its own kind of problem, with its place).
  std::string problem;
};

/// Reads the numbers of `text` (nullptr reads as empty). `expected` = 0 accepts any count;
/// with `finite`, inf and nan are refused ("expected a finite number").
[[nodiscard]] XmlNumbers read_xml_numbers(const char* text, std::size_t expected, const std::string& what,
                                          bool finite);

}  // namespace rigid::io::detail
