#include "rigid/mesh/read_mesh.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Geometry>
#include "detail/read_mesh.hpp"
#include "detail/read_text.hpp"
#include "detail/triangulate.hpp"
#include "rigid/common/error.hpp"

namespace rigid::mesh {
namespace {

using Index = std::uint32_t;
using detail::fail_byte;
using detail::fail_file;
using detail::fail_line;
using detail::slurp;
using detail::Tokens;

// Appends the triangles of polygon `face` (counted from 1) read at `line` (or at byte `byte`
// of a binary file, when line is 0); a polygon triangulate_polygon refuses is an error there.
void add_polygon(const std::string& path, TriangleMesh& mesh, const std::vector<Index>& poly,
                 std::size_t face, int line, std::uint64_t byte = 0) {
  const auto problem = detail::triangulate_polygon(mesh.vertices, poly, mesh.triangles);
  if (!problem) return;
  const std::string msg = fmt::format("face {}: {}", face, *problem);
  if (line > 0) fail_line(path, line, msg);
  fail_byte(path, byte, msg);
}

template <class T>
T load(const char* p, bool big_endian) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big)) {
    auto* b = reinterpret_cast<unsigned char*>(&v);
    std::reverse(b, b + sizeof(T));
  }
  return v;
}

// Reads n binary STL records from `in` (positioned after the 84-byte header) in chunks into
// one reused buffer: the file is never held whole. The copies of a vertex in an STL file are
// one float32 value written again for every triangle, so corners are shared as they are read
// by exact equality of the three float32 bit patterns (−0 = +0; open addressing, the key held
// in the slot): the 3 n-vertex soup is never built, and the first copy's value is kept.
TriangleMesh read_stl_binary_records(const std::string& path, std::istream& in, std::uint32_t n,
                                     double scale) {
  struct Slot {
    std::uint32_t x, y, z;
    Index index;  // kEmpty: free
  };
  constexpr Index kEmpty = 0xffffffffu;
  const auto hash = [](std::uint32_t x, std::uint32_t y, std::uint32_t z) {
    std::uint64_t h = x * 0x9E3779B97F4A7C15ull;
    h ^= y * 0xC2B2AE3D27D4EB4Full;
    h ^= z * 0x165667B19E3779F9ull;
    h ^= h >> 29;
    h *= 0xBF58476D1CE4E5B9ull;
    return h ^ (h >> 32);
  };
  // a closed mesh has about n/2 vertices: n slots keep the table at most half full
  std::size_t capacity = 64;
  while (capacity < n) capacity *= 2;
  std::vector<Slot> table(capacity, Slot{0, 0, 0, kEmpty});
  TriangleMesh mesh;
  mesh.vertices.reserve(n / 2 + 16);
  mesh.triangles.reserve(n);
  const auto vertex = [&](const std::uint32_t* b) {
    // −0 and +0 are one position
    const std::uint32_t x = b[0] == 0x80000000u ? 0 : b[0];
    const std::uint32_t y = b[1] == 0x80000000u ? 0 : b[1];
    const std::uint32_t z = b[2] == 0x80000000u ? 0 : b[2];
    std::size_t mask = capacity - 1;
    std::size_t slot = hash(x, y, z) & mask;
    while (table[slot].index != kEmpty &&
           (table[slot].x != x || table[slot].y != y || table[slot].z != z)) {
      slot = (slot + 1) & mask;
    }
    if (table[slot].index != kEmpty) return table[slot].index;
    const auto id = static_cast<Index>(mesh.vertices.size());
    table[slot] = {x, y, z, id};
    mesh.vertices.emplace_back(static_cast<double>(std::bit_cast<float>(b[0])) * scale,
                               static_cast<double>(std::bit_cast<float>(b[1])) * scale,
                               static_cast<double>(std::bit_cast<float>(b[2])) * scale);
    if (2 * mesh.vertices.size() > capacity) {  // rehash into twice the slots
      std::vector<Slot> old(capacity * 2, Slot{0, 0, 0, kEmpty});
      old.swap(table);
      capacity *= 2;
      mask = capacity - 1;
      for (const Slot& e : old) {
        if (e.index == kEmpty) continue;
        std::size_t s = hash(e.x, e.y, e.z) & mask;
        while (table[s].index != kEmpty) s = (s + 1) & mask;
        table[s] = e;
      }
    }
    return id;
  };
  constexpr std::size_t kRecord = 50;
  constexpr std::size_t kChunk = 1 << 14;  // triangles per read: 800 kB, stays in cache
  const auto buffer = std::make_unique_for_overwrite<char[]>(kChunk * kRecord);
  for (std::size_t first = 0; first < n; first += kChunk) {
    const std::size_t count = std::min<std::size_t>(kChunk, n - first);
    if (!in.read(buffer.get(), static_cast<std::streamsize>(count * kRecord))) {
      fail_byte(path, 84 + kRecord * first, "reading the file failed");
    }
    for (std::size_t i = 0; i < count; ++i) {
      const char* rec = buffer.get() + kRecord * i + 12;  // skip the normal
      // little-endian float32 bit patterns; a float is finite unless its exponent bits are
      // all ones (Inf, NaN)
      std::uint32_t bits[9];
      bool finite = true;
      for (int k = 0; k < 9; ++k) {
        bits[k] = load<std::uint32_t>(rec + 4 * k, false);
        finite &= (bits[k] & 0x7f800000u) != 0x7f800000u;
      }
      const std::size_t t = first + i;
      if (!finite) {
        for (int k = 0; k < 9; ++k) {
          const float f = std::bit_cast<float>(bits[k]);
          if (!std::isfinite(f)) {
            fail_byte(path, 84 + kRecord * t + 12 + 4 * static_cast<std::size_t>(k),
                      fmt::format("coordinate of triangle {} is {}: expected a finite number",
                                  t + 1, f));
          }
        }
      }
      const Index a = vertex(bits);
      const Index b = vertex(bits + 3);
      const Index c = vertex(bits + 6);
      mesh.triangles.push_back({a, b, c});
    }
  }
  return mesh;
}

