#pragma once
// MJCF text edits for the references the tests and benchmarks load in MuJoCo.

#include <cstddef>
#include <string>

namespace rigid::test {

/// The text without its <freejoint .../> elements: MuJoCo's model of the robot pinned at its
/// root (what rigid reads with RobotReadOptions::pin_free_root).
inline std::string without_free_joints(std::string text) {
  for (std::size_t at; (at = text.find("<freejoint")) != std::string::npos;) {
    text.erase(at, text.find("/>", at) + 2 - at);
  }
  return text;
}

}  // namespace rigid::test
