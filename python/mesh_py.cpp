// rigid.mesh: triangle meshes from files or numpy arrays, repair, exact mass properties.
#include <fmt/format.h>

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "convert.hpp"
#include "rigid/mass/density.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/wording.hpp"
#include "rigid/io/atomic_file.hpp"
#include "rigid/mesh.hpp"

namespace py = pybind11;
namespace cv = rigid::python::convert;

namespace {
// the library's remedies (`shell = true`) in Python's terms (shell=True)
std::vector<std::string> worded(const std::vector<std::string>& messages) {
  std::vector<std::string> out;
  for (const auto& m : messages) out.push_back(rigid::word_for(rigid::Surface::kPython, m));
  return out;
}

// The library's remedy "run repair_mesh(mesh) first" in Python's terms: rigid.mesh.repair.
template <class F>
auto with_repair_worded(F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const rigid::Error& e) {
    std::string m = e.what();
    const std::string from = "repair_mesh(mesh)";
    for (std::size_t at = m.find(from); at != std::string::npos; at = m.find(from, at)) {
      m.replace(at, from.size(), "rigid.mesh.repair(mesh)");
      at += from.size();
    }
    throw rigid::Error(m);
  }
}
}  // namespace

namespace {

using rigid::mesh::TriangleMesh;

TriangleMesh from_arrays(const py::object& vertices, const py::object& triangles) {
  const char* f = "rigid.mesh.TriangleMesh";
  const Eigen::Matrix3Xd v = cv::points(vertices, {f, "vertices"});
  // vertex indices: integers only (a float array would be truncated silently)
  py::array a;
  try {
    a = py::module_::import("numpy").attr("asarray")(triangles);
  } catch (const py::error_already_set&) {
    throw rigid::Error(
        fmt::format("{}(): argument 'triangles' must be an integer array of shape (m, 3); "
                    "got a sequence that is not rectangular",
                    f));
  }
  const char kind = a.dtype().kind();
  if (a.ndim() == 0 && kind != 'i' && kind != 'u' && kind != 'f') {
    throw py::type_error(fmt::format(
        "{}(): argument 'triangles' must be an integer array of shape (m, 3); got {}", f,
        py::str(py::type::handle_of(triangles).attr("__name__")).cast<std::string>()));
  }
  // an empty list has dtype float64: no index to truncate
  if (kind != 'i' && kind != 'u' && !(a.size() == 0 && kind == 'f')) {
    throw rigid::Error(
        fmt::format("{}(): argument 'triangles' must hold integer vertex indices; got dtype {}", f,
                    py::str(a.dtype()).cast<std::string>()));
  }
  if (a.ndim() != 2 || a.shape(1) != 3) {
    std::string shape = "(";
    for (py::ssize_t k = 0; k < a.ndim(); ++k)
      shape += fmt::format("{}{}", k ? ", " : "", a.shape(k));
    shape += a.ndim() == 1 ? ",)" : ")";
    throw rigid::Error(
        fmt::format("{}(): argument 'triangles' must have shape (m, 3); got {}", f, shape));
  }
  const auto idx = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(a);
  TriangleMesh m;
  m.vertices.reserve(static_cast<std::size_t>(v.cols()));
  for (Eigen::Index i = 0; i < v.cols(); ++i) m.vertices.emplace_back(v.col(i));
  const auto ff = idx.unchecked<2>();
  for (py::ssize_t i = 0; i < ff.shape(0); ++i) {
    std::array<std::uint32_t, 3> t{};
    for (int k = 0; k < 3; ++k) {
      RIGID_REQUIRE(ff(i, k) >= 0 && ff(i, k) < static_cast<long long>(m.vertices.size()),
                    "triangle {} uses vertex {}: expected 0 to {}", i, ff(i, k),
                    static_cast<long long>(m.vertices.size()) - 1);
      t[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(ff(i, k));
    }
    m.triangles.push_back(t);
  }
  return m;
}

namespace rm = rigid::mesh;

// TriangleMesh.vertices: an (n, 3) float array (m).
py::array_t<double> vertices_array(const TriangleMesh& t) {
  py::array_t<double> a({static_cast<py::ssize_t>(t.vertices.size()), py::ssize_t{3}});
  auto w = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < t.vertices.size(); ++i)
    for (int k = 0; k < 3; ++k) w(static_cast<py::ssize_t>(i), k) = t.vertices[i][k];
  return a;
}

// TriangleMesh.triangles: an (m, 3) integer array of vertex indices.
py::array_t<long long> triangles_array(const TriangleMesh& t) {
  py::array_t<long long> a({static_cast<py::ssize_t>(t.triangles.size()), py::ssize_t{3}});
  auto w = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < t.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k)
      w(static_cast<py::ssize_t>(i), k) = t.triangles[i][static_cast<std::size_t>(k)];
  return a;
}

