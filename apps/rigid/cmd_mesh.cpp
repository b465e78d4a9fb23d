#include "cmd_mesh.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <optional>

#include <fmt/format.h>

#include "rigid/common/error.hpp"
#include "rigid/mesh.hpp"

namespace rigid::cli {
namespace {

void warn(const std::string& s) {
  std::fputs(fmt::format("rigid: warning: {}\n", s).c_str(), stderr);
}

// One line on what fill_holes did.
std::string describe_fill(const mesh::HoleFillReport& f) {
  std::string s = fmt::format("filled {} hole{} ({} triangles added, patch area {:.9g} m²):",
                              f.holes.size(), f.holes.size() == 1 ? "" : "s",
                              f.triangles_added, f.area);
  for (const auto& h : f.holes) s += fmt::format(" {} edges/{:.6g} m²;", h.boundary_edges, h.area);
  s.pop_back();
  return s;
}

// Repairs `m`; with `fill` and holes present, closes the simple holes and repairs again
// (orienting the now closed components).
struct RepairAndFill {
  mesh::RepairReport first;                  ///< of the mesh as read
  std::optional<mesh::HoleFillReport> fill;  ///< what fill_holes added, if it ran
  std::optional<mesh::RepairReport> after;   ///< of the filled mesh
  [[nodiscard]] const mesh::RepairReport& final_report() const { return after ? *after : first; }
};

RepairAndFill repair_and_fill(mesh::TriangleMesh& m, const mesh::RepairOptions& ro, bool fill) {
  RepairAndFill r{mesh::repair_mesh(m, ro), std::nullopt, std::nullopt};
  if (fill && r.first.boundary_edges > 0) {
    r.fill = mesh::fill_holes(m);
    r.after = mesh::repair_mesh(m, ro);
  }
  return r;
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
  const RepairAndFill rf = repair_and_fill(m, ro, opts.fill_holes);
  const mesh::RepairReport& rep = rf.final_report();
  const auto box = m.bounding_box();
  std::string out = fmt::format("{}\n", opts.file);
  out += fmt::format("bounding box: ({:.6g}, {:.6g}, {:.6g}) to ({:.6g}, {:.6g}, {:.6g}) m\n",
                     box[0].x(), box[0].y(), box[0].z(), box[1].x(), box[1].y(), box[1].z());
  out += mesh::describe(rf.first);
  if (rf.fill) {
    out += describe_fill(*rf.fill) + "\nafter filling:\n" + mesh::describe(*rf.after);
  }
  for (const auto& w : rep.warnings) out += fmt::format("warning: {}\n", w);
  std::string problem;
  if (!rep.closed()) {
    problem = fmt::format("the mesh is not closed ({} boundary edges, {} non-manifold edges): "
                          "its volume is undefined; use `rigid inertia {} --shell` for a thin "
                          "shell, or --fill-holes to close simple holes",
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
  const mesh::MassSpec spec{opts.mass, opts.density, opts.shell, opts.thickness};
  const double scale = mesh::unit_scale(opts.units);
  if (!opts.fill_holes) {  // read, repair and integrate without repeated work
    const mesh::MeshFileMass r = mesh::mesh_mass_from_file(file, scale, spec);
    for (const auto& w : r.repair.warnings) warn(fmt::format("{}: {}", file, w));
    for (const auto& w : r.mass.warnings) warn(fmt::format("{}: {}", file, w));
    emit_inertia(r.mass.properties, out);
    return;
  }
  mesh::TriangleMesh m = mesh::read_mesh(file, scale);
  const RepairAndFill rf = repair_and_fill(m, {}, opts.fill_holes);
  if (rf.fill) {
    for (const auto& w : rf.first.warnings) {  // what the filled mesh no longer shows
      if (w.find("the mesh is open") == std::string::npos) warn(fmt::format("{}: {}", file, w));
    }
    warn(fmt::format("{}: {}", file, describe_fill(*rf.fill)));
  }
  for (const auto& w : rf.final_report().warnings) warn(fmt::format("{}: {}", file, w));
  const auto res = mesh::mesh_mass_properties(m, spec, rf.final_report());
  for (const auto& w : res.warnings) warn(fmt::format("{}: {}", file, w));
  emit_inertia(res.properties, out);
}

}  // namespace rigid::cli
