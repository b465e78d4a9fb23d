#pragma once
// Shared by inertial_fix.cpp (URDF, SDF, the rewrite) and mjcf_bodies.cpp (MJCF): the
// geometry of one link/body, measured in its frame.

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rigid/mass/mass_properties.hpp"

namespace tinyxml2 {
class XMLElement;
}

namespace rigid::io::detail {

/// A problem of one geometry or attribute: recorded in the link, not thrown, so that every
/// link of a file is tried and reported.
struct GeometryProblem {
  std::string text;
};

/// One link (URDF/SDF) or body (MJCF) with its geometry measured in its own frame.
struct LinkGeometry {
  const tinyxml2::XMLElement* element = nullptr;
  std::string name;
  int line = 0;
  const tinyxml2::XMLElement* inertial = nullptr;  ///< the existing <inertial>, if any
  /// false: the inertial stays as it is (MJCF: inertiafromgeom="auto" and the body has one,
  /// or inertiafromgeom="false"); keep_detail says why.
  bool recompute = true;
  std::string keep_detail;
  /// Each geometry's mass properties in the link frame, at its own density (URDF/SDF: at
  /// density 1, so that mass = volume; the caller scales).
  std::vector<MassProperties> parts;
  double volume = 0;  ///< m³, every geometry
  /// Geometries that count for nothing (MJCF mass="0"): the body has geometry but no mass.
  bool has_massless_geometry = false;
  std::vector<std::string> warnings;
  std::vector<std::string> errors;
};

/// Whitespace-separated numbers; `expected` = 0 accepts any count.
/// @throws GeometryProblem naming `what`, the text and the expected count.
std::vector<double> parse_numbers(const char* text, std::size_t expected, const std::string& what);

/// A primitive of the catalogue (rigid::mass::primitive_table) by name, at density rho, with
/// its sizes in the catalogue's order. @throws GeometryProblem with the catalogue's refusal.
MassProperties catalogue_primitive(const char* name, double rho, std::vector<double> sizes,
                                   const std::string& what);

/// A mesh file's solid mass properties at density rho, scaled by diag(scale) (m per file
/// unit along x, y, z), in the file's frame; `volume` receives its volume (m³).
/// @throws GeometryProblem for a missing/unreadable/open mesh, a mirroring or zero scale, or
/// a part longer than mesh::kMaxPartSize (a millimetre file read as metres).
MassProperties mesh_solid(const std::string& path, const Eigen::Vector3d& scale, double rho,
                          const std::string& what, double& volume,
                          std::vector<std::string>& warnings);

/// MJCF bodies of the document rooted at <mujoco>, in document order, each measured with
/// MuJoCo's compiler rules. @throws rigid::Error for problems of the whole document
/// (<include>, compiler settings that rescale every body).
std::vector<LinkGeometry> mjcf_links(const tinyxml2::XMLElement* root, const std::string& source);

}  // namespace rigid::io::detail
