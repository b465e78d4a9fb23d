#pragma once
// Shared by inertial_fix.cpp (URDF, SDF, the rewrite) and mjcf_bodies.cpp (MJCF): the
// geometry of one link/body, measured in its frame.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "rigid/mass/mass_properties.hpp"
#include "xml_parse.hpp"

namespace tinyxml2 {
class XMLDocument;
class XMLElement;
}  // namespace tinyxml2

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

/// The largest model file read (bytes): a robot model is kilobytes to a few megabytes.
inline constexpr std::uintmax_t kMaxModelFileBytes = 256u << 20u;

/// The text of a regular file of at most kMaxModelFileBytes. @throws rigid::Error naming
/// `path` if it does not exist, is not a regular file (a directory, FIFO, device), is larger,
/// or cannot be read; the check comes before the file is opened.
std::string read_model_file(const std::string& path);

/// An MJCF document with its <include>s (MuJoCo's XML reference, "include"): the included
/// file's root element is dropped and its children take the include's place; `file` is
/// relative to the directory of the main file; a file is included at most once; includes nest.
/// Every element keeps its own document, so messages name the file and line it came from.
class MjcfDocument {
 public:
  /// The document of the main file `source` rooted at `root` (which must outlive this). With
  /// follow_includes the included files are read now; without, <include> elements are kept
  /// as they are (mjcf_links(root, source) refuses them).
  /// @throws rigid::Error "file:line: ..." for an include that cannot be read or parsed,
  ///   one without 'file', a file included twice, or an empty included file.
  MjcfDocument(const tinyxml2::XMLElement* root, std::string source, bool follow_includes);
  ~MjcfDocument();
  MjcfDocument(const MjcfDocument&) = delete;
  MjcfDocument& operator=(const MjcfDocument&) = delete;

  [[nodiscard]] const tinyxml2::XMLElement* root() const { return root_; }
  /// The main file.
  [[nodiscard]] const std::string& source() const { return source_; }
  /// The file that holds `e`.
  [[nodiscard]] const std::string& file_of(const tinyxml2::XMLElement* e) const;
  /// The child elements of `e` in document order, followed <include>s replaced by their
  /// files' elements; only those named `name` unless it is empty.
  [[nodiscard]] std::vector<const tinyxml2::XMLElement*> children(const tinyxml2::XMLElement* e,
                                                                  std::string_view name = {}) const;
  /// The root element of the file that the followed <include> element `include` brings in
  /// (its children take the include's place), or nullptr if `include` is none.
  [[nodiscard]] const tinyxml2::XMLElement* included_root(const tinyxml2::XMLElement* include) const;
  /// The text of the included file whose root is `root` (an included_root()).
  [[nodiscard]] const std::string& included_text(const tinyxml2::XMLElement* root) const;
  /// Throws rigid::Error "file:line: message" at `e`.
  [[noreturn]] void refuse(const tinyxml2::XMLElement* e, const std::string& message) const;

 private:
  void load_includes(const tinyxml2::XMLElement* e, std::vector<std::string>& seen);
  void append_children(const tinyxml2::XMLElement* e, std::string_view name,
                       std::vector<const tinyxml2::XMLElement*>& out) const;

  const tinyxml2::XMLElement* root_;
  std::string source_;
  std::vector<std::unique_ptr<tinyxml2::XMLDocument>> included_docs_;
  std::map<const tinyxml2::XMLDocument*, std::string> file_names_;
  std::map<const tinyxml2::XMLElement*, const tinyxml2::XMLElement*> include_roots_;
  std::map<const tinyxml2::XMLElement*, std::string> included_texts_;  // by included root
};

/// <compiler> settings of an MJCF model (MuJoCo's defaults).
struct MjcfCompiler {
  bool degrees = true;  // angle="degree" is MuJoCo's default
  std::string eulerseq = "xyz";
  std::string meshdir, assetdir;
  std::string inertiafromgeom = "auto";
  double group_min = 0, group_max = 5;  // inertiagrouprange
  bool exact_mesh_inertia = false;       // exactmeshinertia
};

/// Attribute name → value of one element kind in one default class.
using MjcfAttributes = std::map<std::string, std::string, std::less<>>;

/// <default> classes: class name → attributes, per element kind ("main" is the top class;
/// a nested class starts from its parent's attributes).
struct MjcfDefaults {
  std::map<std::string, MjcfAttributes, std::less<>> geom, mesh, joint;
};

/// The <compiler> settings (the last of repeated ones wins). @throws rigid::Error at the
/// element for a setting with an unknown value or one that rescales every inertia.
MjcfCompiler read_mjcf_compiler(const MjcfDocument& doc);

/// Every <default> class of the document. @throws rigid::Error for a nested class without name.
MjcfDefaults read_mjcf_defaults(const MjcfDocument& doc);

/// The rotation (parent ← element) that an element's own orientation attribute states (quat,
/// axisangle, euler, xyaxes or zaxis, at most one, with <compiler angle eulerseq>, MuJoCo's
/// rules), or nullopt if it has none. @throws GeometryProblem for a bad one.
std::optional<Eigen::Matrix3d> mjcf_orientation(const tinyxml2::XMLElement* e,
                                                const MjcfCompiler& compiler);

/// MJCF bodies of the document rooted at <mujoco>, in document order, each measured with
/// MuJoCo's compiler rules. @throws rigid::Error for problems of the whole document
/// (<include>, compiler settings that rescale every body).
std::vector<LinkGeometry> mjcf_links(const tinyxml2::XMLElement* root, const std::string& source);

/// mjcf_links on a document whose <include>s are followed.
std::vector<LinkGeometry> mjcf_links(const MjcfDocument& doc);

}  // namespace rigid::io::detail
