#include "rigid/mass/primitives.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/LU>

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"

namespace rigid::mass {
namespace {

using std::numbers::pi;

// A uniform body of unit density: its measure (volume, area or length) and, per unit
// mass, the COM and the inertia about the COM.
struct UnitBody {
  double measure;
  Eigen::Vector3d com;
  Eigen::Matrix3d inertia_per_mass;
};

UnitBody diagonal_body(double measure, double Ixx, double Iyy, double Izz,
                       const Eigen::Vector3d& com = Eigen::Vector3d::Zero()) {
  return UnitBody{measure, com, Eigen::Vector3d(Ixx, Iyy, Izz).asDiagonal()};
}

void require_size(const char* function, const char* name, double value) {
  if (!std::isfinite(value) || !(value > 0.0)) {
    detail::throw_error(function,
                        fmt::format("{} must be positive and finite, got {} m", name, value));
  }
}

void require_less(const char* function, const char* small_name, double small,
                  const char* large_name, double large) {
  if (!(small < large)) {
    detail::throw_error(function, fmt::format("{} must be less than {}, got {} = {} m and {} = {} m",
                                              small_name, large_name, small_name, small,
                                              large_name, large));
  }
}

MassProperties with_mass(const char* function, double m, const UnitBody& body) {
  if (!std::isfinite(m) || !(m > 0.0)) {
    detail::throw_error(function, fmt::format("mass must be positive and finite, got {} kg", m));
  }
  return MassProperties(m, body.com, m * body.inertia_per_mass);
}

MassProperties with_density(const char* function, const char* unit, double rho,
                            const UnitBody& body) {
  if (!std::isfinite(rho) || !(rho > 0.0)) {
    detail::throw_error(function,
                        fmt::format("density must be positive and finite, got {} {}", rho, unit));
  }
  const double m = rho * body.measure;
  return MassProperties(m, body.com, m * body.inertia_per_mass);
}

constexpr const char* kVolumeDensity = "kg/m³";
constexpr const char* kArealDensity = "kg/m²";
constexpr const char* kLinearDensity = "kg/m";

UnitBody sphere(const char* fn, double r) {
  require_size(fn, "radius", r);
  const double I = 0.4 * r * r;
  return diagonal_body(4.0 / 3.0 * pi * r * r * r, I, I, I);
}

UnitBody thick_shell(const char* fn, double r1, double r2) {
  require_size(fn, "inner radius", r1);
  require_size(fn, "outer radius", r2);
  require_less(fn, "inner radius", r1, "outer radius", r2);
  // (r₂⁵ − r₁⁵)/(r₂³ − r₁³) with the common factor (r₂ − r₁) cancelled, so that a thin
  // wall does not lose digits.
  const double num = r2 * r2 * r2 * r2 + r2 * r2 * r2 * r1 + r2 * r2 * r1 * r1 +
                     r2 * r1 * r1 * r1 + r1 * r1 * r1 * r1;
  const double den = r2 * r2 + r2 * r1 + r1 * r1;
  const double I = 0.4 * num / den;
  return diagonal_body(4.0 / 3.0 * pi * (r2 - r1) * den, I, I, I);
}

UnitBody thin_sphere(const char* fn, double r) {
  require_size(fn, "radius", r);
  const double I = 2.0 / 3.0 * r * r;
  return diagonal_body(4.0 * pi * r * r, I, I, I);
}

UnitBody ellipsoid(const char* fn, double a, double b, double c) {
  require_size(fn, "semi-axis a", a);
  require_size(fn, "semi-axis b", b);
  require_size(fn, "semi-axis c", c);
  return diagonal_body(4.0 / 3.0 * pi * a * b * c, (b * b + c * c) / 5.0, (a * a + c * c) / 5.0,
                       (a * a + b * b) / 5.0);
}

UnitBody box(const char* fn, double lx, double ly, double lz) {
  require_size(fn, "lx", lx);
  require_size(fn, "ly", ly);
  require_size(fn, "lz", lz);
  return diagonal_body(lx * ly * lz, (ly * ly + lz * lz) / 12.0, (lx * lx + lz * lz) / 12.0,
                       (lx * lx + ly * ly) / 12.0);
}

UnitBody cylinder(const char* fn, double r, double h) {
  require_size(fn, "radius", r);
  require_size(fn, "height", h);
  const double Ixx = (3.0 * r * r + h * h) / 12.0;
  return diagonal_body(pi * r * r * h, Ixx, Ixx, 0.5 * r * r);
}

UnitBody tube(const char* fn, double r1, double r2, double h) {
  require_size(fn, "inner radius", r1);
  require_size(fn, "outer radius", r2);
  require_size(fn, "height", h);
  require_less(fn, "inner radius", r1, "outer radius", r2);
  const double s = r1 * r1 + r2 * r2;
  const double Ixx = (3.0 * s + h * h) / 12.0;
  return diagonal_body(pi * (r2 - r1) * (r2 + r1) * h, Ixx, Ixx, 0.5 * s);
}

UnitBody thin_cylinder(const char* fn, double r, double h) {
  require_size(fn, "radius", r);
  require_size(fn, "height", h);
  const double Ixx = 0.5 * r * r + h * h / 12.0;
  return diagonal_body(2.0 * pi * r * h, Ixx, Ixx, r * r);
}

UnitBody capped_thin_cylinder(const char* fn, double r, double h) {
  require_size(fn, "radius", r);
  require_size(fn, "height", h);
  // lateral surface plus two disks at z = ±h/2 (per unit areal density)
  const double A_l = 2.0 * pi * r * h;
  const double A_c = pi * r * r;
  const double A = A_l + 2.0 * A_c;
  const double Izz = A_l * r * r + 2.0 * A_c * 0.5 * r * r;
  const double Ixx = A_l * (0.5 * r * r + h * h / 12.0) + 2.0 * A_c * (0.25 * r * r + 0.25 * h * h);
  return diagonal_body(A, Ixx / A, Ixx / A, Izz / A);
}

UnitBody frustum(double r1, double r2, double h) {
  // ρ = 1; radius r(z) = r₁ + d z/h, d = r₂ − r₁.
  //   V    = ∫ π r² dz            = π h (r₁² + r₁r₂ + r₂²)/3
  //   F_z  = ∫ π r² z dz          = π h² (r₁²/2 + 2r₁d/3 + d²/4)
  //   S_zz = ∫ π r² z² dz         = π h³ (r₁²/3 + r₁d/2 + d²/5)
  //   I_zz = ∫ π r⁴/2 dz          = π h (r₁⁴ + r₁³r₂ + r₁²r₂² + r₁r₂³ + r₂⁴)/10
  //   S_xx = S_yy = I_zz/2 (each disk slice: ∫x² dA = π r⁴/4)
  const double d = r2 - r1;
  const double V = pi * h * (r1 * r1 + r1 * r2 + r2 * r2) / 3.0;
  const double Fz = pi * h * h * (r1 * r1 / 2.0 + 2.0 * r1 * d / 3.0 + d * d / 4.0);
  const double Szz = pi * h * h * h * (r1 * r1 / 3.0 + r1 * d / 2.0 + d * d / 5.0);
  const double r1s = r1 * r1;
  const double r2s = r2 * r2;
  const double Izz = pi * h * (r1s * r1s + r1s * r1 * r2 + r1s * r2s + r1 * r2s * r2 + r2s * r2s) / 10.0;
  const double zc = Fz / V;
  // about the base origin I_xx = S_yy + S_zz; shift to the COM.
  const double Ixx = 0.5 * Izz + Szz - V * zc * zc;
  return diagonal_body(V, Ixx / V, Ixx / V, Izz / V, Eigen::Vector3d(0, 0, zc));
}

UnitBody cone(const char* fn, double r, double h) {
  require_size(fn, "radius", r);
  require_size(fn, "height", h);
  const double Ixx = 3.0 * r * r / 20.0 + 3.0 * h * h / 80.0;
  return diagonal_body(pi * r * r * h / 3.0, Ixx, Ixx, 0.3 * r * r,
                       Eigen::Vector3d(0, 0, 0.25 * h));
}

UnitBody checked_frustum(const char* fn, double r1, double r2, double h) {
  require_size(fn, "bottom radius", r1);
  require_size(fn, "top radius", r2);
  require_size(fn, "height", h);
  return frustum(r1, r2, h);
}

UnitBody capsule(const char* fn, double r, double l) {
  require_size(fn, "radius", r);
  if (!std::isfinite(l) || !(l >= 0.0)) {
    detail::throw_error(fn, fmt::format("length must be non-negative and finite, got {} m", l));
  }
  const double m_c = pi * r * r * l;
  const double m_h = 2.0 / 3.0 * pi * r * r * r;
  const double V = m_c + 2.0 * m_h;
  const double Izz = m_c * r * r / 2.0 + 2.0 * m_h * 0.4 * r * r;
  const double Ixx = m_c * (l * l / 12.0 + r * r / 4.0) +
                     2.0 * m_h * (0.4 * r * r + l * l / 4.0 + 3.0 * l * r / 8.0);
  return diagonal_body(V, Ixx / V, Ixx / V, Izz / V);
}

UnitBody torus(const char* fn, double R, double a) {
  require_size(fn, "major radius R", R);
  require_size(fn, "minor radius a", a);
  if (!(a <= R)) {
    detail::throw_error(fn, fmt::format("minor radius a must not exceed major radius R, got "
                                        "a = {} m and R = {} m (a self-intersecting torus)",
                                        a, R));
  }
  const double Ixx = 0.5 * R * R + 5.0 / 8.0 * a * a;
  return diagonal_body(2.0 * pi * pi * R * a * a, Ixx, Ixx, R * R + 0.75 * a * a);
}

UnitBody rod(const char* fn, double l) {
  require_size(fn, "length", l);
  const double I = l * l / 12.0;
  return diagonal_body(l, I, I, 0.0);
}

UnitBody plate(const char* fn, double lx, double ly) {
  require_size(fn, "lx", lx);
  require_size(fn, "ly", ly);
  return diagonal_body(lx * ly, ly * ly / 12.0, lx * lx / 12.0, (lx * lx + ly * ly) / 12.0);
}

UnitBody disk(const char* fn, double r) {
  require_size(fn, "radius", r);
  return diagonal_body(pi * r * r, 0.25 * r * r, 0.25 * r * r, 0.5 * r * r);
}

// a circle of radius r in the xy-plane: every element is at distance r from the z axis, so
// I_zz = ∫ r² dm = m r²; by symmetry I_xx = I_yy and, the ring being planar, I_xx + I_yy = I_zz
// (perpendicular-axis theorem), so I_xx = I_yy = m r²/2; its length is 2πr
UnitBody ring(const char* fn, double r) {
  require_size(fn, "radius", r);
  return diagonal_body(2.0 * pi * r, 0.5 * r * r, 0.5 * r * r, r * r);
}

UnitBody tetrahedron(const char* fn, const Eigen::Vector3d& v0, const Eigen::Vector3d& v1,
                     const Eigen::Vector3d& v2, const Eigen::Vector3d& v3) {
  const Eigen::Vector3d* v[] = {&v0, &v1, &v2, &v3};
  for (int i = 0; i < 4; ++i) {
    if (!v[i]->allFinite()) {
      detail::throw_error(fn, fmt::format("vertex {} must be finite, got {} m", i,
                                          to_string(v[i]->transpose())));
    }
  }
  // edges from v0: v0 is the local origin, which keeps round-off relative to the size.
  Eigen::Matrix3d E;
  E << v1 - v0, v2 - v0, v3 - v0;
  double longest = 0.0;
  for (int i = 0; i < 4; ++i) {
    for (int j = i + 1; j < 4; ++j) longest = std::max(longest, (*v[i] - *v[j]).norm());
  }
  const double det = E.determinant();
  if (!(std::abs(det) > 1e-12 * longest * longest * longest)) {
    detail::throw_error(fn, fmt::format("the tetrahedron is degenerate: |det(v1 − v0, v2 − v0, "
                                        "v3 − v0)| = {} m³ is not above 1e-12·(longest edge {} m)³",
                                        std::abs(det), longest));
  }
  const double V = std::abs(det) / 6.0;
  // S = V/20 (Σ e eᵀ + (Σ e)(Σ e)ᵀ): the exact second moment of a uniform simplex about
  // a vertex, from ∫ x xᵀ over the simplex = V (Σ_i e_i e_iᵀ + s sᵀ)/20 with s = Σ e_i
  // [Tonon2005].
  const Eigen::Vector3d s = E.rowwise().sum();
  const Eigen::Matrix3d S = V / 20.0 * (E * E.transpose() + s * s.transpose());
  const Eigen::Vector3d c = s / 4.0;
  const Eigen::Matrix3d S_c = S - V * c * c.transpose();
  const Eigen::Matrix3d I = S_c.trace() * Eigen::Matrix3d::Identity() - S_c;
  return UnitBody{V, v0 + c, I / V};
}

}  // namespace

// clang-format off
MassProperties solid_sphere_with_mass(double m, double r) { return with_mass(__func__, m, sphere(__func__, r)); }
MassProperties solid_sphere_with_density(double rho, double r) { return with_density(__func__, kVolumeDensity, rho, sphere(__func__, r)); }
MassProperties thick_spherical_shell_with_mass(double m, double r1, double r2) { return with_mass(__func__, m, thick_shell(__func__, r1, r2)); }
MassProperties thick_spherical_shell_with_density(double rho, double r1, double r2) { return with_density(__func__, kVolumeDensity, rho, thick_shell(__func__, r1, r2)); }
MassProperties thin_spherical_shell_with_mass(double m, double r) { return with_mass(__func__, m, thin_sphere(__func__, r)); }
MassProperties thin_spherical_shell_with_density(double sigma, double r) { return with_density(__func__, kArealDensity, sigma, thin_sphere(__func__, r)); }
MassProperties solid_ellipsoid_with_mass(double m, double a, double b, double c) { return with_mass(__func__, m, ellipsoid(__func__, a, b, c)); }
MassProperties solid_ellipsoid_with_density(double rho, double a, double b, double c) { return with_density(__func__, kVolumeDensity, rho, ellipsoid(__func__, a, b, c)); }
MassProperties solid_box_with_mass(double m, double lx, double ly, double lz) { return with_mass(__func__, m, box(__func__, lx, ly, lz)); }
MassProperties solid_box_with_density(double rho, double lx, double ly, double lz) { return with_density(__func__, kVolumeDensity, rho, box(__func__, lx, ly, lz)); }
MassProperties solid_cylinder_with_mass(double m, double r, double h) { return with_mass(__func__, m, cylinder(__func__, r, h)); }
MassProperties solid_cylinder_with_density(double rho, double r, double h) { return with_density(__func__, kVolumeDensity, rho, cylinder(__func__, r, h)); }
MassProperties thick_tube_with_mass(double m, double r1, double r2, double h) { return with_mass(__func__, m, tube(__func__, r1, r2, h)); }
MassProperties thick_tube_with_density(double rho, double r1, double r2, double h) { return with_density(__func__, kVolumeDensity, rho, tube(__func__, r1, r2, h)); }
MassProperties thin_cylindrical_shell_with_mass(double m, double r, double h) { return with_mass(__func__, m, thin_cylinder(__func__, r, h)); }
MassProperties thin_cylindrical_shell_with_density(double sigma, double r, double h) { return with_density(__func__, kArealDensity, sigma, thin_cylinder(__func__, r, h)); }
MassProperties capped_cylindrical_shell_with_mass(double m, double r, double h) { return with_mass(__func__, m, capped_thin_cylinder(__func__, r, h)); }
MassProperties capped_cylindrical_shell_with_density(double sigma, double r, double h) { return with_density(__func__, kArealDensity, sigma, capped_thin_cylinder(__func__, r, h)); }
MassProperties solid_cone_with_mass(double m, double r, double h) { return with_mass(__func__, m, cone(__func__, r, h)); }
MassProperties solid_cone_with_density(double rho, double r, double h) { return with_density(__func__, kVolumeDensity, rho, cone(__func__, r, h)); }
MassProperties solid_frustum_with_mass(double m, double r1, double r2, double h) { return with_mass(__func__, m, checked_frustum(__func__, r1, r2, h)); }
MassProperties solid_frustum_with_density(double rho, double r1, double r2, double h) { return with_density(__func__, kVolumeDensity, rho, checked_frustum(__func__, r1, r2, h)); }
MassProperties solid_capsule_with_mass(double m, double r, double l) { return with_mass(__func__, m, capsule(__func__, r, l)); }
MassProperties solid_capsule_with_density(double rho, double r, double l) { return with_density(__func__, kVolumeDensity, rho, capsule(__func__, r, l)); }
MassProperties solid_torus_with_mass(double m, double R, double a) { return with_mass(__func__, m, torus(__func__, R, a)); }
MassProperties solid_torus_with_density(double rho, double R, double a) { return with_density(__func__, kVolumeDensity, rho, torus(__func__, R, a)); }
MassProperties thin_rod_with_mass(double m, double l) { return with_mass(__func__, m, rod(__func__, l)); }
MassProperties thin_rod_with_density(double lambda, double l) { return with_density(__func__, kLinearDensity, lambda, rod(__func__, l)); }
MassProperties thin_rectangular_plate_with_mass(double m, double lx, double ly) { return with_mass(__func__, m, plate(__func__, lx, ly)); }
MassProperties thin_rectangular_plate_with_density(double sigma, double lx, double ly) { return with_density(__func__, kArealDensity, sigma, plate(__func__, lx, ly)); }
MassProperties thin_disk_with_mass(double m, double r) { return with_mass(__func__, m, disk(__func__, r)); }
MassProperties thin_disk_with_density(double sigma, double r) { return with_density(__func__, kArealDensity, sigma, disk(__func__, r)); }
MassProperties thin_ring_with_mass(double m, double r) { return with_mass(__func__, m, ring(__func__, r)); }
MassProperties thin_ring_with_density(double lambda, double r) { return with_density(__func__, kLinearDensity, lambda, ring(__func__, r)); }
// clang-format on

MassProperties solid_tetrahedron_with_mass(double m, const Eigen::Vector3d& v0,
                                           const Eigen::Vector3d& v1, const Eigen::Vector3d& v2,
                                           const Eigen::Vector3d& v3) {
  return with_mass(__func__, m, tetrahedron(__func__, v0, v1, v2, v3));
}

MassProperties solid_tetrahedron_with_density(double rho, const Eigen::Vector3d& v0,
                                              const Eigen::Vector3d& v1, const Eigen::Vector3d& v2,
                                              const Eigen::Vector3d& v3) {
  return with_density(__func__, kVolumeDensity, rho, tetrahedron(__func__, v0, v1, v2, v3));
}

MassProperties point_mass(double m, const Eigen::Vector3d& p) {
  RIGID_REQUIRE(std::isfinite(m) && m > 0.0, "mass must be positive and finite, got {} kg", m);
  RIGID_REQUIRE(p.allFinite(), "position must be finite, got {} m", to_string(p.transpose()));
  return MassProperties(m, p, Eigen::Matrix3d::Zero());
}

MassProperties point_masses(std::span<const double> masses, const Eigen::Matrix3Xd& points) {
  RIGID_REQUIRE(!masses.empty(), "needs at least one point mass, got none");
  RIGID_REQUIRE(static_cast<Eigen::Index>(masses.size()) == points.cols(),
                "got {} masses but {} points; expected one mass per point", masses.size(),
                points.cols());
  std::vector<MassProperties> parts;
  parts.reserve(masses.size());
  for (std::size_t i = 0; i < masses.size(); ++i) {
    const double m = masses[i];
    RIGID_REQUIRE(std::isfinite(m) && m > 0.0,
                  "mass {} must be positive and finite, got {} kg", i, m);
    RIGID_REQUIRE(points.col(static_cast<Eigen::Index>(i)).allFinite(),
                  "point {} must be finite, got {} m", i,
                  to_string(points.col(static_cast<Eigen::Index>(i)).transpose()));
    parts.emplace_back(m, points.col(static_cast<Eigen::Index>(i)), Eigen::Matrix3d::Zero());
  }
  return combine(parts);
}

}  // namespace rigid::mass