void bind_triangle_mesh(py::module_& mesh) {
  py::class_<TriangleMesh>(mesh, "TriangleMesh", "Indexed triangle mesh (vertices in m).")
      .def(py::init(&from_arrays), py::arg("vertices"), py::arg("triangles"),
           "A mesh from vertices (shape (n, 3), m, one vertex per row, any real dtype) and "
           "triangles (shape (m, 3), integer indices into the vertices; counter-clockwise seen "
           "from outside once oriented). Nothing is checked or repaired here: "
           "mass_properties refuses a mesh that is open or inconsistently wound.")
      .def_property_readonly("vertices", &vertices_array, "Vertex positions, an (n, 3) array (m).")
      .def_property_readonly("triangles", &triangles_array,
                             "Vertex indices of each triangle, an (m, 3) integer array.")
      .def(py::pickle(
          [](const TriangleMesh& t) { return py::make_tuple(vertices_array(t), triangles_array(t)); },
          [](const py::tuple& state) {
            if (state.size() != 2) {
              throw rigid::Error(fmt::format(
                  "rigid.mesh.TriangleMesh.__setstate__(): the state must be the tuple "
                  "(vertices, triangles) that __getstate__ returns; got {} values",
                  state.size()));
            }
            return from_arrays(state[0], state[1]);
          }))
      .def("__len__", &TriangleMesh::size)
      .def("__repr__",
           [](const TriangleMesh& t) {
             return fmt::format("TriangleMesh({} vertices, {} triangles)", t.vertices.size(),
                                t.triangles.size());
           })
      .def_property_readonly(
          "bounding_box",
          [](const TriangleMesh& t) {
            const auto b = t.bounding_box();
            return py::make_tuple(b[0], b[1]);
          },
          "(min corner, max corner) of the vertices (m); zeros when empty.")
      .def("scale", &TriangleMesh::scale, py::arg("factor"),
           "Multiplies every vertex by factor (in place; e.g. 1e-3 for millimetres).")
      .def(
          "translate",
          [](TriangleMesh& t, const py::object& d) {
            t.translate(cv::vector3(d, {"TriangleMesh.translate", "d_M"}));
          },
          py::arg("d_M"), "Moves every vertex by d_M (shape (3,), m; in place).")
      .def("reverse_winding", &TriangleMesh::reverse_winding,
           "Reverses the winding of every triangle (flips all normals; in place).");
}

