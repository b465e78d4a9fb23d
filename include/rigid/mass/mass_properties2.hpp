#pragma once

#include <string>

#include <Eigen/Core>
#include <fmt/format.h>

/// Planar (2D) mass properties and uniform laminae.
namespace rigid {

/// Mass properties of a planar body in a frame B with origin O: mass m (kg), center of
/// mass p_OC_B (m) and the scalar moment of inertia about the axis ⊥ the plane through the
/// COM, I_C = ∫ρ |r − c|² dA (kg·m²).
///
/// Class invariant (checked by the constructor): m > 0, everything finite, I_C ≥ 0.
class MassProperties2 {
 public:
  /// @throws rigid::Error if mass is not positive and finite, the COM is not finite or the
  /// moment is negative or not finite.
  MassProperties2(double mass, const Eigen::Vector2d& p_OC_B, double moment_com);

  [[nodiscard]] double mass() const { return mass_; }
  [[nodiscard]] const Eigen::Vector2d& com() const { return p_OC_B_; }
  [[nodiscard]] double moment_com() const { return moment_com_; }

  /// Moment about the perpendicular axis through Q (parallel-axis theorem):
  /// I_Q = I_C + m |p_OC − p_OQ|².
  [[nodiscard]] double moment_about(const Eigen::Vector2d& p_OQ_B) const;

  /// The same body moved by d_B (m).
  [[nodiscard]] MassProperties2 shifted(const Eigen::Vector2d& d_B) const;

  /// The same body with its coordinates rotated by `angle` (rad, counter-clockwise):
  /// the COM rotates, the moment is unchanged.
  [[nodiscard]] MassProperties2 rotated(double angle) const;

 private:
  double mass_;
  Eigen::Vector2d p_OC_B_;
  double moment_com_;
};

/// Union of two planar bodies: masses add, moments are shifted to the common COM and added.
[[nodiscard]] MassProperties2 combine(const MassProperties2& a, const MassProperties2& b);

}  // namespace rigid

namespace rigid::mass {

/// Uniform disk lamina of radius r centred at the origin: I_C = m r²/2; m = σ π r².
[[nodiscard]] MassProperties2 disk_lamina_with_mass(double m, double r);
[[nodiscard]] MassProperties2 disk_lamina_with_density(double sigma, double r);

/// Uniform annulus lamina r_inner < r_outer: I_C = m (r₁² + r₂²)/2; m = σ π (r₂² − r₁²).
[[nodiscard]] MassProperties2 annulus_lamina_with_mass(double m, double r_inner, double r_outer);
[[nodiscard]] MassProperties2 annulus_lamina_with_density(double sigma, double r_inner,
                                                          double r_outer);

/// Uniform rectangle lamina lx × ly centred at the origin: I_C = m (lx² + ly²)/12; m = σ lx ly.
[[nodiscard]] MassProperties2 rectangle_lamina_with_mass(double m, double lx, double ly);
[[nodiscard]] MassProperties2 rectangle_lamina_with_density(double sigma, double lx, double ly);

/// Planar second-moment matrix J_C = ∫σ (r − c)(r − c)ᵀ dA of a uniform simple polygon,
/// together with its area and centroid, for the perpendicular-axis theorem: a thin plate
/// of this shape in the xy-plane has I_xx = J_yy, I_yy = J_xx, I_xy = −J_xy and
/// I_zz = J_xx + J_yy = I_xx + I_yy.
struct PolygonMoments {
  double area;               ///< m²
  Eigen::Vector2d centroid;  ///< m
  Eigen::Matrix2d J_C;       ///< per unit areal density (m⁴)
};

/// Area, centroid and second moments of a simple polygon (vertices in order, either
/// orientation), by the shoelace sums over the edges (v_i, v_{i+1}) with c_i = x_i y_{i+1} − x_{i+1} y_i:
/// A = Σ c_i/2, A c = Σ c_i (v_i + v_{i+1})/6, ∫x² = Σ c_i (x_i² + x_i x_{i+1} + x_{i+1}²)/12,
/// ∫xy = Σ c_i (2x_i y_i + x_i y_{i+1} + x_{i+1} y_i + 2 x_{i+1} y_{i+1})/24, about vertex 0.
/// @throws rigid::Error if fewer than 3 vertices, a vertex is not finite, two edges cross
/// (self-intersecting) or the area is zero.
[[nodiscard]] PolygonMoments polygon_moments(const Eigen::Matrix2Xd& vertices);

/// Uniform lamina with the shape of a simple polygon: I_C = σ tr(J_C).
[[nodiscard]] MassProperties2 polygon_lamina_with_mass(double m, const Eigen::Matrix2Xd& vertices);
[[nodiscard]] MassProperties2 polygon_lamina_with_density(double sigma,
                                                          const Eigen::Matrix2Xd& vertices);

}  // namespace rigid::mass

/// "MassProperties2{mass: 2 kg, com: [0, 0.5] m, moment_com: 0.25 kg·m²}"
template <>
struct fmt::formatter<rigid::MassProperties2> : fmt::formatter<std::string_view> {
  auto format(const rigid::MassProperties2& mp, fmt::format_context& ctx) const
      -> decltype(ctx.out());
};
