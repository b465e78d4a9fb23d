#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "rigid/mass/mass_properties.hpp"

namespace rigid::cli {

/// How `rigid inertia` prints mass properties; shared by every source of mass properties
/// (primitives here, mesh files, ...).
struct InertiaOutputOptions {
  std::string about = "com";    ///< "com", "origin" or "x,y,z" (m): point the inertia is about
  std::string frame = "body";   ///< "body" or "principal"
  std::string format = "text";  ///< "text", "json", "urdf", "mjcf" or "sdf"
  std::string name = "body";    ///< link/body name in URDF/MJCF/SDF
  std::string output;           ///< file to write (atomically); empty: standard output
};

/// The text of `mp` in the requested format (see InertiaOutputOptions).
/// @throws rigid::Error for an unknown format/frame, a malformed --about, or --about other
/// than com with urdf/mjcf/sdf (those formats store the inertia about the COM).
[[nodiscard]] std::string format_inertia(const MassProperties& mp, const InertiaOutputOptions& out);

/// Writes format_inertia(mp, out) to out.output or standard output.
void emit_inertia(const MassProperties& mp, const InertiaOutputOptions& out);

/// A name of the primitive catalogue (rigid::mass::primitive_table) as the command line spells
/// it: '_' becomes '-' ("solid_cylinder" → "solid-cylinder", "inner_radius" → "inner-radius").
[[nodiscard]] std::string cli_name(const std::string& catalogue_name);

/// Options of `rigid inertia <primitive>`; the subcommands, their aliases and their size
/// options are the catalogue's.
struct InertiaPrimitiveOptions {
  std::string primitive;                      ///< the catalogue's canonical name
  std::map<std::string, double> sizes;        ///< canonical size name → value (m)
  std::map<std::string, std::string> points;  ///< point name → "x,y,z" (m)
  std::optional<double> mass;           ///< kg
  std::optional<double> density;        ///< kg/m³ (kg/m² shells and plates, kg/m rods)
  InertiaOutputOptions output;
};

/// `rigid inertia <primitive> ...`.
void run_inertia_primitive(const InertiaPrimitiveOptions& opts);

/// Options of `rigid inertia SOURCE` when SOURCE is not a primitive or `check`.
struct InertiaSourceOptions {
  std::string source;
  InertiaOutputOptions output;
  std::optional<double> mass;       ///< kg (mesh files)
  std::optional<double> density;    ///< kg/m³ solid, kg/m² shell (kg/m³ with thickness)
  std::string units = "m";          ///< mesh file unit: m, cm, mm or in
  bool shell = false;               ///< mesh as a thin shell
  std::optional<double> thickness;  ///< m, with shell
  bool fill_holes = false;          ///< mesh: close simple holes first
};

/// `rigid inertia SOURCE`: SOURCE names no primitive; reports the choices.
void run_inertia_source(const InertiaSourceOptions& opts);

/// Options of `rigid inertia check FILE`.
struct InertiaCheckOptions {
  std::string file;
};

/// `rigid inertia check FILE`: lists every invalid inertial (file:line, link/body, reason);
/// throws rigid::Error (non-zero exit) when any is invalid.
void run_inertia_check(const InertiaCheckOptions& opts);

}  // namespace rigid::cli
