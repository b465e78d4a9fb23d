#include "rigid/mesh/mesh_mass.hpp"

#include <array>
#include <cmath>
#include <cstdint>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "detail/accumulate.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/wording.hpp"
#include "rigid/mesh/repair.hpp"

namespace rigid::mesh {
namespace {

Eigen::Vector3d default_reference(const TriangleMesh& mesh) {
  const auto box = mesh.bounding_box();
  return 0.5 * (box[0] + box[1]);
}

// Σ v vᵀ over the three vertices plus s sᵀ, accumulated into the upper triangle.
using Accumulator = detail::VolumeSums;

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

// The sums run over kLanes triangles at once in GCC/Clang vector types: portable code that
// compiles to SSE2 (baseline x86-64, two doubles per register) or to wider units where the
// target has them, with kLanes independent partial sums per quantity. Plain C++ cannot be
// vectorised by the compiler here: reordering a floating-point reduction needs -ffast-math.
constexpr int kLanes = 4;
using Lanes = double __attribute__((vector_size(kLanes * sizeof(double))));

static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double), "vertices are packed xyz");
static_assert(sizeof(std::array<std::uint32_t, 3>) == 3 * sizeof(std::uint32_t));

// Weight of one triangle (a, b, c) relative to the reference point.
enum class Weight {
  kDet,      // det[a b c] = a · (b × c): 6 × the signed volume of the tetrahedron (R, a, b, c)
  kTwiceArea  // |(b − a) × (c − a)|: twice the triangle's area
};

// Σ w, Σ w s, Σ w (a aᵀ + b bᵀ + c cᵀ + s sᵀ) over the triangles, s = a + b + c, with the
// corners taken relative to p_OR. Per triangle: 9 subtractions (corners relative to R),
// 14 flops for det, 6 for s, 7 for Σ w and Σ w s, 6 × 9 for the second moments: 90 flops,
// done kLanes triangles at a time.
template <Weight kWeight>
[[gnu::always_inline]] inline Accumulator accumulate(const TriangleMesh& mesh,
                                                     const Eigen::Vector3d& p_OR) {
  const double* v = mesh.vertices.empty() ? nullptr : mesh.vertices.front().data();
  const std::uint32_t* tri = mesh.triangles.empty() ? nullptr : mesh.triangles.front().data();
  const std::size_t n = mesh.triangles.size();
  const double rx = p_OR.x(), ry = p_OR.y(), rz = p_OR.z();
  Lanes w_sum{}, fx{}, fy{}, fz{}, xx{}, yy{}, zz{}, xy{}, xz{}, yz{};
    static_assert(kLanes == 4, "the gather below builds four lanes");
  const Lanes r_x = {rx, rx, rx, rx}, r_y = {ry, ry, ry, ry}, r_z = {rz, rz, rz, rz};
  // corner k of the four triangles (pointers to xyz), relative to R: a part far from the
  // origin keeps its precision
  const auto block = [&](const double* const (&p)[4][3]) {
    const Lanes ax = Lanes{p[0][0][0], p[1][0][0], p[2][0][0], p[3][0][0]} - r_x;
    const Lanes ay = Lanes{p[0][0][1], p[1][0][1], p[2][0][1], p[3][0][1]} - r_y;
    const Lanes az = Lanes{p[0][0][2], p[1][0][2], p[2][0][2], p[3][0][2]} - r_z;
    const Lanes bx = Lanes{p[0][1][0], p[1][1][0], p[2][1][0], p[3][1][0]} - r_x;
    const Lanes by = Lanes{p[0][1][1], p[1][1][1], p[2][1][1], p[3][1][1]} - r_y;
    const Lanes bz = Lanes{p[0][1][2], p[1][1][2], p[2][1][2], p[3][1][2]} - r_z;
    const Lanes cx = Lanes{p[0][2][0], p[1][2][0], p[2][2][0], p[3][2][0]} - r_x;
    const Lanes cy = Lanes{p[0][2][1], p[1][2][1], p[2][2][1], p[3][2][1]} - r_y;
    const Lanes cz = Lanes{p[0][2][2], p[1][2][2], p[2][2][2], p[3][2][2]} - r_z;
    Lanes w;
    if constexpr (kWeight == Weight::kDet) {
      w = ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx);
    } else {
      const Lanes ux = bx - ax, uy = by - ay, uz = bz - az;
      const Lanes vx = cx - ax, vy = cy - ay, vz = cz - az;
      const Lanes nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
      const Lanes n2 = nx * nx + ny * ny + nz * nz;
      for (int l = 0; l < kLanes; ++l) w[l] = std::sqrt(n2[l]);
    }
    const Lanes sx = ax + bx + cx, sy = ay + by + cy, sz = az + bz + cz;
    w_sum += w;
    fx += w * sx;
    fy += w * sy;
    fz += w * sz;
    xx += w * (ax * ax + bx * bx + cx * cx + sx * sx);
    yy += w * (ay * ay + by * by + cy * cy + sy * sy);
    zz += w * (az * az + bz * bz + cz * cz + sz * sz);
    xy += w * (ax * ay + bx * by + cx * cy + sx * sy);
    xz += w * (ax * az + bx * bz + cx * cz + sx * sz);
    yz += w * (ay * az + by * bz + cy * cz + sy * sz);
  };
  const auto corners = [&](std::size_t first, std::size_t count, const double* (&p)[4][3]) {
    for (std::size_t l = 0; l < count; ++l) {
      const std::uint32_t* t = tri + 3 * (first + l);
      for (int k = 0; k < 3; ++k) p[l][k] = v + 3 * std::size_t{t[k]};
    }
  };
  const double* p[4][3];
  std::size_t first = 0;
  for (; first + kLanes <= n; first += kLanes) {
    corners(first, kLanes, p);
    block(p);
  }
  if (first < n) {
    // missing lanes: the triangle (R, R, R), whose weight and moments are zero
    const double* r = p_OR.data();
    for (auto& lane : p) lane[0] = lane[1] = lane[2] = r;
    corners(first, n - first, p);
    block(p);
  }
  // lanes added in a fixed order: the result does not depend on the build's vector width
  const auto total = [](const Lanes& x) {
    double s = 0;
    for (int l = 0; l < kLanes; ++l) s += x[l];
    return s;
  };
  return {total(w_sum), total(fx), total(fy), total(fz), total(xx),
          total(yy),    total(zz), total(xy), total(xz), total(yz)};
}

}  // namespace