TriangleMesh read_stl_binary(const std::string& path, const std::string& data, double scale) {
  if (data.size() < 84) {
    fail_byte(path, data.size(),
              fmt::format("truncated binary STL: {} bytes, expected at least 84 (header and "
                          "triangle count)",
                          data.size()));
  }
  const auto n = load<std::uint32_t>(data.data() + 80, false);
  const std::uint64_t expected = 84 + 50ull * n;
  if (expected != data.size()) {
    fail_byte(path, 80,
              fmt::format("binary STL triangle count {} needs {} bytes but the file has {}: "
                          "truncated or corrupt",
                          n, expected, data.size()));
  }
  std::istringstream in(data.substr(84));
  return read_stl_binary_records(path, in, n, scale);
}

// ASCII STL: one or more `solid NAME … endsolid NAME` blocks (several exporters write one
// block per part or per colour), each a list of facets. Every block is read: the mesh is
// their union.
TriangleMesh read_stl_ascii(const std::string& path, const std::string& data, double scale) {
  Tokens body(path, data, 0, 1, false);
  TriangleMesh mesh;
  std::vector<Index> poly;
  std::size_t facet = 0;
  for (int solids = 0;; ++solids) {
    const auto start = body.next();
    if (!start) {
      if (solids > 0) break;
      fail_line(path, body.current_line(), "the file is empty: expected 'solid'");
    }
    if (*start != "solid") {
      fail_line(path, body.line(), fmt::format("'{}': expected 'solid'{}", start->substr(0, 40),
                                               solids > 0 ? " or the end of the file" : ""));
    }
    body.skip_line();  // the solid's name runs to the end of its line
    for (;;) {
      const auto t = body.next();
      if (!t) fail_line(path, body.current_line(), "unexpected end of file: expected 'endsolid'");
      if (*t == "endsolid") break;
      if (*t != "facet") {
        fail_line(path, body.line(),
                  fmt::format("'{}': expected 'facet' or 'endsolid'", t->substr(0, 40)));
      }
      ++facet;
      const int facet_line = body.line();
      if (body.expect("'normal'") != "normal") fail_line(path, body.line(), "expected 'normal'");
      for (int c = 0; c < 3; ++c) (void)body.number("a normal component", false);
      if (body.expect("'outer'") != "outer") fail_line(path, body.line(), "expected 'outer loop'");
      if (body.expect("'loop'") != "loop") fail_line(path, body.line(), "expected 'outer loop'");
      poly.clear();
      for (;;) {
        const auto w = body.expect("'vertex' or 'endloop'");
        if (w == "endloop") break;
        if (w != "vertex") {
          fail_line(path, body.line(),
                    fmt::format("'{}': expected 'vertex' or 'endloop'", w.substr(0, 40)));
        }
        Eigen::Vector3d p;
        for (int c = 0; c < 3; ++c) p[c] = body.number("a vertex coordinate") * scale;
        if (mesh.vertices.size() >= 0xfffffffeu) {
          fail_line(path, body.line(), "more than 2³² − 2 vertices: not supported");
        }
        poly.push_back(static_cast<Index>(mesh.vertices.size()));
        mesh.vertices.push_back(p);
      }
      if (poly.size() < 3) {
        fail_line(path, body.line(),
                  fmt::format("facet with {} vertices: expected at least 3", poly.size()));
      }
      add_polygon(path, mesh, poly, facet, facet_line);
      if (body.expect("'endfacet'") != "endfacet") {
        fail_line(path, body.line(), "expected 'endfacet'");
      }
    }
    body.skip_line();  // `endsolid NAME`
  }
  return mesh;
}

