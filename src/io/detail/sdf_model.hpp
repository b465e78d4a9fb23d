#pragma once
// The SDFormat reader behind read_robot_model (src/io/sdf_model.cpp): robot_model.cpp hands it
// a parsed document whose root element is <sdf>.

#include <string>
#include <vector>

#include "rigid/io/robot_model.hpp"

namespace tinyxml2 {
class XMLElement;
}  // namespace tinyxml2

namespace rigid::io::detail {

/// The tree of the one <model> of an <sdf> document (at its top or in its one <world>); `xml`
/// is the document's text (for inertia_from_geometry), `file` names it in messages.
/// @throws rigid::Error "file:line: ..." for what include/rigid/io/robot_model.hpp lists.
[[nodiscard]] RobotModel read_sdf_model(const tinyxml2::XMLElement* sdf, const std::string& xml,
                                        const std::string& file, const RobotReadOptions& options);

/// Every link's inertial from its collision geometry (URDF, SDF), measured as `rigid inertia
/// fix` does at options.density; links without geometry keep their stated inertial. Defined in
/// robot_model.cpp, used by both readers.
/// @throws rigid::Error for a density that is not positive and finite, or geometry fix refuses.
void set_geometry_inertials(const std::string& xml, const std::string& file,
                            const RobotReadOptions& options, std::vector<RobotLink>& links);

}  // namespace rigid::io::detail
