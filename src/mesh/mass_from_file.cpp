#include "rigid/mesh/mass_from_file.hpp"

#include <utility>

#include "detail/read_mesh.hpp"
#include "detail/repair.hpp"

namespace rigid::mesh {

MeshFileMass mesh_mass_from_file(const std::string& path, double scale, const MassSpec& spec,
                                 const RepairOptions& options) {
  detail::ReadResult read = detail::read_mesh(path, scale);
  RepairReport report = detail::repair_mesh(read.mesh, options, read.vertices_distinct);
  MeshMassResult mass = mesh_mass_properties(read.mesh, spec, report);
  return {std::move(report), std::move(mass)};
}

}  // namespace rigid::mesh
