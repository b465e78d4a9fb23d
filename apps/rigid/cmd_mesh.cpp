#include "cmd_mesh.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>

#include <fmt/format.h>

#include "rigid/common/error.hpp"
#include "rigid/mesh.hpp"

namespace rigid::cli {
namespace {

void warn(const std::string& s) {
  std::fputs(fmt::format("rigid: warning: {}\n", s).c_str(), stderr);
}

}  // namespace

bool is_mesh_file(const std::string& path) {
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos) return false;
  std::string e = path.substr(dot + 1);
  std::transform(e.begin(), e.end(), e.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e == "stl" || e == "obj" || e == "ply" || e == "off";
}

void run_mesh_check(const MeshCheckOptions& opts) {
  mesh::TriangleMesh m = mesh::read_mesh(opts.file, mesh::unit_scale(opts.units));
  mesh::RepairOptions ro;
  ro.weld_tolerance = opts.weld_tolerance;
  const mesh::RepairReport rep = mesh::repair_mesh(m, ro);
  const auto box = m.bounding_box();
  std::string out = fmt::format("{}\n", opts.file);
  out += fmt::format("bounding box: ({:.6g}, {:.6g}, {:.6g}) to ({:.6g}, {:.6g}, {:.6g}) m\n",
                     box[0].x(), box[0].y(), box[0].z(), box[1].x(), box[1].y(), box[1].z());
  out += mesh::describe(rep);
  for (const auto& w : rep.warnings) out += fmt::format("warning: {}\n", w);
  std::string problem;
  if (!rep.closed()) {
    problem = fmt::format("the mesh is not closed ({} boundary edges, {} non-manifold edges): "
                          "its volume is undefined; use `rigid inertia {} --shell` for a thin "
                          "shell, or close the holes",
                          rep.boundary_edges, rep.non_manifold_edges, opts.file);
  } else {
    const double v = mesh::volume_moments(m).measure;
    out += fmt::format("volume: {:.9g} m³, area: {:.9g} m²\n", v,
                       mesh::surface_moments(m).measure);
    if (!(v > 0)) problem = fmt::format("the enclosed volume is {} m³: expected positive", v);
    const double size = m.bounding_box_diagonal();
    if (size > 100.0) {
      out += fmt::format("warning: the mesh is {:.4g} m across: if the file is in millimetres, "
                         "use --units mm\n",
                         size);
    }
  }
  out += problem.empty() ? "mass properties: trustworthy as a solid\n"
                         : "mass properties: NOT trustworthy as a solid\n";
  std::fputs(out.c_str(), stdout);
  std::fflush(stdout);
  if (!problem.empty()) RIGID_THROW("{}: {}", opts.file, problem);
}

void run_inertia_mesh(const std::string& file, const MeshInertiaOptions& opts,
                      const InertiaOutputOptions& out) {
  mesh::TriangleMesh m = mesh::read_mesh(file, mesh::unit_scale(opts.units));
  const mesh::RepairReport rep = mesh::repair_mesh(m);
  for (const auto& w : rep.warnings) warn(fmt::format("{}: {}", file, w));
  const auto res = mesh::mesh_mass_properties(
      m, mesh::MassSpec{opts.mass, opts.density, opts.shell, opts.thickness});
  for (const auto& w : res.warnings) warn(fmt::format("{}: {}", file, w));
  emit_inertia(res.properties, out);
}

}  // namespace rigid::cli