std::string extension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  const auto slash = path.find_last_of("/\\");
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e = path.substr(dot + 1);
  for (auto& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

void check_indices(const std::string& path, const TriangleMesh& mesh) {
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    for (Index i : mesh.triangles[f]) {
      if (i >= mesh.vertices.size()) {
        rigid::detail::throw_error_at(SourceLocation{path, 0, 0},
                               fmt::format("face {} uses vertex index {}: the file has {} "
                                           "vertices (indices 0 to {})",
                                           f + 1, i, mesh.vertices.size(),
                                           static_cast<long long>(mesh.vertices.size()) - 1));
      }
    }
  }
}

// PLY scalar types.
enum class PlyType { i8, u8, i16, u16, i32, u32, f32, f64 };

std::optional<PlyType> ply_type(std::string_view s) {
  if (s == "char" || s == "int8") return PlyType::i8;
  if (s == "uchar" || s == "uint8") return PlyType::u8;
  if (s == "short" || s == "int16") return PlyType::i16;
  if (s == "ushort" || s == "uint16") return PlyType::u16;
  if (s == "int" || s == "int32") return PlyType::i32;
  if (s == "uint" || s == "uint32") return PlyType::u32;
  if (s == "float" || s == "float32") return PlyType::f32;
  if (s == "double" || s == "float64") return PlyType::f64;
  return std::nullopt;
}

std::size_t ply_size(PlyType t) {
  switch (t) {
    case PlyType::i8:
    case PlyType::u8: return 1;
    case PlyType::i16:
    case PlyType::u16: return 2;
    case PlyType::i32:
    case PlyType::u32:
    case PlyType::f32: return 4;
    case PlyType::f64: return 8;
  }
  return 0;
}

double ply_load(PlyType t, const char* p, bool big) {
  switch (t) {
    case PlyType::i8: return load<std::int8_t>(p, big);
    case PlyType::u8: return load<std::uint8_t>(p, big);
    case PlyType::i16: return load<std::int16_t>(p, big);
    case PlyType::u16: return load<std::uint16_t>(p, big);
    case PlyType::i32: return load<std::int32_t>(p, big);
    case PlyType::u32: return load<std::uint32_t>(p, big);
    case PlyType::f32: return load<float>(p, big);
    case PlyType::f64: return load<double>(p, big);
  }
  return 0;
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::f32;
  bool list = false;
  PlyType count_type = PlyType::u8;
};

