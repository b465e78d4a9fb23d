#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rigid/mass/mass_properties.hpp"
#include "rigid/mesh/repair.hpp"
#include "rigid/mesh/triangle_mesh.hpp"

namespace rigid::mesh {

/// Integrals of a mesh about a reference point R (p_OR_M): the zeroth, first and second
/// moments ∫1, ∫r, ∫r rᵀ with r = p − p_OR, over the enclosed volume (solid) or the surface
/// (shell). Exact for the polyhedron up to round-off.
struct MeshMoments {
  Eigen::Vector3d p_OR_M = Eigen::Vector3d::Zero();  ///< reference point (m)
  double measure = 0.0;                              ///< volume (m³) or area (m²)
  Eigen::Vector3d first = Eigen::Vector3d::Zero();   ///< ∫ r (m⁴ or m³)
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();  ///< ∫ r rᵀ (m⁵ or m⁴)
};

/// Volume moments by the divergence theorem: each triangle (a, b, c) with the reference
/// point spans a signed tetrahedron of volume det[a b c]/6, first moment det·(a+b+c)/24 and
/// second moment det/120 · (a aᵀ + b bᵀ + c cᵀ + s sᵀ), s = a + b + c [Tonon2005, eq. 2–4].
/// The reference point is the bounding-box centre unless given, so that a mesh far from the
/// origin keeps its precision.
[[nodiscard]] MeshMoments volume_moments(const TriangleMesh& mesh,
                                         std::optional<Eigen::Vector3d> p_OR_M = std::nullopt);

/// Surface moments: area A = |(b−a)×(c−a)|/2, first moment A·s/3, second moment
/// A/12 · (a aᵀ + b bᵀ + c cᵀ + s sᵀ) per triangle.
[[nodiscard]] MeshMoments surface_moments(const TriangleMesh& mesh,
                                          std::optional<Eigen::Vector3d> p_OR_M = std::nullopt);

/// How the body's mass is given: exactly one of mass (kg) and density (kg/m³ for a solid,
/// kg/m² for a shell; with thickness, kg/m³ of the shell material).
struct MassSpec {
  std::optional<double> mass;
  std::optional<double> density;
  bool shell = false;
  std::optional<double> thickness;  ///< m, shell only: surface density = thickness × density
};

/// Mass properties and the plausibility warnings that go with them.
struct MeshMassResult {
  MassProperties properties;
  double measure = 0.0;  ///< volume (m³) or area (m²)
  std::vector<std::string> warnings;
  std::array<Eigen::Vector3d, 2> bounding_box;  ///< corners (min, max) of the mesh (m)
};

/// A part longer than this (m) is taken for a file in millimetres read as metres.
inline constexpr double kMaxPartSize = 10.0;
/// A part shorter than this (m) is taken for a file in metres read in a smaller unit.
inline constexpr double kMinPartSize = 1e-3;

/// Units plausibility of a part's bounding box (corners in m): a warning naming the `units`
/// setting when its longest side is more than kMaxPartSize (a 20 × 30 × 10 mm part read as
/// metres) or less than kMinPartSize; nothing for parts from 1 mm to 10 m.
[[nodiscard]] std::vector<std::string> size_warnings(const std::array<Eigen::Vector3d, 2>& box);

/// Mass properties of a repaired mesh (see repair_mesh). A solid must be closed and
/// consistently oriented (every directed edge once, its reverse once): otherwise
/// rigid::Error counts the boundary, non-manifold or misoriented edges and points to
/// repair_mesh and to the `shell` and `fill_holes` settings (rigid::setting, worded by each
/// front end), so a mesh that skipped repair never gives a wrong volume silently.
/// Warns when the implied size, mass or density is implausible (size_warnings; a mass over
/// 1000 t; a density outside 0.5–30 000 kg/m³: e.g. a part in millimetres read as metres,
/// 10⁹ times the mass), naming the `units` setting; for a shell without a thickness, when the
/// areal density (given or implied) is outside 0.01–1000 kg/m², e.g. a volume density in kg/m³
/// given without the thickness.
/// @throws rigid::Error for a bad MassSpec, an open or misoriented solid or a zero
/// volume/area.
[[nodiscard]] MeshMassResult mesh_mass_properties(const TriangleMesh& mesh, const MassSpec& spec);

/// The same for a mesh that `repaired`, the report of repair_mesh on it, describes (the mesh
/// unchanged since): closedness is taken from the report's boundary and non-manifold edge
/// counts instead of matching the edges again. Bitwise the same result as the overload
/// without the report when the report is the mesh's.
/// @throws rigid::Error as mesh_mass_properties(mesh, spec).
[[nodiscard]] MeshMassResult mesh_mass_properties(const TriangleMesh& mesh, const MassSpec& spec,
                                                  const RepairReport& repaired);

}  // namespace rigid::mesh
