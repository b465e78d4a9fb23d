#pragma once

#include <cmath>
#include <numbers>

#include "rigid/mesh/triangle_mesh.hpp"

namespace rigid::test {

/// Axis-aligned box [0,a]×[0,b]×[0,c], 12 outward triangles.
inline mesh::TriangleMesh box_mesh(double a, double b, double c) {
  mesh::TriangleMesh m;
  for (int i = 0; i < 8; ++i) {
    m.vertices.emplace_back((i & 1) ? a : 0.0, (i & 2) ? b : 0.0, (i & 4) ? c : 0.0);
  }
  // Quads listed counter-clockwise seen from outside.
  const std::uint32_t q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                 {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : q) {
    m.triangles.push_back({f[0], f[1], f[2]});
    m.triangles.push_back({f[0], f[2], f[3]});
  }
  return m;
}

/// Tetrahedron with vertices p0..p3 (p3 on the positive side of p0p1p2 by right hand).
inline mesh::TriangleMesh tetra_mesh(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                     const Eigen::Vector3d& p2, const Eigen::Vector3d& p3) {
  mesh::TriangleMesh m;
  m.vertices = {p0, p1, p2, p3};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  return m;
}

/// UV sphere of radius r with n rings (2n segments); vertices exactly on the sphere.
inline mesh::TriangleMesh uv_sphere(double r, int n) {
  mesh::TriangleMesh m;
  const int seg = 2 * n;
  m.vertices.emplace_back(0, 0, r);
  for (int i = 1; i < n; ++i) {
    const double th = std::numbers::pi * i / n;
    for (int j = 0; j < seg; ++j) {
      const double ph = 2 * std::numbers::pi * j / seg;
      m.vertices.emplace_back(r * std::sin(th) * std::cos(ph), r * std::sin(th) * std::sin(ph),
                              r * std::cos(th));
    }
  }
  m.vertices.emplace_back(0, 0, -r);
  const auto idx = [&](int ring, int j) {
    return static_cast<std::uint32_t>(1 + (ring - 1) * seg + (j % seg));
  };
  const auto south = static_cast<std::uint32_t>(m.vertices.size() - 1);
  for (int j = 0; j < seg; ++j) m.triangles.push_back({0, idx(1, j), idx(1, j + 1)});
  for (int i = 1; i + 1 < n; ++i) {
    for (int j = 0; j < seg; ++j) {
      m.triangles.push_back({idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)});
      m.triangles.push_back({idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)});
    }
  }
  for (int j = 0; j < seg; ++j) m.triangles.push_back({south, idx(n - 1, j + 1), idx(n - 1, j)});
  return m;
}

}  // namespace rigid::test
