#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "rigid/mesh/triangle_mesh.hpp"

namespace rigid::mesh {

/// The largest mesh file read (bytes): 2 GiB, a binary STL of 43 million triangles. Larger
/// files are refused before they are opened.
inline constexpr std::uint64_t kMaxMeshFileBytes = std::uint64_t{1} << 31;

/// The file extensions read_mesh reads, as its messages list them.
inline constexpr std::string_view kSupportedExtensions = ".stl, .obj, .ply and .off";

/// Length of one file unit in metres: "m" → 1, "cm" → 0.01, "mm" → 0.001, "in" → 0.0254.
/// @throws rigid::Error naming the unit and the accepted ones.
[[nodiscard]] double unit_scale(std::string_view unit);

/// Reads a triangle mesh from STL (binary or ASCII; a binary file whose 80-byte header starts
/// with "solid" is recognised by its size; every `solid … endsolid` block of an ASCII file is
/// read), OBJ (`v` and `f` records, read in double precision; materials are never opened),
/// PLY (ASCII, binary little- and big-endian) or OFF, chosen by the file extension
/// (case-insensitive). Vertices are multiplied by `scale` (metres per file unit). Polygons
/// with more than three vertices are triangulated in their plane (ear clipping), so concave
/// faces keep their area; a polygon that is not planar (beyond detail::kPlanarityTolerance of
/// its size) or not simple is refused. Binary STL repeats every vertex per triangle: copies
/// with bitwise equal float32 coordinates are shared as the file is read (the rest of welding
/// is repair_mesh's); ASCII STL is returned as one vertex per corner.
/// Limits, checked before anything is read or allocated: only regular files (a directory, a
/// device such as /dev/zero, a FIFO are refused by type), at most kMaxMeshFileBytes, and the
/// counts a header declares (binary STL triangles, PLY elements, OFF vertices and faces) must
/// fit in the file's size.
/// @throws rigid::Error starting with the file name and, where it applies, `line N` or
/// `byte N`, for unreadable, empty, truncated or malformed files, non-finite coordinates
/// (NaN, infinity, beyond the double range) in every format, indices out of range,
/// non-planar or self-intersecting polygons and unsupported extensions.
[[nodiscard]] TriangleMesh read_mesh(const std::string& path, double scale = 1.0);

/// Readers by format, for files whose extension does not say it (same contract as read_mesh).
[[nodiscard]] TriangleMesh read_stl(const std::string& path, double scale = 1.0);
[[nodiscard]] TriangleMesh read_obj(const std::string& path, double scale = 1.0);
[[nodiscard]] TriangleMesh read_ply(const std::string& path, double scale = 1.0);
[[nodiscard]] TriangleMesh read_off(const std::string& path, double scale = 1.0);

/// The bytes of a binary STL (80-byte header, count, 50 bytes per triangle; float32
/// coordinates), for a caller that writes them its own way (rigid.mesh.write_stl: atomically).
[[nodiscard]] std::string stl_binary(const TriangleMesh& mesh);
/// Writes stl_binary(mesh) to `path` with a plain stream (tests and benchmarks; a user-facing
/// output goes through io::write_file_atomically).
void write_stl_binary(const TriangleMesh& mesh, const std::string& path);

}  // namespace rigid::mesh
