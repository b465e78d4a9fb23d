#include "rigid/mesh/mesh_mass.hpp"

#include <cmath>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "rigid/common/error.hpp"
#include "rigid/mesh/repair.hpp"

namespace rigid::mesh {
namespace {

Eigen::Vector3d default_reference(const TriangleMesh& mesh) {
  const auto box = mesh.bounding_box();
  return 0.5 * (box[0] + box[1]);
}

// Σ v vᵀ over the three vertices plus s sᵀ, accumulated into the upper triangle.
struct Accumulator {
  double measure = 0, fx = 0, fy = 0, fz = 0;
  double xx = 0, yy = 0, zz = 0, xy = 0, xz = 0, yz = 0;

  // Adds one triangle (solid: tetrahedron with the reference point) with weight w and
  // vertices a, b, c relative to the reference; s = a + b + c.
  void add(double w, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
           const Eigen::Vector3d& s) {
    measure += w;
    fx += w * s.x();
    fy += w * s.y();
    fz += w * s.z();
    xx += w * (a.x() * a.x() + b.x() * b.x() + c.x() * c.x() + s.x() * s.x());
    yy += w * (a.y() * a.y() + b.y() * b.y() + c.y() * c.y() + s.y() * s.y());
    zz += w * (a.z() * a.z() + b.z() * b.z() + c.z() * c.z() + s.z() * s.z());
    xy += w * (a.x() * a.y() + b.x() * b.y() + c.x() * c.y() + s.x() * s.y());
    xz += w * (a.x() * a.z() + b.x() * b.z() + c.x() * c.z() + s.x() * s.z());
    yz += w * (a.y() * a.z() + b.y() * b.z() + c.y() * c.z() + s.y() * s.z());
  }
};

MeshMoments finish(const Accumulator& a, const Eigen::Vector3d& p_OR, double k0, double k1,
                   double k2) {
  MeshMoments m;
  m.p_OR_M = p_OR;
  m.measure = a.measure * k0;
  m.first = Eigen::Vector3d(a.fx, a.fy, a.fz) * k1;
  m.second << a.xx, a.xy, a.xz, a.xy, a.yy, a.yz, a.xz, a.yz, a.zz;
  m.second *= k2;
  return m;
}

}  // namespace

MeshMoments volume_moments(const TriangleMesh& mesh, std::optional<Eigen::Vector3d> p_OR_M) {
  const Eigen::Vector3d r = p_OR_M ? *p_OR_M : default_reference(mesh);
  Accumulator acc;
  const auto* v = mesh.vertices.data();
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = v[t[0]] - r;
    const Eigen::Vector3d b = v[t[1]] - r;
    const Eigen::Vector3d c = v[t[2]] - r;
    // det[a b c] = a · (b × c) = 6 × signed volume of the tetrahedron (R, a, b, c).
    const double det = a.x() * (b.y() * c.z() - b.z() * c.y()) -
                       a.y() * (b.x() * c.z() - b.z() * c.x()) +
                       a.z() * (b.x() * c.y() - b.y() * c.x());
    const Eigen::Vector3d s = a + b + c;
    acc.add(det, a, b, c, s);
  }
  // [Tonon2005, eq. 2–4]: V = det/6, ∫r = det·s/24, ∫r rᵀ = det/120 (Σ v vᵀ + s sᵀ).
  return finish(acc, r, 1.0 / 6.0, 1.0 / 24.0, 1.0 / 120.0);
}

MeshMoments surface_moments(const TriangleMesh& mesh, std::optional<Eigen::Vector3d> p_OR_M) {
  const Eigen::Vector3d r = p_OR_M ? *p_OR_M : default_reference(mesh);
  Accumulator acc;
  const auto* v = mesh.vertices.data();
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = v[t[0]] - r;
    const Eigen::Vector3d b = v[t[1]] - r;
    const Eigen::Vector3d c = v[t[2]] - r;
    const double area2 = (b - a).cross(c - a).norm();  // twice the area
    const Eigen::Vector3d s = a + b + c;
    acc.add(area2, a, b, c, s);
  }
  // Triangle: A, ∫r = A s/3, ∫r rᵀ = A/12 (Σ v vᵀ + s sᵀ); acc holds 2A.
  return finish(acc, r, 0.5, 1.0 / 6.0, 1.0 / 24.0);
}