struct PlyElement {
  std::string name;
  int line = 0;  // of its `element` line in the header
  std::size_t count = 0;
  std::vector<PlyProperty> props;
};

// A PLY header: its elements, its format and where the data after it begin.
struct PlyHeader {
  std::vector<PlyElement> elements;
  std::string format;
  std::size_t pos = 0;  // the first byte after the header
  int line = 0;         // the header's last line (end_header)
};

// The rest of a `property` header line: `<type> <name>` or `list <count type> <type> <name>`.
PlyProperty parse_ply_property(const std::string& path, int line, std::istringstream& ls) {
  PlyProperty p;
  std::string t;
  ls >> t;
  if (t == "list") {
    std::string ct, it;
    ls >> ct >> it >> p.name;
    const auto a = ply_type(ct);
    const auto b = ply_type(it);
    if (!a || !b) fail_line(path, line, fmt::format("unknown list types '{} {}'", ct, it));
    p.list = true;
    p.count_type = *a;
    p.type = *b;
  } else {
    ls >> p.name;
    const auto a = ply_type(t);
    if (!a) fail_line(path, line, fmt::format("unknown property type '{}'", t));
    p.type = *a;
  }
  return p;
}

// Reads the header: lines up to "end_header", with the 'ply' magic line first.
PlyHeader read_ply_header(const std::string& path, const std::string& data) {
  PlyHeader h;
  std::size_t& pos = h.pos;
  int& line = h.line;
  bool ended = false;
  while (pos < data.size()) {
    std::size_t eol = data.find('\n', pos);
    if (eol == std::string::npos) eol = data.size();
    std::string text = data.substr(pos, eol - pos);
    if (!text.empty() && text.back() == '\r') text.pop_back();
    pos = eol + 1;
    ++line;
    std::istringstream ls(text);
    std::string word;
    ls >> word;
    if (line == 1) {
      if (word != "ply") fail_line(path, 1, "missing 'ply' magic line: not a PLY file");
      continue;
    }
    if (word == "format") {
      ls >> h.format;
      if (h.format != "ascii" && h.format != "binary_little_endian" && h.format != "binary_big_endian") {
        fail_line(path, line, fmt::format("format '{}': expected ascii, binary_little_endian or "
                                          "binary_big_endian",
                                          h.format));
      }
    } else if (word == "element") {
      PlyElement e;
      long long n = -1;
      ls >> e.name >> n;
      if (!ls || n < 0) fail_line(path, line, "expected 'element <name> <count>'");
      e.count = static_cast<std::size_t>(n);
      e.line = line;
      h.elements.push_back(e);
    } else if (word == "property") {
      if (h.elements.empty()) fail_line(path, line, "property before any element");
      h.elements.back().props.push_back(parse_ply_property(path, line, ls));
    } else if (word == "end_header") {
      ended = true;
      break;
    } else if (word == "comment" || word == "obj_info" || word.empty()) {
      continue;
    } else {
      fail_line(path, line, fmt::format("unknown header keyword '{}'", word));
    }
  }
  if (!ended) fail_line(path, line, "no 'end_header': truncated PLY header");
  if (h.format.empty()) fail_line(path, line, "no 'format' line in the PLY header");
  return h;
}

