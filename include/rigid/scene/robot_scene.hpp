#pragma once

/// A robot model file (URDF, MJCF) as a scene of generalized coordinates: every surface that
/// takes a scene (eom, modes, run, sweep, check, report, export, Python) takes the model.
/// docs/robots.md states the conventions.
///
///  - Coordinates: the joints, by their names, in the model's order (depth first, MuJoCo's
///    qpos order); q(0) = each joint's ref, q̇(0) = 0.
///  - Bodies: the links that move. A link welded to its parent (no joint) is merged into it
///    (its inertial added in the parent's frame); one welded to the world is left out (it does
///    not move). A moving link without mass that carries exactly one moving link is merged
///    into it (its joints come first); any other massless moving link is refused.
///  - Passive forces: damping d gives the force −d q̇ on its coordinate, stiffness k the
///    potential ½ k (q − springref)², armature a the kinetic energy ½ a q̇².
///  - Gravity: the model's. [simulation]: t_end = 5 s, the coordinates' default integrator;
///    `--set simulation.t_end=…` and the other overrides apply as to any scene.

#include <cstddef>
#include <filesystem>
#include <string_view>

#include "rigid/io/robot_model.hpp"
#include "rigid/scene/scene.hpp"

namespace rigid::scene {

/// The scene of a robot model; `file` is the model file (the scene's file, for messages and
/// the default output directory).
/// With `symbolic_inertia`, each body's mass, COM and inertia are scene parameters
/// (ModelOptions::symbolic_inertia; a body that absorbed welded links carries their sum).
/// @throws rigid::Error naming the link for a massless moving link that cannot be merged.
[[nodiscard]] Scene scene_from_robot(const io::RobotModel& model,
                                     const std::filesystem::path& file,
                                     bool symbolic_inertia = false);

/// The options io::read_robot_model takes, from `options` (a field left unset: its default);
/// `file` names the model in messages.
/// @throws rigid::Error for a density that is not finite and > 0, or that is set without
///   inertia_from_geometry (it would change nothing).
[[nodiscard]] io::RobotReadOptions robot_read_options(const ModelOptions& options,
                                                      const std::filesystem::path& file);

/// The scene of the robot model `xml`, the text of `file`, read with `options`
/// (robot_read_options); `scene_file` is the scene's file (for messages and the default output
/// directory): `file` itself, or the TOML scene whose `[model]` names it.
/// @throws rigid::Error as robot_read_options, io::read_robot_model and scene_from_robot do,
///   and for a density set for a model other than URDF (an MJCF geom carries its own).
[[nodiscard]] Scene scene_from_robot_file(const std::string& xml,
                                          const std::filesystem::path& file,
                                          const ModelOptions& options,
                                          const std::filesystem::path& scene_file);

/// True when `text` is an XML document (its first non-blank character is '<'): a robot model
/// rather than a TOML scene.
[[nodiscard]] bool looks_like_xml(std::string_view text);

}  // namespace rigid::scene
