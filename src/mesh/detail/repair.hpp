#pragma once
// repair_mesh for a mesh whose vertices are known to be distinct (private to the mesh module).

#include "rigid/mesh/repair.hpp"

namespace rigid::mesh::detail {

/// repair_mesh(mesh, options); with `vertices_distinct` (no two vertices have bitwise equal
/// coordinates, −0 = +0, as the binary STL reader guarantees) the exact weld, which would
/// find nothing to merge and return the mesh unchanged, is skipped. Same mesh and report.
RepairReport repair_mesh(TriangleMesh& mesh, const RepairOptions& options, bool vertices_distinct);

}  // namespace rigid::mesh::detail