// Limits before allocation: every row of an element takes at least the bytes of its
// scalars and list counts (binary) or two characters per property, a digit and a separator
// (ascii); the declared counts must fit in what follows the header. An element without
// properties would hold rows of no data, which no file size bounds: refused.
void check_ply_counts(const std::string& path, const std::string& data, const PlyHeader& h,
                      bool ascii) {
  std::uint64_t left = data.size() - std::min(h.pos, data.size()) + (ascii ? 1 : 0);
  for (const auto& e : h.elements) {
    std::uint64_t row = 0;
    if (e.props.empty() && e.count > 0) {
      fail_line(path, e.line,
                fmt::format("element {} declares {} rows but no properties: expected at least "
                            "one property per element (rows without data cannot be counted "
                            "in the file)",
                            e.name, e.count));
    }
    for (const auto& p : e.props) row += ascii ? 2 : ply_size(p.list ? p.count_type : p.type);
    if (row == 0) continue;
    if (e.count > left / row) {
      fail_line(path, e.line,
                fmt::format("element {} declares {} rows of at least {} bytes each, but only {} "
                            "bytes of data follow the header: truncated or corrupt",
                            e.name, e.count, row, left));
    }
    left -= e.count * row;
    if (e.name == "vertex" && e.count >= 0xfffffffeu) {
      fail_line(path, e.line, fmt::format("{} vertices: at most 2³² − 2 are supported", e.count));
    }
  }
}

// Which properties of an element the mesh uses: x, y and z of a vertex, the index list of a
// face (-1: none).
struct PlyRoles {
  bool is_vertex = false, is_face = false;
  int xyz[3] = {-1, -1, -1};
  int index_prop = -1;
};

// The roles of e's properties; a vertex without x, y or z, or a face without indices, is refused.
PlyRoles ply_roles(const std::string& path, const PlyElement& e) {
  PlyRoles roles;
  roles.is_vertex = e.name == "vertex";
  roles.is_face = e.name == "face";
  for (std::size_t k = 0; k < e.props.size(); ++k) {
    const auto& p = e.props[k];
    if (roles.is_vertex && !p.list) {
      if (p.name == "x") roles.xyz[0] = static_cast<int>(k);
      if (p.name == "y") roles.xyz[1] = static_cast<int>(k);
      if (p.name == "z") roles.xyz[2] = static_cast<int>(k);
    }
    if (roles.is_face && p.list && (p.name == "vertex_indices" || p.name == "vertex_index")) {
      roles.index_prop = static_cast<int>(k);
    }
  }
  if (roles.is_vertex && (roles.xyz[0] < 0 || roles.xyz[1] < 0 || roles.xyz[2] < 0)) {
    fail_line(path, e.line, "element vertex lacks x, y or z properties");
  }
  if (roles.is_face && roles.index_prop < 0) {
    fail_line(path, e.line, "element face lacks a vertex_indices list");
  }
  return roles;
}

// Reads the elements after a PLY header (ascii or binary) into a mesh: the vertices scaled,
// the faces triangulated, every other element read over.
class PlyDataReader {
 public:
  PlyDataReader(const std::string& path, const std::string& data, const PlyHeader& h, double scale)
      : path_(path), data_(data), ascii_(h.format == "ascii"), big_(h.format == "binary_big_endian"),
        scale_(scale), pos_(h.pos), tok_(path, data, h.pos, h.line + 1, false) {}

  // reads the rows of element e (an element without properties has none)
  void read_element(const PlyElement& e) {
    const bool is_vertex = e.name == "vertex";
    const bool is_face = e.name == "face";
    if (e.props.empty() && !is_vertex && !is_face) return;  // a count of 0 (others refused)
    const PlyRoles roles = ply_roles(path_, e);
    if (is_vertex) {
      nv_ = e.count;
      mesh_.vertices.reserve(e.count);  // checked against the file's size above
    }
    for (std::size_t r = 0; r < e.count; ++r) read_row(e, roles, r);
  }

  [[nodiscard]] TriangleMesh& mesh() { return mesh_; }

 private:
  // row r of e: a vertex appended, a face's polygon triangulated
  void read_row(const PlyElement& e, const PlyRoles& roles, std::size_t r) {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    poly_.clear();
    for (std::size_t k = 0; k < e.props.size(); ++k) {
      if (e.props[k].list) {
        read_list(e, roles, r, k);
      } else {
        read_scalar(e, roles, r, k, p);
      }
    }
    if (roles.is_vertex) mesh_.vertices.push_back(p);
    if (roles.is_face) {
      if (poly_.size() < 3) {
        const std::string msg =
            fmt::format("face {} has {} vertices: expected at least 3", r + 1, poly_.size());
        if (ascii_) fail_line(path_, tok_.line(), msg);
        fail_byte(path_, pos_, msg);
      }
      add_polygon(path_, mesh_, poly_, r + 1, ascii_ ? tok_.line() : 0, pos_);
    }
  }

