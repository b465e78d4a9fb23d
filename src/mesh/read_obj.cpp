// Wavefront OBJ: the `v` and `f` records.
//
// Read here rather than with tinyobjloader: its number parser reads "nan" and "inf" as 0
// without a word, Debian's default build (libtinyobjloader.so) stores float coordinates (a
// box 1000 km from the origin loses its size), its errors carry no line number, and it opens
// the files that `mtllib` names (a path to /dev/zero reads forever). A mass computation needs only vertices and faces: this
// reader parses them in double precision with the C-locale from_chars, refuses non-finite
// coordinates with their line, and never opens another file.
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "detail/read_text.hpp"
#include "detail/triangulate.hpp"
#include "rigid/mesh/read_mesh.hpp"

namespace rigid::mesh {
namespace {

using Index = std::uint32_t;

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// The whitespace-separated fields of one logical line, comments removed.
void split(std::string_view line, std::vector<std::string_view>& fields) {
  fields.clear();
  const std::size_t hash = line.find('#');
  if (hash != std::string_view::npos) line = line.substr(0, hash);
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) fields.push_back(line.substr(start, i - start));
  }
}

struct Face {
  int line;
  std::size_t first;  // into the index list
  std::size_t count;
};

}  // namespace

TriangleMesh read_obj(const std::string& path, double scale) {
  const std::string data = detail::slurp(path);
  TriangleMesh mesh;
  std::vector<long long> indices;  // 0-based, resolved; range-checked once all vertices are read
  std::vector<Face> faces;
  std::vector<std::string_view> fields;
  std::string joined;  // a line continued with a trailing backslash
  std::size_t pos = 0;
  int line = 0;
  while (pos < data.size()) {
    ++line;
    const int first_line = line;
    std::size_t eol = data.find('\n', pos);
    if (eol == std::string::npos) eol = data.size();
    std::string_view text(data.data() + pos, eol - pos);
    pos = eol + 1;
    // `\` at the end of a line continues it on the next
    const auto continued = [](std::string_view t) {
      while (!t.empty() && is_space(t.back())) t.remove_suffix(1);
      return !t.empty() && t.back() == '\\';
    };
    if (continued(text)) {
      joined.clear();
      while (continued(text)) {
        while (is_space(text.back())) text.remove_suffix(1);
        joined.append(text.substr(0, text.size() - 1)).push_back(' ');
        if (pos >= data.size()) {
          text = {};
          break;
        }
        ++line;
        eol = data.find('\n', pos);
        if (eol == std::string::npos) eol = data.size();
        text = std::string_view(data.data() + pos, eol - pos);
        pos = eol + 1;
      }
      joined.append(text);
      text = joined;
    }
    split(text, fields);
    if (fields.empty()) continue;
    if (fields[0] == "v") {
      if (fields.size() < 4) {
        detail::fail_line(path, first_line,
                          fmt::format("a vertex with {} coordinates: expected 'v x y z'",
                                      fields.size() - 1));
      }
      Eigen::Vector3d p;
      for (int c = 0; c < 3; ++c) {
        const std::string_view f = fields[static_cast<std::size_t>(c) + 1];
        const std::optional<double> x = detail::parse_double(f);
        if (!x) {
          detail::fail_line(path, first_line,
                            fmt::format("'{}' is not a number: expected a vertex coordinate",
                                        f.substr(0, 40)));
        }
        if (!std::isfinite(*x)) {
          detail::fail_line(path, first_line,
                            fmt::format("a coordinate of vertex {} is {}: expected a finite "
                                        "number",
                                        mesh.vertices.size() + 1, f.substr(0, 40)));
        }
        p[c] = *x * scale;
      }
      if (mesh.vertices.size() >= 0xfffffffeu) {
        detail::fail_line(path, first_line, "more than 2³² − 2 vertices: not supported");
      }
      mesh.vertices.push_back(p);
    } else if (fields[0] == "f") {
      if (fields.size() < 4) {
        detail::fail_line(path, first_line,
                          fmt::format("face {} with {} vertices: expected at least 3",
                                      faces.size() + 1, fields.size() - 1));
      }
      const std::size_t first = indices.size();
      for (std::size_t j = 1; j < fields.size(); ++j) {
        // `v`, `v/vt`, `v//vn` or `v/vt/vn`: the vertex index is before the first slash
        const std::string_view f = fields[j];
        const std::string_view v = f.substr(0, f.find('/'));
        long long i = 0;
        const char* b = v.data() + (v.size() > 1 && v.front() == '+' ? 1 : 0);
        const auto [p, ec] = std::from_chars(b, v.data() + v.size(), i);
        if (v.empty() || ec != std::errc() || p != v.data() + v.size() || i == 0) {
          detail::fail_line(path, first_line,
                            fmt::format("'{}' is not a vertex reference: expected a vertex "
                                        "index counted from 1 (or back from -1)",
                                        f.substr(0, 40)));
        }
        // negative: relative to the vertices read so far (-1 is the last)
        const long long resolved =
            i > 0 ? i - 1 : static_cast<long long>(mesh.vertices.size()) + i;
        if (resolved < 0) {
          detail::fail_line(path, first_line,
                            fmt::format("face {} refers to vertex {}, before the first vertex "
                                        "({} read so far)",
                                        faces.size() + 1, i, mesh.vertices.size()));
        }
        indices.push_back(resolved);
      }
      faces.push_back({first_line, first, fields.size() - 1});
    }
    // every other record (vt, vn, g, o, s, usemtl, mtllib, l, p, ...) carries nothing a mass
    // needs: materials in particular are never opened
  }
  if (faces.empty()) detail::fail_file(path, "no faces: not a mesh OBJ file (no 'f' records)");
  std::vector<Index> poly;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    poly.clear();
    for (std::size_t j = 0; j < faces[f].count; ++j) {
      const long long i = indices[faces[f].first + j];
      if (i >= static_cast<long long>(mesh.vertices.size())) {
        detail::fail_line(path, faces[f].line,
                          fmt::format("face {} uses vertex {}: the file has {} vertices", f + 1,
                                      i + 1, mesh.vertices.size()));
      }
      poly.push_back(static_cast<Index>(i));
    }
    const auto problem = detail::triangulate_polygon(mesh.vertices, poly, mesh.triangles);
    if (problem) detail::fail_line(path, faces[f].line, fmt::format("face {}: {}", f + 1, *problem));
  }
  return mesh;
}

}  // namespace rigid::mesh
