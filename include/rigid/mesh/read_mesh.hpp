#pragma once

#include <string>
#include <string_view>

#include "rigid/mesh/triangle_mesh.hpp"

namespace rigid::mesh {

/// Length of one file unit in metres: "m" → 1, "cm" → 0.01, "mm" → 0.001, "in" → 0.0254.
/// @throws rigid::Error naming the unit and the accepted ones.
[[nodiscard]] double unit_scale(std::string_view unit);

/// Reads a triangle mesh from STL (binary or ASCII; a binary file whose 80-byte header starts
/// with "solid" is recognised by its size), OBJ (polygons fan-triangulated), PLY (ASCII,
/// binary little- and big-endian) or OFF, chosen by the file extension (case-insensitive).
/// Vertices are multiplied by `scale` (metres per file unit). Polygons are fan-triangulated.
/// Binary STL repeats every vertex per triangle: copies with bitwise equal float32 coordinates
/// are shared as the file is read (the rest of welding is repair_mesh's); ASCII STL is
/// returned as one vertex per corner.
/// @throws rigid::Error starting with the file name and, where it applies, `line N` or
/// `byte N`, for unreadable, empty, truncated or malformed files, non-finite coordinates
/// and indices out of range.
[[nodiscard]] TriangleMesh read_mesh(const std::string& path, double scale = 1.0);

/// Readers by format, for files whose extension does not say it (same contract as read_mesh).
[[nodiscard]] TriangleMesh read_stl(const std::string& path, double scale = 1.0);
[[nodiscard]] TriangleMesh read_obj(const std::string& path, double scale = 1.0);
[[nodiscard]] TriangleMesh read_ply(const std::string& path, double scale = 1.0);
[[nodiscard]] TriangleMesh read_off(const std::string& path, double scale = 1.0);

/// Writes a binary STL (80-byte header, count, 50 bytes per triangle; float32 coordinates).
void write_stl_binary(const TriangleMesh& mesh, const std::string& path);

}  // namespace rigid::mesh