// The volume sum compiled twice, for baseline x86-64 (SSE2) and for AVX2, the variant chosen
// once at run time: portable binaries, and twice the vector width where the CPU has it. Same
// operations in the same order (no FMA: contraction is off in ISO C++ mode and AVX2 alone
// has no FMA), so both give bitwise the same result (tests/mesh compare them).
namespace detail {

VolumeSums accumulate_volume_baseline(const TriangleMesh& mesh, const Eigen::Vector3d& p_OR) {
  return accumulate<Weight::kDet>(mesh, p_OR);
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && defined(__linux__)
bool avx2_available() { return __builtin_cpu_supports("avx2") != 0; }

[[gnu::target("avx2")]] VolumeSums accumulate_volume_avx2(const TriangleMesh& mesh,
                                                          const Eigen::Vector3d& p_OR) {
  return accumulate<Weight::kDet>(mesh, p_OR);
}
#else
bool avx2_available() { return false; }

VolumeSums accumulate_volume_avx2(const TriangleMesh& mesh, const Eigen::Vector3d& p_OR) {
  return accumulate<Weight::kDet>(mesh, p_OR);
}
#endif

VolumeSums accumulate_volume(const TriangleMesh& mesh, const Eigen::Vector3d& p_OR) {
  static const bool avx2 = avx2_available();
  return avx2 ? accumulate_volume_avx2(mesh, p_OR) : accumulate_volume_baseline(mesh, p_OR);
}

}  // namespace detail

MeshMoments volume_moments(const TriangleMesh& mesh, std::optional<Eigen::Vector3d> p_OR_M) {
  const Eigen::Vector3d r = p_OR_M ? *p_OR_M : default_reference(mesh);
  // [Tonon2005, eq. 2–4]: V = det/6, ∫r = det·s/24, ∫r rᵀ = det/120 (Σ v vᵀ + s sᵀ).
  return finish(detail::accumulate_volume(mesh, r), r, 1.0 / 6.0, 1.0 / 24.0, 1.0 / 120.0);
}

MeshMoments surface_moments(const TriangleMesh& mesh, std::optional<Eigen::Vector3d> p_OR_M) {
  const Eigen::Vector3d r = p_OR_M ? *p_OR_M : default_reference(mesh);
  // Triangle: A, ∫r = A s/3, ∫r rᵀ = A/12 (Σ v vᵀ + s sᵀ); the sums hold 2A.
  return finish(accumulate<Weight::kTwiceArea>(mesh, r), r, 0.5, 1.0 / 6.0, 1.0 / 24.0);
}

namespace {

// Plausibility: the densest engineering material (osmium) is 22.6e3 kg/m³, the lightest
// solid foams ~1 kg/m³; a mesh in millimetres read as metres is 10³ times too long and, at a
// given density, 10⁹ times too heavy.
constexpr double kMaxDensity = 3e4;
constexpr double kMinDensity = 0.5;
// A sheet's mass per unit area ρ·t: 10 µm of aluminium foil is 2700 × 1e-5 = 0.027 kg/m², 13 cm
// of steel plate 7850 × 0.13 ≈ 1000 kg/m². Outside, the number is most likely a volume density
// (kg/m³) given without the thickness, or a length unit that is off by 10³.
constexpr double kMinArealDensity = 0.01;
constexpr double kMaxArealDensity = 1000.0;
constexpr double kMaxMass = 1e6;  // kg: a solid of more than 1000 t is not a part

}  // namespace

std::vector<std::string> size_warnings(const std::array<Eigen::Vector3d, 2>& box) {
  const Eigen::Vector3d size = box[1] - box[0];
  const double longest = size.maxCoeff();
  std::vector<std::string> out;
  if (longest > kMaxPartSize) {
    out.push_back(fmt::format(
        "the part is {:.4g} × {:.4g} × {:.4g} m, more than {} m long: if the file's numbers are "
        "millimetres, use {}",
        size.x(), size.y(), size.z(), kMaxPartSize, setting("units", "mm")));
  } else if (longest < kMinPartSize) {
    out.push_back(fmt::format(
        "the part is {:.4g} × {:.4g} × {:.4g} m, less than {} m long: check the length unit "
        "({} reads the numbers as metres)",
        size.x(), size.y(), size.z(), kMinPartSize, setting("units", "m")));
  }
  return out;
}

namespace detail {

// mesh_mass_properties with the mesh's edge counts (boundary, non-manifold) found by the
// caller, or found here when not given. (Named like the public function: its errors start
// with the name.)
MeshMassResult mesh_mass_properties(const TriangleMesh& mesh, const MassSpec& spec,
                               const std::optional<EdgeCounts>& known_edges) {
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
    RIGID_REQUIRE(spec.shell, "thickness {} m given for a solid: a thickness applies to a shell ({}) only",
                  *spec.thickness, setting("shell"));
    RIGID_REQUIRE(std::isfinite(*spec.thickness) && *spec.thickness > 0,
                  "thickness {} m: expected a positive finite value", *spec.thickness);
  }
  RIGID_REQUIRE(!mesh.triangles.empty(), "the mesh has no triangles");

