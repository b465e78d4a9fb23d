#pragma once

#include <string>

#include "rigid/mesh/mesh_mass.hpp"
#include "rigid/mesh/repair.hpp"

namespace rigid::mesh {

/// What mesh_mass_from_file found: the repair report and the mass properties.
struct MeshFileMass {
  RepairReport repair;  ///< of the mesh as read (its warnings are the caller's to show)
  MeshMassResult mass;
};

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

}  // namespace rigid::mesh
