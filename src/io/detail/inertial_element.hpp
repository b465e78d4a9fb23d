#pragma once
// One <inertial> element read as `rigid inertia check` reads it: shared by read_inertials
// (inertial_xml.cpp) and fix_inertials (inertial_fix.cpp), which finds the elements itself.

#include <string>

#include "rigid/io/inertial_xml.hpp"

namespace tinyxml2 {
class XMLElement;
}  // namespace tinyxml2

namespace rigid::io::detail {

/// The inertial `inertial` of the link/body `name`, held by `file`, in `format`'s conventions;
/// a problem of the element or of the mass properties it states is the entry's `problem`.
[[nodiscard]] InertialEntry read_inertial_element(const tinyxml2::XMLElement* inertial,
                                                  InertialFormat format, std::string name,
                                                  std::string file);

}  // namespace rigid::io::detail