  // the binary value of `type` at pos_, which moves past it; refused past the end of the data
  double binary_value(PlyType type, const PlyElement& e, std::size_t r) {
    if (pos_ + ply_size(type) > data_.size()) {
      fail_byte(path_, pos_, fmt::format("truncated PLY: element {} {} of {}", e.name,
                                         r + 1, e.count));
    }
    const double v = ply_load(type, data_.data() + pos_, big_);
    pos_ += ply_size(type);
    return v;
  }

  // a list's length, 0 to 10^6
  std::size_t list_length(const PlyProperty& prop, const PlyElement& e, std::size_t r) {
    if (ascii_) {
      const long long c = tok_.integer("a list length");
      if (c < 0 || c > 1'000'000) {
        fail_line(path_, tok_.line(), fmt::format("list length {}: expected 0 to 10^6", c));
      }
      return static_cast<std::size_t>(c);
    }
    const double c = binary_value(prop.count_type, e, r);
    if (!(c >= 0 && c <= 1e6)) {
      fail_byte(path_, pos_, fmt::format("list length {}: expected 0 to 10^6", c));
    }
    return static_cast<std::size_t>(c);
  }

  // list property k of row r; a face's vertex indices, each checked, go to poly_
  void read_list(const PlyElement& e, const PlyRoles& roles, std::size_t r, std::size_t k) {
    const auto& prop = e.props[k];
    const std::size_t n = list_length(prop, e, r);
    for (std::size_t j = 0; j < n; ++j) {
      const double v = ascii_ ? static_cast<double>(tok_.integer("a list entry"))
                              : binary_value(prop.type, e, r);
      if (roles.is_face && static_cast<int>(k) == roles.index_prop) {
        if (!(v >= 0 && v < static_cast<double>(nv_))) {
          const std::string msg = fmt::format(
              "face {} uses vertex index {}: the file has {} vertices", r + 1, v, nv_);
          if (ascii_) fail_line(path_, tok_.line(), msg);
          fail_byte(path_, pos_ - ply_size(prop.type), msg);
        }
        poly_.push_back(static_cast<Index>(v));
      }
    }
  }

  // scalar property k of row r; a vertex coordinate, which must be finite, goes to p (scaled)
  void read_scalar(const PlyElement& e, const PlyRoles& roles, std::size_t r, std::size_t k,
                   Eigen::Vector3d& p) {
    const auto& prop = e.props[k];
    double v = 0;
    std::size_t at = pos_;
    // a coordinate must be finite; other properties (normals, colours) are not used
    const bool coordinate =
        roles.is_vertex && (static_cast<int>(k) == roles.xyz[0] || static_cast<int>(k) == roles.xyz[1] ||
                            static_cast<int>(k) == roles.xyz[2]);
    if (ascii_) {
      v = tok_.number(coordinate ? "a vertex coordinate" : "a property value", coordinate);
    } else {
      v = binary_value(prop.type, e, r);
      if (coordinate && !std::isfinite(v)) {
        fail_byte(path_, at, fmt::format("{} of {} {} is {}: expected a finite number",
                                         prop.name, e.name, r + 1, v));
      }
    }
    for (int c = 0; c < 3; ++c) {
      if (roles.is_vertex && static_cast<int>(k) == roles.xyz[c]) p[c] = v * scale_;
    }
  }

  const std::string& path_;
  const std::string& data_;
  bool ascii_, big_;
  double scale_;
  std::size_t pos_;
  Tokens tok_;
  TriangleMesh mesh_;
  std::size_t nv_ = 0;
  std::vector<Index> poly_;
};

}  // namespace

double unit_scale(std::string_view unit) {
  if (unit == "m") return 1.0;
  if (unit == "cm") return 0.01;
  if (unit == "mm") return 0.001;
  if (unit == "in") return 0.0254;
  RIGID_THROW("unknown unit '{}': expected m, cm, mm or in", unit);
}

