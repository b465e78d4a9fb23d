#include "rigid/mesh/mass_from_file.hpp"

#include <utility>

#include <fmt/format.h>

#include "detail/read_mesh.hpp"
#include "detail/repair.hpp"
#include "rigid/common/wording.hpp"

namespace rigid::mesh {

PreparedMesh prepare_mesh_file(const std::string& path, double scale, const RepairOptions& options,
                               bool fill) {
  detail::ReadResult read = detail::read_mesh(path, scale);
  RepairReport first = detail::repair_mesh(read.mesh, options, read.vertices_distinct);
  if (!fill || first.boundary_edges == 0) {
    return {std::move(read.mesh), std::move(first), std::nullopt, std::nullopt};
  }
  HoleFillReport filled = fill_holes(read.mesh);
  RepairReport after = repair_mesh(read.mesh, options);
  return {std::move(read.mesh), std::move(after), std::move(filled), std::move(first)};
}

MeshFileMass measure_prepared_mesh(const PreparedMesh& prepared, const MassSpec& spec) {
  MeshMassResult mass = mesh_mass_properties(prepared.mesh, spec, prepared.repair);
  return {prepared.repair, prepared.filled, prepared.before_fill, std::move(mass), spec.shell};
}

MeshFileMass mesh_mass_from_file(const std::string& path, double scale, const MassSpec& spec,
                                 const RepairOptions& options) {
  return measure_prepared_mesh(prepare_mesh_file(path, scale, options, false), spec);
}

MeshFileMass mesh_mass_from_file(const std::string& path, double scale, const MassSpec& spec,
                                 const RepairOptions& options, bool fill) {
  return measure_prepared_mesh(prepare_mesh_file(path, scale, options, fill), spec);
}

std::vector<std::string> MeshFileMass::warnings() const {
  // "the mesh is open … (use `shell = true` …)" speaks of a solid: a shell may be open, and the
  // remedy it names is the setting that was given
  auto speaks_of_a_solid = [](const std::string& w) { return w.starts_with("the mesh is open"); };
  std::vector<std::string> out;
  if (filled) {
    for (const auto& w : before_fill->warnings) {  // what the filled mesh no longer shows
      if (!speaks_of_a_solid(w)) out.push_back(w);
    }
    out.push_back(describe(*filled));
  }
  for (const auto& w : repair.warnings) {
    if (!(shell && speaks_of_a_solid(w))) out.push_back(w);
  }
  out.insert(out.end(), mass.warnings.begin(), mass.warnings.end());
  return out;
}

std::string describe(const HoleFillReport& f) {
  std::string s = fmt::format("filled {} ({} added, patch area {:.9g} m²):", counted(f.holes.size(), "hole"),
                              counted(f.triangles_added, "triangle"), f.area);
  for (const auto& h : f.holes) s += fmt::format(" {}/{:.6g} m²;", counted(h.boundary_edges, "edge"), h.area);
  s.pop_back();
  return s;
}

}  // namespace rigid::mesh