namespace {

// Plausibility: the densest engineering material (osmium) is 22.6e3 kg/m³, the lightest
// solid foams ~1 kg/m³; a mesh in millimetres read as metres is 10³ times too long.
constexpr double kMaxDensity = 3e4;
constexpr double kMinDensity = 0.5;
constexpr double kMaxSize = 100.0;  // m: larger than any part one computes an inertia for

}  // namespace

MeshMassResult mesh_mass_properties(const TriangleMesh& mesh, const MassSpec& spec) {
  RIGID_REQUIRE(spec.mass.has_value() != spec.density.has_value(),
                "give exactly one of mass and density (got {})",
                spec.mass ? "both" : "neither");
  if (spec.mass) {
    RIGID_REQUIRE(std::isfinite(*spec.mass) && *spec.mass > 0,
                  "mass {} kg: expected a positive finite value", *spec.mass);
  } else {
    RIGID_REQUIRE(std::isfinite(*spec.density) && *spec.density > 0,
                  "density {}: expected a positive finite value", *spec.density);
  }
  if (spec.thickness) {
    RIGID_REQUIRE(spec.shell, "thickness {} m given for a solid: thickness applies to --shell only",
                  *spec.thickness);
    RIGID_REQUIRE(std::isfinite(*spec.thickness) && *spec.thickness > 0,
                  "thickness {} m: expected a positive finite value", *spec.thickness);
  }
  RIGID_REQUIRE(!mesh.triangles.empty(), "the mesh has no triangles");

  if (!spec.shell) {
    const EdgeCounts e = count_edges(mesh);
    RIGID_REQUIRE(e.boundary == 0 && e.non_manifold == 0,
                  "the mesh is not closed ({} boundary edges, {} non-manifold edges), so it "
                  "bounds no solid: use --shell for a thin shell, or close the holes first",
                  e.boundary, e.non_manifold);
  }
  const MeshMoments mom = spec.shell ? surface_moments(mesh) : volume_moments(mesh);
  const char* what = spec.shell ? "area" : "volume";
  RIGID_REQUIRE(mom.measure > 0 && std::isfinite(mom.measure),
                "mesh {} is {}: expected positive{}", what, mom.measure,
                spec.shell ? "" : " (a closed, outward-oriented surface; see repair_mesh)");
  double rho = 0;  // per unit of measure
  if (spec.mass) {
    rho = *spec.mass / mom.measure;
  } else {
    rho = *spec.density * (spec.thickness ? *spec.thickness : 1.0);
  }
  const double m = rho * mom.measure;
  const Eigen::Vector3d p_RC = mom.first / mom.measure;
  // Covariance about the COM: ∫ρ (r − c)(r − c)ᵀ = ρ(∫r rᵀ − V c cᵀ).
  Eigen::Matrix3d C = rho * (mom.second - mom.measure * p_RC * p_RC.transpose());
  C = 0.5 * (C + C.transpose()).eval();
  const Eigen::Matrix3d I = C.trace() * Eigen::Matrix3d::Identity() - C;
  MeshMassResult out{MassProperties(m, mom.p_OR_M + p_RC, I), mom.measure, {}};

  const double size = mesh.bounding_box_diagonal();
  if (size > kMaxSize) {
    out.warnings.push_back(fmt::format(
        "the mesh is {:.4g} m across: if the file is in millimetres, use --units mm", size));
  }
  if (!spec.shell || spec.thickness) {
    const double density = spec.shell ? rho / *spec.thickness : rho;
    if (density > kMaxDensity || density < kMinDensity) {
      out.warnings.push_back(fmt::format(
          "implied density {:.4g} kg/m³ is outside any real material ({} to {} kg/m³): {}",
          density, kMinDensity, kMaxDensity,
          density < kMinDensity ? "if the file is in millimetres, use --units mm"
                                : "check --units (the file may be in metres, not mm)"));
    }
  }
  return out;
}

}  // namespace rigid::mesh