  if (!spec.shell) {
    // a solid: each directed edge once and its reverse once (closed, consistently wound);
    // without repair's report the edges are matched here, and a mesh that has not been
    // repaired gets that remedy first
    const EdgeCounts e = known_edges ? *known_edges : count_edges(mesh);
    const char* unrepaired =
        known_edges ? ""
                    : " (if the mesh has not been through repair_mesh(mesh), run it first: it "
                      "welds duplicate vertices and orients the triangles)";
    RIGID_REQUIRE(e.boundary == 0 && e.non_manifold == 0,
                  "the mesh is not closed ({}, {}), so it "
                  "bounds no solid: use {} for a thin shell, or {} to close simple holes{}",
                  counted(e.boundary, "boundary edge"), counted(e.non_manifold, "non-manifold edge"),
                  setting("shell"), setting("fill_holes"),
                  unrepaired);
    RIGID_REQUIRE(e.misoriented == 0,
                  "the mesh's triangles are not consistently oriented ({} edges are traversed "
                  "twice in the same direction), so its volume would be wrong: run "
                  "repair_mesh(mesh) first (it orients every component outward)",
                  e.misoriented);
  }
  // one pass for the box: its centre is the reference point, its diagonal the size
  const auto box = mesh.bounding_box();
  const Eigen::Vector3d p_OR = 0.5 * (box[0] + box[1]);
  const MeshMoments mom = spec.shell ? surface_moments(mesh, p_OR) : volume_moments(mesh, p_OR);
  const char* what = spec.shell ? "area" : "volume";
  RIGID_REQUIRE(mom.measure > 0 && std::isfinite(mom.measure),
                "mesh {} is {}: expected positive{}", what, mom.measure,
                spec.shell ? "" : " (a closed surface whose triangles face outward encloses a positive "
                                  "volume; a flat or inside-out mesh does not)");
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
  MeshMassResult out{MassProperties(m, mom.p_OR_M + p_RC, I), mom.measure, {}, {}};

