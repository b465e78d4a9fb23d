#include "rigid/mesh/triangle_mesh.hpp"

#include <utility>

namespace rigid::mesh {

std::array<Eigen::Vector3d, 2> TriangleMesh::bounding_box() const {
  if (vertices.empty()) return {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  Eigen::Vector3d lo = vertices.front();
  Eigen::Vector3d hi = vertices.front();
  for (const auto& p : vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {lo, hi};
}

double TriangleMesh::bounding_box_diagonal() const {
  const auto box = bounding_box();
  return (box[1] - box[0]).norm();
}

void TriangleMesh::scale(double factor) {
  for (auto& p : vertices) p *= factor;
}

void TriangleMesh::translate(const Eigen::Vector3d& d_M) {
  for (auto& p : vertices) p += d_M;
}

void TriangleMesh::reverse_winding() {
  for (auto& t : triangles) std::swap(t[1], t[2]);
}

}  // namespace rigid::mesh
