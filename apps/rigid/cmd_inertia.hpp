#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rigid/mass/mass_properties.hpp"
#include "rigid/mass/placement.hpp"
#include "rigid/mass/primitive_table.hpp"
#include "rigid/mass/uncertainty.hpp"

namespace rigid::cli {

/// How `rigid inertia` prints mass properties; shared by every source of mass properties
/// (primitives here, mesh files, ...).
struct InertiaOutputOptions {
  std::string about = "com";    ///< "com", "origin" or "x,y,z" (m): point the inertia is about
  std::string frame = "body";   ///< "body" or "principal"
  std::string format = "text";  ///< "text", "json", "urdf", "mjcf" or "sdf"
  std::string name = "body";    ///< link/body name in URDF/MJCF/SDF
  std::string output;           ///< file to write (atomically); empty: standard output
  /// Set by the source, not by a flag: the rotation R_LI of a principal frame known exactly (a
  /// placed primitive's own frame), written by urdf/mjcf/sdf with --frame principal.
  std::optional<Eigen::Matrix3d> inertial_frame;
};

/// The text of `mp` in the requested format (see InertiaOutputOptions).
/// URDF/MJCF/SDF state the inertia about the COM and the COM's position from the link origin,
/// so the inertia about any point follows from the file: --about com or origin writes the body
/// as it is; --about x,y,z writes it with the link origin at that point (COM at c − p), so the
/// file's inertia about its link origin is the tensor about p.
/// @throws rigid::Error for an unknown format/frame, a malformed --about, or --frame principal
/// with --about a point in urdf/mjcf/sdf (those formats give the principal axes about the COM
/// only, not those of the tensor about the point).
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
  /// ρ(x, y, z) in kg/m³ with x, y, z in m in the shape's own frame (solid box, cylinder,
  /// sphere); empty: a constant density or a mass
  std::string density_field;
  InertiaOutputOptions output;
  // placement in the link frame (rigid::mass::Placement); empty: not given
  std::string axis;    ///< x, y, z, -x, -y, -z or "vx,vy,vz"
  std::string origin;  ///< "x,y,z" (m)
  std::string rpy;     ///< "roll,pitch,yaw" (rad)
  /// "dims=±0.1mm,density=±2%,..." (rigid::mass::parse_tolerances); empty: none
  std::string tolerance;
};

/// `rigid inertia <primitive> ...`.
void run_inertia_primitive(const InertiaPrimitiveOptions& opts);

/// A primitive in the link frame, and the rotation R_LS of its own frame when it was placed.
struct PlacedPrimitive {
  MassProperties mp;
  std::optional<Eigen::Matrix3d> R_LS;
};

/// The primitive `own` (in its own frame) placed by --axis, --rpy and --origin
/// (rigid::mass::Placement); unchanged, with no R_LS, when none is given.
/// @throws rigid::Error for a malformed or zero axis, origin or rpy.
/// The placement of --axis, --rpy, --origin. @throws rigid::Error for a malformed one.
[[nodiscard]] mass::Placement parse_placement(const InertiaPrimitiveOptions& opts);

/// `rigid inertia <primitive> ... --tolerance ...`: values ± 1σ (text or json).
void emit_uncertain_primitive(const mass::PrimitiveEntry& e, const mass::PrimitiveArguments& args,
                              const InertiaPrimitiveOptions& opts);

/// Refuses --tolerance with an output that has no place for σ (urdf, ..., --frame principal).
void require_uncertainty_output(const InertiaOutputOptions& out);

/// mass::parse_tolerances of --tolerance; its refusal as a usage error (exit status 2).
[[nodiscard]] std::vector<mass::Tolerance> parse_tolerance_option(const std::string& text);

/// The --about point of a propagated tensor: nullopt for the COM.
[[nodiscard]] std::optional<Eigen::Vector3d> uncertainty_about(const InertiaOutputOptions& out);

/// Prints mass, COM and inertia (about p) each ± its 1σ (rigid::mass::mass_properties_vector
/// order), in text or JSON, naming the uncertain inputs.
void emit_uncertain(const Eigen::Matrix<double, 10, 1>& value, const Eigen::Matrix<double, 10, 1>& sigma,
                    const std::vector<std::string>& inputs, const Eigen::Vector3d& p,
                    const InertiaOutputOptions& out);

[[nodiscard]] PlacedPrimitive place_primitive(const MassProperties& own, const InertiaPrimitiveOptions& opts);

/// Options of `rigid inertia SOURCE` when SOURCE is not a primitive or `check`.
struct InertiaSourceOptions {
  std::string source;
  InertiaOutputOptions output;
  std::optional<double> mass;       ///< kg (mesh files)
  std::optional<double> density;    ///< kg/m³: a solid's, or a shell's material (with thickness)
  std::optional<double> areal_density;  ///< kg/m²: a shell's mass per unit area (implies shell)
  std::string density_field;        ///< ρ(x, y, z) in kg/m³ over a closed mesh (m, its frame)
  std::string units = "m";          ///< mesh file unit: m, cm, mm or in
  bool shell = false;               ///< mesh as a thin shell
  std::optional<double> thickness;  ///< m, with shell
  bool fill_holes = false;          ///< mesh: close simple holes first
  std::string tolerance;            ///< mesh: "vertices=±0.05mm,density=±2%"
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
