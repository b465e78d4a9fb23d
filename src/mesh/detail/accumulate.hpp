#pragma once
// The volume sums of volume_moments, with each compiled variant callable by name (private to
// the mesh module; the tests compare the variants bit for bit).

#include <Eigen/Core>

#include "rigid/mesh/triangle_mesh.hpp"

namespace rigid::mesh::detail {

/// Σ d, Σ d s and the upper triangle of Σ d (a aᵀ + b bᵀ + c cᵀ + s sᵀ) over the triangles,
/// d = det[a b c], s = a + b + c, corners relative to the reference point p_OR.
struct VolumeSums {
  double measure = 0, fx = 0, fy = 0, fz = 0;
  double xx = 0, yy = 0, zz = 0, xy = 0, xz = 0, yz = 0;
};

/// The sums compiled for baseline x86-64 (SSE2 on x86-64; the target's default elsewhere).
[[nodiscard]] VolumeSums accumulate_volume_baseline(const TriangleMesh& mesh,
                                                    const Eigen::Vector3d& p_OR);

/// True where accumulate_volume_avx2 exists (x86-64 Linux, GCC) and this CPU runs it.
[[nodiscard]] bool avx2_available();

/// The same sums compiled for AVX2: the same operations in the same order (no FMA), so the
/// result is bitwise that of accumulate_volume_baseline. Call only when avx2_available();
/// elsewhere it is the baseline.
[[nodiscard]] VolumeSums accumulate_volume_avx2(const TriangleMesh& mesh,
                                                const Eigen::Vector3d& p_OR);

/// The variant for this CPU (AVX2 when available), chosen once.
[[nodiscard]] VolumeSums accumulate_volume(const TriangleMesh& mesh, const Eigen::Vector3d& p_OR);

}  // namespace rigid::mesh::detail