// What count_edges, repair and fill_holes report.
void bind_mesh_reports(py::module_& mesh) {
  py::class_<rm::EdgeCounts>(mesh, "EdgeCounts", "Edges by how many triangles use them.")
      .def_readonly("boundary", &rm::EdgeCounts::boundary, "edges used by one triangle")
      .def_readonly("non_manifold", &rm::EdgeCounts::non_manifold, "edges used by three or more")
      .def_readonly("misoriented", &rm::EdgeCounts::misoriented,
                    "edges two triangles traverse in the same direction (inconsistent winding)")
      .def("__repr__", [](const rm::EdgeCounts& e) {
        return fmt::format("EdgeCounts(boundary={}, non_manifold={}, misoriented={})", e.boundary,
                           e.non_manifold, e.misoriented);
      });

  py::class_<rm::ComponentReport>(mesh, "ComponentReport",
                                  "One connected component of a repaired mesh.")
      .def_readonly("triangles", &rm::ComponentReport::triangles, "Triangles in the component.")
      .def_readonly("boundary_edges", &rm::ComponentReport::boundary_edges,
                    "Edges used by one triangle only (0 for a closed component).")
      .def_readonly("volume", &rm::ComponentReport::signed_volume,
                    "Signed volume after orientation (m³; meaningful when closed).")
      .def_readonly("area", &rm::ComponentReport::area, "Surface area (m²).")
      .def("__repr__", [](const rm::ComponentReport& c) {
        return fmt::format(
            "ComponentReport(triangles={}, boundary_edges={}, volume={} m³, area={} m²)",
            c.triangles, c.boundary_edges, c.signed_volume, c.area);
      });

  py::class_<rm::RepairReport>(mesh, "RepairReport",
                               "What rigid.mesh.repair found and changed; str() is the "
                               "text `rigid mesh check` prints.")
      .def_readonly("welded_vertices", &rm::RepairReport::welded_vertices,
                    "Vertices merged into another.")
      .def_readonly("degenerate_triangles", &rm::RepairReport::degenerate_triangles,
                    "Triangles removed: a repeated index or zero area.")
      .def_readonly("boundary_edges", &rm::RepairReport::boundary_edges,
                    "Edges used by exactly one triangle.")
      .def_readonly("non_manifold_edges", &rm::RepairReport::non_manifold_edges,
                    "Edges used by three or more triangles.")
      .def_readonly("reoriented_triangles", &rm::RepairReport::reoriented_triangles,
                    "Triangles flipped to agree with their neighbours.")
      .def_readonly("inverted_components", &rm::RepairReport::inverted_components,
                    "Closed components with negative volume, flipped outward.")
      .def_readonly("tolerance_weld", &rm::RepairReport::tolerance_weld,
                    "True if the tolerance weld ran (after the exact weld left open edges).")
      .def_readonly("components", &rm::RepairReport::components,
                    "One ComponentReport per connected component.")
      .def_property_readonly(
          "warnings", [](const rm::RepairReport& r) { return worded(r.warnings); },
          "One sentence per problem left (open edges, non-manifold edges, ...).")
      .def_property_readonly(
          "closed", &rm::RepairReport::closed,
          "True when the mesh bounds a solid: every edge shared by exactly two triangles.")
      .def("__str__", [](const rm::RepairReport& r) { return rm::describe(r); })
      .def("__repr__", [](const rm::RepairReport& r) {
        return fmt::format(
            "RepairReport(closed={}, components={}, welded_vertices={}, degenerate_triangles={}, "
            "boundary_edges={}, non_manifold_edges={}, reoriented_triangles={}, "
            "inverted_components={}, warnings={})",
            r.closed() ? "True" : "False", r.components.size(), r.welded_vertices,
            r.degenerate_triangles, r.boundary_edges, r.non_manifold_edges, r.reoriented_triangles,
            r.inverted_components, r.warnings.size());
      });

  py::class_<rm::FilledHole>(mesh, "FilledHole", "One hole closed by rigid.mesh.fill_holes.")
      .def_readonly("boundary_edges", &rm::FilledHole::boundary_edges,
                    "Edges of the hole's border loop.")
      .def_readonly("area", &rm::FilledHole::area, "Area of the patch that closes it (m²).")
      .def("__repr__", [](const rm::FilledHole& h) {
        return fmt::format("FilledHole(boundary_edges={}, area={} m²)", h.boundary_edges, h.area);
      });

  py::class_<rm::HoleFillReport>(mesh, "HoleFillReport", "What rigid.mesh.fill_holes added.")
      .def_readonly("holes", &rm::HoleFillReport::holes,
                    "One FilledHole per hole, in the order found.")
      .def_readonly("triangles_added", &rm::HoleFillReport::triangles_added, "Triangles added.")
      .def_readonly("vertices_added", &rm::HoleFillReport::vertices_added,
                    "Vertices added (fan centres).")
      .def_readonly("area", &rm::HoleFillReport::area, "Total area of the patches (m²).")
      .def("__repr__", [](const rm::HoleFillReport& r) {
        return fmt::format(
            "HoleFillReport(holes={}, triangles_added={}, vertices_added={}, area={} m²)",
            r.holes.size(), r.triangles_added, r.vertices_added, r.area);
      });
}

// Mesh files: read (STL/OBJ/PLY/OFF), write_stl, and the units of a file.
void bind_mesh_files(py::module_& mesh) {
  mesh.def(
      "read",
      [](const py::object& path, double scale) {
        const std::string file = cv::path(path, {"rigid.mesh.read", "path"});
        py::gil_scoped_release release;
        return cv::reading("rigid.mesh.read", file, [&] { return rm::read_mesh(file, scale); });
      },
      py::arg("path"), py::arg("scale") = 1.0,
      "Read an STL/OBJ/PLY/OFF file (a str or pathlib.Path; the format from the extension); "
      "coordinates multiplied by scale (m per file unit). Errors start with the file name.");
  mesh.def(
      "write_stl",
      [](const TriangleMesh& t, const py::object& path) {
        const std::string file = cv::path(path, {"rigid.mesh.write_stl", "path"});
        cv::reading("rigid.mesh.write_stl", file,
                    [&] { rigid::io::write_file_atomically(file, rm::stl_binary(t)); });
      },
      py::arg("mesh"), py::arg("path"),
      "Writes a binary STL (float32 coordinates, m) to path (a str or pathlib.Path), "
      "atomically: a new file renamed over the old one; a directory, FIFO, socket or device "
      "at path is refused, and a symlink is written through.");
  mesh.def("unit_scale", &rm::unit_scale, py::arg("unit"), "Metres per unit: m, cm, mm or in.");
}

