#pragma once

#include <optional>
#include <string>

#include "cmd_inertia.hpp"

namespace rigid::cli {

/// Options of `rigid mesh check FILE`.
struct MeshCheckOptions {
  std::string file;
  std::string units = "m";        ///< m, cm, mm or in: length of one file unit
  double weld_tolerance = 1e-7;   ///< relative to the bounding-box diagonal
  bool fill_holes = false;        ///< close simple holes (mesh::fill_holes) before judging
};

/// `rigid mesh check FILE`: prints what is wrong with the mesh and whether its solid mass
/// properties can be trusted; throws rigid::Error (exit 1) when they cannot.
void run_mesh_check(const MeshCheckOptions& opts);

/// Mesh options of `rigid inertia FILE`.
struct MeshInertiaOptions {
  std::optional<double> mass;       ///< kg
  std::optional<double> density;    ///< kg/m³: a solid's, or a shell's material (with thickness)
  std::optional<double> areal_density;  ///< kg/m²: a shell's mass per unit area (implies shell)
  std::string units = "m";          ///< m, cm, mm or in
  bool shell = false;               ///< thin shell instead of a solid
  std::optional<double> thickness;  ///< m, shell only
  bool fill_holes = false;          ///< close simple holes (mesh::fill_holes) first
  std::string tolerance;            ///< "vertices=±0.05mm,density=±2%": values ± 1σ
  /// ρ(x, y, z) in kg/m³ (x, y, z in m in the mesh's frame, after --units) over the closed
  /// mesh, instead of an amount (scene::integrate_density_field_over_mesh)
  std::string density_field{};
};

/// True when `path` has a mesh extension (.stl, .obj, .ply, .off, any case).
[[nodiscard]] bool is_mesh_file(const std::string& path);

/// `rigid inertia FILE ...` for a mesh: read, repair, (fill holes, repair again,) mass
/// properties, then emit_inertia. Repairs, filled holes and plausibility problems are printed
/// to standard error as warnings.
void run_inertia_mesh(const std::string& file, const MeshInertiaOptions& mesh,
                      const InertiaOutputOptions& out);

}  // namespace rigid::cli
