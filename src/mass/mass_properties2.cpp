#include "rigid/mass/mass_properties2.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"

namespace rigid {

MassProperties2::MassProperties2(double mass, const Eigen::Vector2d& p_OC_B, double moment_com)
    : mass_(mass), p_OC_B_(p_OC_B), moment_com_(moment_com) {
  RIGID_REQUIRE(std::isfinite(mass) && mass > 0.0, "mass must be positive and finite, got {} kg",
                mass);
  RIGID_REQUIRE(p_OC_B.allFinite(), "center of mass must be finite, got {} m",
                to_string(p_OC_B.transpose()));
  RIGID_REQUIRE(std::isfinite(moment_com) && moment_com >= 0.0,
                "moment of inertia must be non-negative and finite, got {} kg·m²", moment_com);
}

double MassProperties2::moment_about(const Eigen::Vector2d& p_OQ_B) const {
  return moment_com_ + mass_ * (p_OC_B_ - p_OQ_B).squaredNorm();
}

MassProperties2 MassProperties2::shifted(const Eigen::Vector2d& d_B) const {
  return MassProperties2(mass_, p_OC_B_ + d_B, moment_com_);
}

MassProperties2 MassProperties2::rotated(double angle) const {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  return MassProperties2(mass_, Eigen::Vector2d(c * p_OC_B_.x() - s * p_OC_B_.y(),
                                                s * p_OC_B_.x() + c * p_OC_B_.y()),
                         moment_com_);
}

MassProperties2 combine(const MassProperties2& a, const MassProperties2& b) {
  const double m = a.mass() + b.mass();
  const Eigen::Vector2d c = (a.mass() * a.com() + b.mass() * b.com()) / m;
  return MassProperties2(m, c, a.moment_about(c) + b.moment_about(c));
}

}  // namespace rigid

namespace rigid::mass {
namespace {

using std::numbers::pi;

void require_size(const char* fn, const char* name, double v) {
  if (!std::isfinite(v) || !(v > 0.0)) {
    detail::throw_error(fn, fmt::format("{} must be positive and finite, got {} m", name, v));
  }
}

MassProperties2 make(const char* fn, bool is_density, double value, double area,
                     const Eigen::Vector2d& com, double moment_per_mass) {
  if (!std::isfinite(value) || !(value > 0.0)) {
    detail::throw_error(fn, is_density ? fmt::format("density must be positive and finite, got {} kg/m²", value)
                                       : fmt::format("mass must be positive and finite, got {} kg", value));
  }
  const double m = is_density ? value * area : value;
  return MassProperties2(m, com, m * moment_per_mass);
}

// segments (p, q) and (r, s) properly intersect or overlap
bool segments_cross(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r,
                    const Eigen::Vector2d& s) {
  auto orient = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    const double v = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    return (v > 0) - (v < 0);
  };
  auto on_segment = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    return std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) &&
           std::min(a.y(), b.y()) <= c.y() && c.y() <= std::max(a.y(), b.y());
  };
  const int o1 = orient(p, q, r);
  const int o2 = orient(p, q, s);
  const int o3 = orient(r, s, p);
  const int o4 = orient(r, s, q);
  if (o1 != o2 && o3 != o4) return true;
  if (o1 == 0 && on_segment(p, q, r)) return true;
  if (o2 == 0 && on_segment(p, q, s)) return true;
  if (o3 == 0 && on_segment(r, s, p)) return true;
  if (o4 == 0 && on_segment(r, s, q)) return true;
  return false;
}

}  // namespace

MassProperties2 disk_lamina_with_mass(double m, double r) {
  require_size(__func__, "radius", r);
  return make(__func__, false, m, pi * r * r, Eigen::Vector2d::Zero(), 0.5 * r * r);
}
MassProperties2 disk_lamina_with_density(double sigma, double r) {
  require_size(__func__, "radius", r);
  return make(__func__, true, sigma, pi * r * r, Eigen::Vector2d::Zero(), 0.5 * r * r);
}
MassProperties2 annulus_lamina_with_mass(double m, double r1, double r2) {
  require_size(__func__, "inner radius", r1);
  require_size(__func__, "outer radius", r2);
  RIGID_REQUIRE(r1 < r2, "inner radius must be less than outer radius, got {} m and {} m", r1, r2);
  return make(__func__, false, m, pi * (r2 - r1) * (r2 + r1), Eigen::Vector2d::Zero(),
              0.5 * (r1 * r1 + r2 * r2));
}
MassProperties2 annulus_lamina_with_density(double sigma, double r1, double r2) {
  require_size(__func__, "inner radius", r1);
  require_size(__func__, "outer radius", r2);
  RIGID_REQUIRE(r1 < r2, "inner radius must be less than outer radius, got {} m and {} m", r1, r2);
  return make(__func__, true, sigma, pi * (r2 - r1) * (r2 + r1), Eigen::Vector2d::Zero(),
              0.5 * (r1 * r1 + r2 * r2));
}
MassProperties2 rectangle_lamina_with_mass(double m, double lx, double ly) {
  require_size(__func__, "lx", lx);
  require_size(__func__, "ly", ly);
  return make(__func__, false, m, lx * ly, Eigen::Vector2d::Zero(), (lx * lx + ly * ly) / 12.0);
}
MassProperties2 rectangle_lamina_with_density(double sigma, double lx, double ly) {
  require_size(__func__, "lx", lx);
  require_size(__func__, "ly", ly);
  return make(__func__, true, sigma, lx * ly, Eigen::Vector2d::Zero(), (lx * lx + ly * ly) / 12.0);
}

