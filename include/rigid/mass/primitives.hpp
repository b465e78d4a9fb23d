#pragma once

#include <span>

#include <Eigen/Core>

#include "rigid/mass/mass_properties.hpp"

/// Mass properties of uniform primitive bodies.
///
/// Every factory comes in two forms that differ only in the first argument:
/// `*_with_mass(m, ...)` takes the mass (kg) and `*_with_density(rho, ...)` the density:
/// kg/m³ for solids, kg/m² (areal) for thin shells and plates, kg/m (linear) for the rod.
/// Lengths are in metres. Frames (the frame B of the returned MassProperties):
///  - bodies of revolution have their axis along z;
///  - every body is centred on its COM (COM at the origin), except the cone and the
///    frustum, whose base disk lies in the plane z = 0 with the body above it (z ≥ 0),
///    and the tetrahedron, which keeps the coordinates of its vertices.
/// Every size must be positive and finite; a violation throws rigid::Error naming the
/// function, the parameter, its value and what was expected.
namespace rigid::mass {

/// Solid sphere of radius r. I = 2/5 m r² about every axis; m = ρ·4/3 π r³.
[[nodiscard]] MassProperties solid_sphere_with_mass(double m, double r);
[[nodiscard]] MassProperties solid_sphere_with_density(double rho, double r);

/// Thick spherical shell between radii r_inner < r_outer.
/// I = 2/5 m (r₂⁵ − r₁⁵)/(r₂³ − r₁³); m = ρ·4/3 π (r₂³ − r₁³).
[[nodiscard]] MassProperties thick_spherical_shell_with_mass(double m, double r_inner,
                                                             double r_outer);
[[nodiscard]] MassProperties thick_spherical_shell_with_density(double rho, double r_inner,
                                                                double r_outer);

/// Thin spherical shell (a surface) of radius r. I = 2/3 m r²; m = σ·4π r² (σ in kg/m²).
[[nodiscard]] MassProperties thin_spherical_shell_with_mass(double m, double r);
[[nodiscard]] MassProperties thin_spherical_shell_with_density(double sigma, double r);

/// Solid ellipsoid with semi-axes a, b, c along x, y, z.
/// I_xx = m (b² + c²)/5 (and cyclic); m = ρ·4/3 π a b c.
[[nodiscard]] MassProperties solid_ellipsoid_with_mass(double m, double a, double b, double c);
[[nodiscard]] MassProperties solid_ellipsoid_with_density(double rho, double a, double b,
                                                          double c);

/// Solid box with edge lengths lx, ly, lz along x, y, z.
/// I_xx = m (ly² + lz²)/12 (and cyclic); m = ρ lx ly lz.
[[nodiscard]] MassProperties solid_box_with_mass(double m, double lx, double ly, double lz);
[[nodiscard]] MassProperties solid_box_with_density(double rho, double lx, double ly, double lz);

/// Solid circular cylinder of radius r and height h, axis z, z ∈ [−h/2, h/2].
/// I_zz = m r²/2, I_xx = I_yy = m (3r² + h²)/12; m = ρ π r² h.
[[nodiscard]] MassProperties solid_cylinder_with_mass(double m, double r, double h);
[[nodiscard]] MassProperties solid_cylinder_with_density(double rho, double r, double h);

/// Thick-walled tube (a rolled-up sheet) between radii r_inner < r_outer, height h, axis z.
/// I_zz = m (r₁² + r₂²)/2, I_xx = I_yy = m (3(r₁² + r₂²) + h²)/12; m = ρ π (r₂² − r₁²) h.
[[nodiscard]] MassProperties thick_tube_with_mass(double m, double r_inner, double r_outer,
                                                  double h);
[[nodiscard]] MassProperties thick_tube_with_density(double rho, double r_inner, double r_outer,
                                                     double h);

/// Thin cylindrical shell (lateral surface only, open ends) of radius r, height h, axis z.
/// I_zz = m r², I_xx = I_yy = m (r²/2 + h²/12); m = σ 2π r h.
[[nodiscard]] MassProperties thin_cylindrical_shell_with_mass(double m, double r, double h);
[[nodiscard]] MassProperties thin_cylindrical_shell_with_density(double sigma, double r,
                                                                 double h);

/// Thin cylindrical shell closed by two thin end disks of the same areal density at
/// z = ±h/2. With A_l = 2π r h and A_c = π r² (each cap), per unit areal density:
/// I_zz = A_l r² + 2 A_c r²/2, I_xx = A_l (r²/2 + h²/12) + 2 A_c (r²/4 + h²/4);
/// m = σ (A_l + 2 A_c).
[[nodiscard]] MassProperties capped_cylindrical_shell_with_mass(double m, double r, double h);
[[nodiscard]] MassProperties capped_cylindrical_shell_with_density(double sigma, double r,
                                                                   double h);

/// Solid right circular cone of base radius r and height h: base disk at z = 0, apex at
/// z = h. COM at z = h/4. About the COM: I_zz = 3/10 m r², I_xx = I_yy = m (3r²/20 + 3h²/80);
/// m = ρ π r² h/3.
[[nodiscard]] MassProperties solid_cone_with_mass(double m, double r, double h);
[[nodiscard]] MassProperties solid_cone_with_density(double rho, double r, double h);

/// Solid conical frustum: radius r_bottom at z = 0, r_top at z = h (either may be larger).
/// With S₂ = r₁² + r₁r₂ + r₂², S₄ = r₁⁴ + r₁³r₂ + r₁²r₂² + r₁r₂³ + r₂⁴, d = r₂ − r₁:
/// V = π h S₂/3, z_C = π h² (r₁²/2 + 2r₁d/3 + d²/4)/V, I_zz = ρ π h S₄/10,
/// I_xx = I_yy = I_zz/2 + ρ π h³ (r₁²/3 + r₁d/2 + d²/5) − m z_C² (about the COM).
[[nodiscard]] MassProperties solid_frustum_with_mass(double m, double r_bottom, double r_top,
                                                     double h);
[[nodiscard]] MassProperties solid_frustum_with_density(double rho, double r_bottom,
                                                        double r_top, double h);

/// Solid capsule: a cylinder of radius r and length l (axis z, centred) with a solid
/// hemisphere of radius r on each end; total length l + 2r. With m_c = ρ π r² l and
/// m_h = ρ 2/3 π r³ (each hemisphere): I_zz = m_c r²/2 + 2 m_h·2r²/5,
/// I_xx = m_c (l²/12 + r²/4) + 2 m_h (2r²/5 + l²/4 + 3 l r/8). l = 0 gives a sphere.
[[nodiscard]] MassProperties solid_capsule_with_mass(double m, double r, double l);
[[nodiscard]] MassProperties solid_capsule_with_density(double rho, double r, double l);

/// Solid torus: tube of radius a around a circle of radius R in the xy-plane, axis z;
/// 0 < a ≤ R. I_zz = m (R² + 3a²/4), I_xx = I_yy = m (R²/2 + 5a²/8); m = ρ 2π² R a².
[[nodiscard]] MassProperties solid_torus_with_mass(double m, double R, double a);
[[nodiscard]] MassProperties solid_torus_with_density(double rho, double R, double a);

/// Thin rod of length l along z, centred. I_xx = I_yy = m l²/12, I_zz = 0; m = λ l.
[[nodiscard]] MassProperties thin_rod_with_mass(double m, double l);
[[nodiscard]] MassProperties thin_rod_with_density(double lambda, double l);

/// Thin rectangular plate lx × ly in the xy-plane, centred.
/// I_xx = m ly²/12, I_yy = m lx²/12, I_zz = m (lx² + ly²)/12; m = σ lx ly.
[[nodiscard]] MassProperties thin_rectangular_plate_with_mass(double m, double lx, double ly);
[[nodiscard]] MassProperties thin_rectangular_plate_with_density(double sigma, double lx,
                                                                 double ly);

/// Thin disk of radius r in the xy-plane, centred. I_xx = I_yy = m r²/4, I_zz = m r²/2;
/// m = σ π r².
[[nodiscard]] MassProperties thin_disk_with_mass(double m, double r);
[[nodiscard]] MassProperties thin_disk_with_density(double sigma, double r);

/// Thin ring (hoop) of radius r in the xy-plane, centred on the z axis: a circle of matter.
/// I_xx = I_yy = m r²/2, I_zz = m r²; m = λ 2πr.
/// @param lambda linear density (kg/m); r radius of the circle (m).
/// @throws rigid::Error if m (lambda) or r is not positive and finite.
[[nodiscard]] MassProperties thin_ring_with_mass(double m, double r);
[[nodiscard]] MassProperties thin_ring_with_density(double lambda, double r);

/// Solid tetrahedron with vertices v0..v3 (any orientation), in the vertices' frame.
/// With e_i = v_i − v0 and V = |det(e1, e2, e3)|/6, the second moment about v0 is
/// S = ρ V/20 (Σ e_i e_iᵀ + (Σ e_i)(Σ e_i)ᵀ), the COM v0 + Σ e_i/4, and I = tr(S_C) 1 − S_C.
/// @throws rigid::Error if a vertex is not finite or the tetrahedron is degenerate
/// (|det| ≤ 1e-12 · (longest edge)³).
[[nodiscard]] MassProperties solid_tetrahedron_with_mass(double m, const Eigen::Vector3d& v0,
                                                         const Eigen::Vector3d& v1,
                                                         const Eigen::Vector3d& v2,
                                                         const Eigen::Vector3d& v3);
[[nodiscard]] MassProperties solid_tetrahedron_with_density(double rho, const Eigen::Vector3d& v0,
                                                            const Eigen::Vector3d& v1,
                                                            const Eigen::Vector3d& v2,
                                                            const Eigen::Vector3d& v3);

/// A point mass m at p (m): zero inertia about its COM.
[[nodiscard]] MassProperties point_mass(double m, const Eigen::Vector3d& p);

/// A set of point masses masses[i] at points.col(i) (3 × n, metres), combined.
/// @throws rigid::Error if the sizes differ, the set is empty, or a mass is not positive.
[[nodiscard]] MassProperties point_masses(std::span<const double> masses,
                                          const Eigen::Matrix3Xd& points);

}  // namespace rigid::mass