  out.bounding_box = box;
  out.warnings = size_warnings(box);
  if (spec.density && m > kMaxMass) {  // a given mass is the user's, not implied
    out.warnings.push_back(fmt::format(
        "the implied mass {:.4g} t is more than {:.4g} t: if the file's numbers are millimetres, "
        "use {}",
        m / 1000, kMaxMass / 1000, setting("units", "mm")));
  }
  if (spec.shell && !spec.thickness &&
      (rho > kMaxArealDensity || rho < kMinArealDensity)) {
    out.warnings.push_back(fmt::format(
        "{} areal density {:.4g} kg/m² is outside real sheets and plates ({} to {} kg/m², from 10 "
        "µm of aluminium foil to 13 cm of steel): {}",
        spec.density ? "the" : "the implied", rho, kMinArealDensity, kMaxArealDensity,
        spec.density && rho > kMaxArealDensity
            ? fmt::format("if {:.4g} is the material's density in kg/m³, give the wall thickness "
                          "(m) with it",
                          rho)
            : "check the mass and the length unit of the file"));
  }
  if (!spec.shell || spec.thickness) {
    const double density = spec.shell ? rho / *spec.thickness : rho;
    if (density > kMaxDensity || density < kMinDensity) {
      out.warnings.push_back(fmt::format(
          "implied density {:.4g} kg/m³ is outside any real material ({} to {} kg/m³): {}",
          density, kMinDensity, kMaxDensity,
          density < kMinDensity ? "if the file is in millimetres, use " + setting("units", "mm")
                                : "check the length unit, " + setting("units", "m") + " (the file may be in metres, not mm)"));
    }
  }
  return out;
}

}  // namespace detail

MeshMassResult mesh_mass_properties(const TriangleMesh& mesh, const MassSpec& spec) {
  return detail::mesh_mass_properties(mesh, spec, std::nullopt);
}

MeshMassResult mesh_mass_properties(const TriangleMesh& mesh, const MassSpec& spec,
                                    const RepairReport& repaired) {
  // repair_mesh's counts are those of its output (flipping faces keeps every undirected
  // edge). Not re-checked here, not even in asserting builds: that is the edge matching this
  // overload exists to skip (the benchmarks run with asserts on); tests/mesh check it.
  return detail::mesh_mass_properties(mesh, spec,
                                      EdgeCounts{repaired.boundary_edges, repaired.non_manifold_edges, 0});
}

}  // namespace rigid::mesh