PolygonMoments polygon_moments(const Eigen::Matrix2Xd& v) {
  const Eigen::Index n = v.cols();
  RIGID_REQUIRE(n >= 3, "a polygon needs at least 3 vertices, got {}", n);
  for (Eigen::Index i = 0; i < n; ++i) {
    RIGID_REQUIRE(v.col(i).allFinite(), "vertex {} must be finite, got {} m", i,
                  to_string(v.col(i).transpose()));
  }
  // simplicity: no two non-adjacent edges may touch (O(n²), fine for hand-made polygons)
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = i + 1; j < n; ++j) {
      const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      if (adjacent) continue;
      if (segments_cross(v.col(i), v.col((i + 1) % n), v.col(j), v.col((j + 1) % n))) {
        RIGID_THROW("the polygon is not simple: edge {} (vertices {}–{}) touches edge {} "
                    "(vertices {}–{}); list the vertices in boundary order without crossings",
                    i, i, (i + 1) % n, j, j, (j + 1) % n);
      }
    }
  }
  // shoelace moment sums [Steger1996]; vertex 0 is the local origin (reduces round-off for
  // polygons far from the origin)
  double A2 = 0.0;  // 2A
  Eigen::Vector2d F6 = Eigen::Vector2d::Zero();  // 6 A c
  double Sxx12 = 0.0;
  double Syy12 = 0.0;
  double Sxy24 = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector2d a = v.col(i) - v.col(0);
    const Eigen::Vector2d b = v.col((i + 1) % n) - v.col(0);
    const double c = a.x() * b.y() - b.x() * a.y();
    A2 += c;
    F6 += c * (a + b);
    Sxx12 += c * (a.x() * a.x() + a.x() * b.x() + b.x() * b.x());
    Syy12 += c * (a.y() * a.y() + a.y() * b.y() + b.y() * b.y());
    Sxy24 += c * (2 * a.x() * a.y() + a.x() * b.y() + b.x() * a.y() + 2 * b.x() * b.y());
  }
  double scale = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) scale = std::max(scale, (v.col(i) - v.col(0)).norm());
  RIGID_REQUIRE(std::abs(A2) > 1e-14 * scale * scale,
                "the polygon has zero area ({} m²); expected a simple polygon enclosing a region",
                A2 / 2);
  const double sign = A2 > 0 ? 1.0 : -1.0;  // clockwise input: every sum changes sign
  PolygonMoments out;
  out.area = sign * A2 / 2;
  const Eigen::Vector2d c_local = F6 / (3 * A2);
  out.centroid = v.col(0) + c_local;
  Eigen::Matrix2d S;
  S << sign * Sxx12 / 12, sign * Sxy24 / 24, sign * Sxy24 / 24, sign * Syy12 / 12;
  out.J_C = S - out.area * c_local * c_local.transpose();
  return out;
}

MassProperties2 polygon_lamina_with_mass(double m, const Eigen::Matrix2Xd& vertices) {
  const PolygonMoments pm = polygon_moments(vertices);
  return make(__func__, false, m, pm.area, pm.centroid, pm.J_C.trace() / pm.area);
}

MassProperties2 polygon_lamina_with_density(double sigma, const Eigen::Matrix2Xd& vertices) {
  const PolygonMoments pm = polygon_moments(vertices);
  return make(__func__, true, sigma, pm.area, pm.centroid, pm.J_C.trace() / pm.area);
}

}  // namespace rigid::mass

auto fmt::formatter<rigid::MassProperties2>::format(const rigid::MassProperties2& mp,
                                                    fmt::format_context& ctx) const
    -> decltype(ctx.out()) {
  const std::string text = fmt::format("MassProperties2{{mass: {} kg, com: {} m, moment_com: {} kg·m²}}",
                                       mp.mass(), rigid::to_string(mp.com().transpose()),
                                       mp.moment_com());
  return fmt::formatter<std::string_view>::format(text, ctx);
}