namespace {

// read_stl; *binary_records says whether the records were read by read_stl_binary_records.
TriangleMesh read_stl(const std::string& path, double scale, bool* binary_records) {
  *binary_records = true;
  // A binary file is recognised by its size (84 + 50 n), whatever its header says; it is
  // read record by record, never whole. The size is that of a regular file within the limit
  // (mesh_file_size), so the declared count is checked against it before anything is
  // allocated.
  const std::uint64_t size = detail::mesh_file_size(path);
  if (size >= 84) {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail_file(path, "cannot open the file for reading");
    char header[84];
    if (in.read(header, 84)) {
      const auto n = load<std::uint32_t>(header + 80, false);
      if (84 + 50ull * n == size) return read_stl_binary_records(path, in, n, scale);
    }
  }
  const std::string data = slurp(path);
  std::size_t i = 0;
  while (i < data.size() && std::isspace(static_cast<unsigned char>(data[i]))) ++i;
  if (data.compare(i, 5, "solid") == 0) {
    // ASCII unless it contains bytes no text STL has.
    const bool text = std::none_of(data.begin(), data.end(), [](char c) {
      return c == '\0';
    });
    if (text) {
      *binary_records = false;
      return read_stl_ascii(path, data, scale);
    }
  }
  return read_stl_binary(path, data, scale);
}

}  // namespace

TriangleMesh read_stl(const std::string& path, double scale) {
  bool binary = false;
  return read_stl(path, scale, &binary);
}

TriangleMesh read_off(const std::string& path, double scale) {
  const std::string data = slurp(path);
  Tokens tok(path, data, 0, 1, true);
  const auto magic = tok.expect("'OFF'");
  // [ST][C][N]OFF: texture coordinates, colours and normals follow the coordinates on each
  // vertex line; only the coordinates are read.
  if (magic.size() < 3 || magic.substr(magic.size() - 3) != "OFF" ||
      magic.find_first_not_of("STCN") < magic.size() - 3) {
    fail_line(path, tok.line(), fmt::format("'{}': expected the OFF header 'OFF'",
                                            std::string(magic.substr(0, 20))));
  }
  const long long nv = tok.integer("the vertex count");
  const long long nf = tok.integer("the face count");
  (void)tok.integer("the edge count");
  // limits before allocation: a vertex line holds at least three numbers ("0 0 0" and its
  // end of line, 6 bytes), a face line at least four ("3 0 1 2", 8 bytes)
  const auto size = static_cast<long long>(data.size());
  if (nv < 0 || nf < 0 || nv > size / 6 || nf > size / 8 || 6 * nv + 8 * nf > size + 1) {
    fail_line(path, tok.line(),
              fmt::format("the header declares {} vertices and {} faces: expected counts from 0 "
                          "that fit in the file's {} bytes (at least 6 per vertex and 8 per "
                          "face): truncated or corrupt",
                          nv, nf, data.size()));
  }
  TriangleMesh mesh;
  mesh.vertices.reserve(static_cast<std::size_t>(nv));
  for (long long i = 0; i < nv; ++i) {
    Eigen::Vector3d p;
    for (int c = 0; c < 3; ++c) p[c] = tok.number("a vertex coordinate") * scale;
    mesh.vertices.push_back(p);
    tok.skip_line();
  }
  std::vector<Index> poly;
  for (long long f = 0; f < nf; ++f) {
    const long long k = tok.integer("a face's vertex count");
    const int line = tok.line();
    if (k < 3 || k > size / 2) {
      fail_line(path, line,
                fmt::format("face {} with {} vertices: expected at least 3 (and at most one per "
                            "two bytes of the file)",
                            f + 1, k));
    }
    poly.clear();
    for (long long j = 0; j < k; ++j) {
      const long long i = tok.integer("a vertex index");
      if (i < 0 || i >= nv) {
        fail_line(path, tok.line(),
                  fmt::format("vertex index {} out of range: the file has {} vertices", i, nv));
      }
      poly.push_back(static_cast<Index>(i));
    }
    add_polygon(path, mesh, poly, static_cast<std::size_t>(f + 1), line);
    tok.skip_line();  // face colours may follow the indices
  }
  return mesh;
}

