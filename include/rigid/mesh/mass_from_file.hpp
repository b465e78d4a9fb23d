#pragma once

#include <optional>
#include <string>
#include <vector>

#include "rigid/mesh/fill_holes.hpp"
#include "rigid/mesh/mesh_mass.hpp"
#include "rigid/mesh/repair.hpp"

namespace rigid::mesh {

/// What mesh_mass_from_file found: the repair report, what hole filling did, the mass
/// properties.
struct MeshFileMass {
  RepairReport repair;  ///< of the mesh that was measured (after filling, if it ran)
  /// With fill_holes and an open mesh: what filling added, and the report of the mesh as read.
  std::optional<HoleFillReport> filled;
  std::optional<RepairReport> before_fill;
  MeshMassResult mass;
  bool shell = false;  ///< measured as a thin shell (MassSpec::shell)
  /// Every warning for the user, in order: the repair of the mesh as read (without "the mesh
  /// is open" when filling closed it, or for a shell, which may be open), what filling did, the
  /// repair after filling, the plausibility of the result.
  [[nodiscard]] std::vector<std::string> warnings() const;
};

/// A mesh file read and repaired (and, with fill_holes, filled) once, so that it can be measured
/// for any number of MassSpecs without reading the file again (a sweep over a mesh body's
/// density or mass). The mesh is what mesh_mass_from_file measures, bit for bit.
struct PreparedMesh {
  TriangleMesh mesh;     ///< after repair (and filling), in metres
  RepairReport repair;   ///< of `mesh`
  std::optional<HoleFillReport> filled;      ///< as MeshFileMass::filled
  std::optional<RepairReport> before_fill;   ///< as MeshFileMass::before_fill
};

/// read_mesh(path, scale) and repair_mesh (then, with `fill_holes` and an open mesh,
/// fill_holes and repair again): the first half of mesh_mass_from_file.
/// @throws rigid::Error as read_mesh and fill_holes do.
[[nodiscard]] PreparedMesh prepare_mesh_file(const std::string& path, double scale,
                                             const RepairOptions& options = {},
                                             bool fill_holes = false);

/// The second half: the mass properties of a prepared mesh for `spec`, with its reports; the
/// same result, bit for bit, as mesh_mass_from_file with the same arguments.
/// @throws rigid::Error as mesh_mass_properties does.
[[nodiscard]] MeshFileMass measure_prepared_mesh(const PreparedMesh& prepared, const MassSpec& spec);

/// One line on what fill_holes did: holes, triangles added, patch areas.
[[nodiscard]] std::string describe(const HoleFillReport& filled);

/// Mass properties of a mesh file: read_mesh(path, scale), repair_mesh(mesh, options),
/// mesh_mass_properties(mesh, spec), with the same mesh, report and result bit for bit, and
/// without their repeated work: a binary STL's vertices come out of the reader already
/// distinct (it shares float32-identical copies), so the exact weld is skipped, and
/// closedness is taken from the edge table repair built.
/// @param path mesh file (see read_mesh); scale metres per file unit (see unit_scale).
/// @throws rigid::Error as read_mesh and mesh_mass_properties do (unreadable or malformed
/// file, bad MassSpec, an open mesh as a solid, a zero volume or area).
[[nodiscard]] MeshFileMass mesh_mass_from_file(const std::string& path, double scale,
                                               const MassSpec& spec,
                                               const RepairOptions& options = {});

/// The same with `fill_holes`: when the repaired mesh is open, its simple holes are closed
/// (rigid::mesh::fill_holes), it is repaired again (orienting the closed components) and then
/// measured. Without fill_holes, or for a closed mesh, the result is the overload's above.
/// @throws rigid::Error as above, and as fill_holes does for a hole that is not simple.
[[nodiscard]] MeshFileMass mesh_mass_from_file(const std::string& path, double scale,
                                               const MassSpec& spec, const RepairOptions& options,
                                               bool fill_holes);

}  // namespace rigid::mesh