// Edges counted, and a mesh repaired and its holes filled in place.
void bind_mesh_repair(py::module_& mesh) {
  mesh.def(
      "count_edges", &rm::count_edges, py::arg("mesh"),
      "Boundary, non-manifold and misoriented edges of the mesh as it is (vertices compared by "
      "index; nothing is welded): a solid's mass properties need all three zero.");
  mesh.def(
      "repair",
      [](TriangleMesh& t, double weld_tolerance) {
        rm::RepairOptions o;
        o.weld_tolerance = weld_tolerance;
        return rm::repair_mesh(t, o);
      },
      py::arg("mesh"), py::arg("weld_tolerance") = 1e-7,
      "Weld, drop degenerate triangles, orient each component outward (in place); returns the "
      "report.");
  mesh.def(
      "fill_holes",
      [](TriangleMesh& t) { return with_repair_worded([&] { return rm::fill_holes(t); }); },
      py::arg("mesh"),
      "Close every hole whose border is a simple loop (in place; run repair first and "
      "again after); a planar hole is closed exactly. Returns the report.");
}

// Exact moments of the enclosed volume and of the surface.
void bind_mesh_moments(py::module_& mesh) {
  for (const bool solid : {true, false}) {
    mesh.def(
        solid ? "volume_moments" : "surface_moments",
        [solid](const TriangleMesh& t, const py::object& about) {
          std::optional<Eigen::Vector3d> p;
          if (!about.is_none())
            p = cv::vector3(
                about,
                {solid ? "rigid.mesh.volume_moments" : "rigid.mesh.surface_moments", "about"});
          const rm::MeshMoments mm = solid ? rm::volume_moments(t, p) : rm::surface_moments(t, p);
          py::dict d;
          d["about"] = mm.p_OR_M;
          d["measure"] = mm.measure;
          d["first"] = mm.first;
          d["second"] = mm.second;
          return d;
        },
        py::arg("mesh"), py::arg("about") = py::none(),
        solid
            ? "Exact moments of the enclosed volume about the point `about` (m, mesh frame; the "
              "bounding-box centre when None): measure ∫1 (m³), first ∫r (m⁴), second ∫r rᵀ (m⁵), "
              "r = p − about; by the divergence theorem, signed by the winding (no check here)."
            : "Exact moments of the surface about `about` (the bounding-box centre when None): "
              "measure area (m²), first ∫r (m³), second ∫r rᵀ (m⁴).");
  }
}

// rigid.mesh.mass_properties: (MassProperties, warnings) of a mesh, or of a repaired copy.
py::tuple mass_properties_with_warnings(const TriangleMesh& t, std::optional<double> mass,
                                        std::optional<double> density, bool shell,
                                        std::optional<double> thickness, bool repair) {
  const rm::MassSpec spec{mass, density, shell, thickness};
  if (!repair) {
    // a mesh that has not been through repair: refused unless closed and consistently
    // oriented (the library checks), with the remedy rigid.mesh.repair(mesh)
    auto r = with_repair_worded([&] { return rm::mesh_mass_properties(t, spec); });
    return py::make_tuple(r.properties, worded(r.warnings));
  }
  // repair=True: a repaired copy is measured (the caller's mesh is unchanged) and what
  // repair changed comes first among the warnings, as `rigid inertia FILE` prints it
  TriangleMesh copy = t;
  const rm::RepairReport report = rm::repair_mesh(copy);
  auto r = rm::mesh_mass_properties(copy, spec, report);
  std::vector<std::string> warnings = report.warnings;
  warnings.insert(warnings.end(), r.warnings.begin(), r.warnings.end());
  return py::make_tuple(r.properties, worded(warnings));
}

// rigid.mesh.vertex_noise_uncertainty: the values and their 1σ as dicts.
py::dict vertex_noise_uncertainty_dict(const TriangleMesh& t, double sigma,
                                       std::optional<double> mass, std::optional<double> density,
                                       const py::object& about_arg) {
  std::optional<Eigen::Vector3d> about;
  if (!about_arg.is_none())
    about = cv::vector3(about_arg, {"rigid.mesh.vertex_noise_uncertainty", "about"});
  const auto u = with_repair_worded([&] {
    return rm::vertex_noise_uncertainty(t, {mass, density, false, std::nullopt}, sigma, about);
  });
  const auto tensor = [](const Eigen::Matrix<double, 10, 1>& y) {
    Eigen::Matrix3d I;
    I << y(4), y(7), y(8), y(7), y(5), y(9), y(8), y(9), y(6);
    return I;
  };
  py::dict d, s;
  d["mass"] = u.value(0);
  d["com"] = Eigen::Vector3d(u.value.segment<3>(1));
  d["inertia"] = tensor(u.value);
  s["mass"] = u.sigma(0);
  s["com"] = Eigen::Vector3d(u.sigma.segment<3>(1));
  s["inertia"] = tensor(u.sigma);
  d["sigma"] = s;
  return d;
}