namespace {

// The mesh of a PLY file's bytes `data` (read from `path`, which the messages name).
TriangleMesh read_ply_data(const std::string& path, const std::string& data, double scale) {
  const PlyHeader header = read_ply_header(path, data);
  check_ply_counts(path, data, header, header.format == "ascii");
  PlyDataReader reader(path, data, header, scale);
  for (const auto& e : header.elements) reader.read_element(e);
  if (reader.mesh().triangles.empty()) fail_line(path, header.line, "the PLY file has no faces");
  return std::move(reader.mesh());
}

}  // namespace

TriangleMesh read_ply(const std::string& path, double scale) {
  return read_ply_data(path, slurp(path), scale);
}

namespace detail {

ReadResult read_mesh(const std::string& path, double scale) {
  RIGID_REQUIRE(std::isfinite(scale) && scale > 0, "scale {}: expected a positive finite number",
                scale);
  const std::string ext = extension(path);
  ReadResult out;
  TriangleMesh& mesh = out.mesh;
  if (ext == "stl") {
    bool binary = false;
    mesh = read_stl(path, scale, &binary);
    out.vertices_distinct = binary && scale >= 1e-250 && scale <= 1e250;
  } else if (ext == "obj") {
    mesh = read_obj(path, scale);
  } else if (ext == "ply") {
    mesh = read_ply(path, scale);
  } else if (ext == "off") {
    mesh = read_off(path, scale);
  } else {
    fail_file(path, fmt::format("{} is not a supported mesh format: the supported extensions "
                                "are {} (any case)",
                                ext.empty() ? std::string("a name without an extension")
                                            : fmt::format("'.{}'", ext),
                                kSupportedExtensions));
  }
  check_indices(path, mesh);
  if (mesh.triangles.empty()) {
    rigid::detail::throw_error_at(SourceLocation{path, 0, 0}, "the mesh has no triangles");
  }
  return out;
}

}  // namespace detail

TriangleMesh read_mesh(const std::string& path, double scale) {
  return detail::read_mesh(path, scale).mesh;
}

std::string stl_binary(const TriangleMesh& mesh) {
  RIGID_REQUIRE(mesh.triangles.size() <= 0xFFFFFFFFu,
                "{} triangles do not fit a binary STL's 32-bit count", mesh.triangles.size());
  std::string out(84 + 50 * mesh.triangles.size(), '\0');
  std::memcpy(out.data(), "binary STL written by rigid", 27);
  const auto n = static_cast<std::uint32_t>(mesh.triangles.size());
  std::memcpy(out.data() + 80, &n, 4);
  char* at = out.data() + 84;
  for (const auto& t : mesh.triangles) {
    float buf[12] = {};
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    const Eigen::Vector3d& b = mesh.vertices[t[1]];
    const Eigen::Vector3d& c = mesh.vertices[t[2]];
    const Eigen::Vector3d nrm = (b - a).cross(c - a).normalized();
    for (int k = 0; k < 3; ++k) {
      buf[k] = static_cast<float>(nrm[k]);
      buf[3 + k] = static_cast<float>(a[k]);
      buf[6 + k] = static_cast<float>(b[k]);
      buf[9 + k] = static_cast<float>(c[k]);
    }
    std::memcpy(at, buf, sizeof(buf));
    at += 50;  // the two attribute bytes stay 0
  }
  return out;
}

void write_stl_binary(const TriangleMesh& mesh, const std::string& path) {
  const std::string bytes = stl_binary(mesh);
  std::ofstream out(path, std::ios::binary);
  RIGID_REQUIRE(out.good(), "cannot open {} for writing", path);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  RIGID_REQUIRE(out.good(), "writing {} failed", path);
}

}  // namespace rigid::mesh
