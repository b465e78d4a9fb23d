#pragma once

// What connects the bodies of a scene, for the report's 3D view: a rod from a body to the body
// it hangs from, or to a fixed pivot in the world. Found from the scene (a body's `parent` and
// its last turn joint, a top's `pivot`) and, for a body posed by expressions alone, from its
// motion: a rod wherever the distance from its frame origin to an earlier body's origin (or to
// the world origin) stays the same over the run. Springs and the ropes the constraints name
// come from the scene as written.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "rigid/scene/model.hpp"

namespace rigid::report::detail {

/// One rod: from `point_B` (the body frame of body `body`, m) to `point_to` (the body frame of
/// body `to`, or the world when `to` is empty: a fixed pivot, m).
struct Link {
  std::size_t body = 0;
  Eigen::Vector3d point_B = Eigen::Vector3d::Zero();
  std::optional<std::size_t> to;
  Eigen::Vector3d point_to = Eigen::Vector3d::Zero();
  /// "parent", "pivot", "constant distance" or "fixed origin" (rods), "spring" (a
  /// [[springs]] entry) or "rope" (a constraint's `rope`)
  std::string rule;
};

/// The poses X_WB of every body (index as in the model) at the report's frames.
struct BodyPoses {
  std::vector<Eigen::Vector3d> p_WB;     ///< body frame origin in W (m)
  std::vector<Eigen::Quaterniond> R_WB;  ///< normalised
};

/// The links of `model`'s bodies given their poses at the report's frames (all the same count).
[[nodiscard]] std::vector<Link> find_links(const scene::Model& model,
                                           const std::vector<BodyPoses>& poses);

}  // namespace rigid::report::detail