// Mass properties of meshes and mesh files, and their uncertainty under vertex noise.
void bind_mesh_mass(py::module_& mesh) {
  mesh.def(
      "mass_properties", &mass_properties_with_warnings, py::arg("mesh"), py::kw_only(),
      py::arg("mass") = py::none(), py::arg("density") = py::none(), py::arg("shell") = false,
      py::arg("thickness") = py::none(), py::arg("repair") = false,
      "(rigid.MassProperties, warnings) of a solid or thin shell in the mesh frame (COM in m, "
      "inertia about the COM in kg·m²); exactly one of mass (kg) and density (kg/m³; kg/m² for a "
      "shell, or kg/m³ with thickness= in m). A solid must be closed and consistently oriented: "
      "otherwise rigid.Error (never a wrong volume), with the remedy rigid.mesh.repair(mesh). "
      "repair=True measures a repaired copy instead (weld, drop degenerate triangles, orient "
      "outward; the mesh passed is unchanged), and the warnings say what repair changed.");
  mesh.def(
      "mass_from_file",
      [](const py::object& path, std::optional<double> mass, std::optional<double> density,
         const std::string& units, bool shell, std::optional<double> thickness, bool fill_holes) {
        const std::string file = cv::path(path, {"rigid.mesh.mass_from_file", "path"});
        std::optional<rm::MeshFileMass> r;
        {
          py::gil_scoped_release release;
          cv::reading("rigid.mesh.mass_from_file", file, [&] {
            r.emplace(rm::mesh_mass_from_file(file, rm::unit_scale(units),
                                              {mass, density, shell, thickness}, {}, fill_holes));
          });
        }
        return py::make_tuple(r->mass.properties, worded(r->warnings()));
      },
      py::arg("path"), py::kw_only(), py::arg("mass") = py::none(), py::arg("density") = py::none(),
      py::arg("units") = "m", py::arg("shell") = false, py::arg("thickness") = py::none(),
      py::arg("fill_holes") = false,
      "(rigid.MassProperties, warnings) of a mesh file (a str or pathlib.Path) read, repaired "
      "(holes filled with "
      "fill_holes=True) and integrated: what `rigid inertia FILE` prints. Exactly one of mass, "
      "density; units m, cm, mm or in.");
  mesh.def(
      "vertex_noise_uncertainty", &vertex_noise_uncertainty_dict, py::arg("mesh"), py::arg("sigma"),
      py::kw_only(), py::arg("mass") = py::none(), py::arg("density") = py::none(),
      py::arg("about") = py::none(),
      "Mass, COM and inertia (about `about`, the COM when None) of a solid mesh with their 1σ when "
      "each vertex coordinate has an independent error of standard deviation sigma (m): "
      "first-order "
      "propagation, as `rigid inertia FILE --tolerance vertices=±…`.");
  mesh.def(
      "integrate_density",
      [](const TriangleMesh& t, const rigid::mass::DensityFunction& rho, double tol, int cells) {
        return rigid::mass::integrate_density_over_mesh(
            rho, t.vertices, t.triangles, {.relative_tolerance = tol, .max_cells = cells});
      },
      py::arg("mesh"), py::arg("rho"), py::arg("relative_tolerance") = 1e-10,
      py::arg("max_cells") = 2000,
      "Mass properties of the density rho(p) (kg/m³; p a point in m, the mesh's frame) over the "
      "solid the closed, outward-oriented mesh bounds (run repair first), by adaptive cubature on "
      "the tetrahedra from its vertices' centroid (Grundmann–Möller, degrees 9 and 7): a "
      "rigid.mass.DensityIntegration (cells: tetrahedra). For a non-convex mesh rho is also "
      "sampled outside the solid, where it must be finite and non-negative. An open or "
      "misoriented mesh is refused.");
}

}  // namespace

void bind_mesh(py::module_& m) {
  auto mesh = m.def_submodule("mesh", "Triangle meshes: readers, repair, exact mass properties.");
  bind_triangle_mesh(mesh);
  bind_mesh_reports(mesh);
  bind_mesh_files(mesh);
  bind_mesh_repair(mesh);
  bind_mesh_moments(mesh);
  bind_mesh_mass(mesh);
}
