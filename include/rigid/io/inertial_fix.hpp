#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "rigid/io/inertial_xml.hpp"
#include "rigid/mass/mass_properties.hpp"

/// Inertials recomputed from geometry: a URDF link's or SDF link's <collision> (or <visual>)
/// shapes, an MJCF body's geoms (with MuJoCo's compiler rules: <default> classes, childclass,
/// fromto, density and mass attributes, inertiafromgeom, meshdir). The document is written
/// back with only the <inertial> elements changed (one inserted where a link has none, with
/// the indentation of its siblings); every other byte is kept. docs/robot-models.md has the
/// rules.
namespace rigid::io {

/// Which geometry of a URDF/SDF link is measured (MJCF bodies have geoms only).
enum class GeometrySource { kCollision, kVisual };

/// Options of fix_inertials.
struct InertialFixOptions {
  /// Density of URDF/SDF geometry (kg/m³). nullopt: 1000 kg/m³ (water), with a warning that
  /// it was assumed. MJCF ignores it: each geom has its own density (default 1000) or mass.
  std::optional<double> density{};
  /// Keep each link's stated (valid, positive) mass and distribute it by the geometry.
  bool keep_mass = false;
  GeometrySource from = GeometrySource::kCollision;
  /// Only these links/bodies (empty: all). A name that matches nothing is refused.
  std::vector<std::string> only{};
  /// `package://NAME/...` resolves to DIR/... for each (NAME, DIR).
  std::vector<std::pair<std::string, std::string>> package_paths{};
};

/// What happened to one link/body.
struct FixedInertial {
  std::string name;
  /// The file that holds the link/body element: InertialFixResult::source, or an MJCF file it
  /// <include>s.
  std::string file;
  int line = 0;  ///< of the link/body element, in `file`
  /// "missing", "invalid", "placeholder", "implausible density", "recomputed" (the old one was
  /// plausible; the geometry's replaces it), "kept" (left as it was: no geometry, or an MJCF
  /// inertial the compiler uses as it is).
  std::string reason;
  std::string detail;  ///< why the reason applies (the check's text, the density ...)
  /// The old inertial as read (mass, COM, inertia about the COM in the link frame), if any.
  std::optional<InertialEntry> old;
  /// The new one (nullopt when kept or not fixable).
  std::optional<MassProperties> fixed;
  double volume = 0;                  ///< of the geometry (m³), 0 if none
  std::vector<std::string> warnings;  ///< per link: assumed density, units, ...
  /// Why it could not be fixed (missing mesh file, unknown geometry, ...); non-empty makes
  /// fix_inertials' result unusable (InertialFixResult::ok() is false).
  std::vector<std::string> errors;
};

struct InertialFixResult {
  std::string source;  ///< the file name given to fix_inertials
  InertialFormat format = InertialFormat::urdf;
  /// The rewritten document (only meaningful when ok()). An MJCF model's <include>d files are
  /// written into it (each <include> element replaced by the included file's elements, with
  /// their inertials fixed): one self-contained file; the included files are not changed.
  std::string text;
  std::vector<FixedInertial> links;
  std::vector<std::string> warnings;  ///< for the whole file (assumed density, ...)
  [[nodiscard]] bool ok() const;
  /// Every error of every link, one "source:line: link 'x': ..." line each.
  [[nodiscard]] std::vector<std::string> errors() const;
  /// @throws rigid::Error listing errors() unless ok(): what every front end says before it
  /// writes nothing.
  void require_ok() const;
};

/// "NAME=DIR" (the `package_path` setting) as (NAME, DIR).
/// @throws rigid::Error if either side is empty or there is no '='.
[[nodiscard]] std::pair<std::string, std::string> parse_package_path(const std::string& text);

/// Recomputes the inertials of the document `xml` (URDF, SDF or MJCF, detected from the root)
/// from its geometry. Relative mesh paths resolve against the directory of `source`, and so do
/// MJCF <include file="..."> elements (MuJoCo's rule), which are followed: their bodies are
/// fixed too, and the rewritten text holds their elements in place of the include.
/// Problems of one link are collected in its `errors` (every link is tried); problems of the
/// whole document throw.
/// @throws rigid::Error "source:line: ..." for malformed XML, an unknown root, an <include>
/// that cannot be read (naming it), a name in options.only that names no link, or a bad option
/// (density not positive).
[[nodiscard]] InertialFixResult fix_inertials(const std::string& xml, const std::string& source,
                                              const InertialFixOptions& options = {});

/// fix_inertials on the contents of the file `path`. @throws rigid::Error if it does not exist,
/// is not a regular file (a directory, FIFO or device: refused before it is opened) or cannot
/// be read.
[[nodiscard]] InertialFixResult fix_inertials_file(const std::string& path,
                                                   const InertialFixOptions& options = {});

/// The table of old vs new per link (text, one row per link) or a JSON document.
[[nodiscard]] std::string fix_table_text(const InertialFixResult& result);
[[nodiscard]] std::string fix_table_json(const InertialFixResult& result);

}  // namespace rigid::io
