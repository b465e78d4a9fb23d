#include "rigid/io/inertial_fix.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numbers>
#include <sstream>
#include <string_view>
#include <unordered_map>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>
#include <tinyxml2.h>

#include "detail/fix_geometry.hpp"
#include "detail/inertial_element.hpp"
#include "detail/xml_numbers.hpp"
#include "detail/xml_parse.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/escape.hpp"
#include "rigid/common/wording.hpp"
#include "rigid/mass/primitive_table.hpp"
#include "rigid/mesh/mass_from_file.hpp"

namespace rigid::io {
namespace detail {

std::vector<double> parse_numbers(const char* text, std::size_t expected, const std::string& what) {
  XmlNumbers n = read_xml_numbers(text, expected, what, true);
  if (!n.problem.empty()) throw GeometryProblem{std::move(n.problem)};
  return std::move(n.values);
}

MassProperties catalogue_primitive(const char* name, double rho, std::vector<double> sizes,
                                   const std::string& what) {
  try {
    return mass::find_primitive(name).make(mass::Amount::kDensity, rho, sizes, {});
  } catch (const Error& e) {
    throw GeometryProblem{fmt::format("{}: {}", what, strip_function_names(e.what()))};
  }
}

MassProperties mesh_solid(const std::string& path, const Eigen::Vector3d& scale, double rho,
                          const std::string& what, double& volume,
                          std::vector<std::string>& warnings) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    throw GeometryProblem{fmt::format("{}: mesh file '{}' does not exist", what, path)};
  }
  if (!(scale.minCoeff() > 0) || !scale.allFinite()) {
    throw GeometryProblem{fmt::format("{}: mesh scale ({}, {}, {}) must be positive and finite "
                                      "(a mirroring scale turns the solid inside out)",
                                      what, scale.x(), scale.y(), scale.z())};
  }
  const bool uniform = scale.x() == scale.y() && scale.y() == scale.z();
  std::optional<mesh::MeshFileMass> file_mass;
  try {
    mesh::MassSpec spec;
    spec.density = rho;
    file_mass = mesh::mesh_mass_from_file(path, uniform ? scale.x() : 1.0, spec);
  } catch (const Error& e) {
    throw GeometryProblem{fmt::format("{}: {}", what, strip_function_names(e.what()))};
  }
  const mesh::MeshFileMass& measured = *file_mass;
  MassProperties mp = measured.mass.properties;
  Eigen::Vector3d extent = measured.mass.bounding_box[1] - measured.mass.bounding_box[0];
  if (!uniform) {
    // a solid mapped by S = diag(scale): m' = det S · m, c' = S c, and the second moment about
    // the COM J = ∫ρ r rᵀ dV = ½ tr(I) 1 − I becomes J' = det S · S J Sᵀ; I' = tr(J') 1 − J'
    const Eigen::Matrix3d S = scale.asDiagonal();
    const double det = scale.prod();
    const Eigen::Matrix3d I = mp.inertia_com();
    const Eigen::Matrix3d J = 0.5 * I.trace() * Eigen::Matrix3d::Identity() - I;
    const Eigen::Matrix3d J2 = det * S * J * S.transpose();
    mp = MassProperties(det * mp.mass(), S * mp.com(),
                        J2.trace() * Eigen::Matrix3d::Identity() - J2);
    extent = extent.cwiseProduct(scale);
  }
  volume = mp.mass() / rho;
  if (extent.maxCoeff() > mesh::kMaxPartSize) {
    throw GeometryProblem{fmt::format(
        "{}: mesh '{}' is {:.4g} m long ({:.4g} × {:.4g} × {:.4g} m): plausibly millimetres read "
        "as metres; give the mesh its scale (0.001 for millimetres)",
        what, path, extent.maxCoeff(), extent.x(), extent.y(), extent.z())};
  }
  if (extent.maxCoeff() < mesh::kMinPartSize) {
    warnings.push_back(fmt::format("{}: mesh '{}' is only {:.4g} m long; check its scale", what,
                                   path, extent.maxCoeff()));
  }
  for (const auto& w : measured.warnings()) {
    // the units advice is the one above, in this file's terms
    if (w.find("units") == std::string::npos) warnings.push_back(fmt::format("{}: {}", what, w));
  }
  return mp;
}

}  // namespace detail

namespace {

using detail::GeometryProblem;
using detail::LinkGeometry;
using detail::parse_numbers;

// ---------------------------------------------------------------------------------------------
// byte positions of elements
//
// tinyxml2 keeps line numbers only; the rewrite needs the bytes where each element starts and
// ends. A small scanner of the same (already well-formed, tinyxml2 parsed it) text finds the
// start tags in document order, which is tinyxml2's order of elements, skipping comments,
// processing instructions, CDATA and the DOCTYPE.

struct ElementSpan {
  std::size_t begin = 0;          // '<'
  std::size_t start_tag_end = 0;  // one past the start tag's '>'
  std::size_t end = 0;            // one past the element (its end tag, or the start tag)
  bool self_closing = false;
};

std::vector<ElementSpan> element_spans(std::string_view s, const std::string& source) {
  std::vector<ElementSpan> out;
  std::vector<std::size_t> open;
  auto fail = [&](std::size_t at) -> void {
    const int line = 1 + static_cast<int>(std::count(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
    rigid::detail::throw_error_at(SourceLocation{source, line, 0},
                                  "could not locate this markup in the text (an unusual DOCTYPE?)");
  };
  auto skip_past = [&](std::size_t from, std::string_view marker) {
    const std::size_t k = s.find(marker, from);
    if (k == std::string_view::npos) fail(from);
    return k + marker.size();
  };
  std::size_t i = 0;
  while ((i = s.find('<', i)) != std::string_view::npos) {
    const std::string_view rest = s.substr(i);
    if (rest.starts_with("<!--")) {
      i = skip_past(i + 4, "-->");
    } else if (rest.starts_with("<![CDATA[")) {
      i = skip_past(i + 9, "]]>");
    } else if (rest.starts_with("<?")) {
      i = skip_past(i + 2, "?>");
    } else if (rest.starts_with("<!")) {
      if (s.substr(i, s.find('>', i) - i).find('[') != std::string_view::npos) fail(i);
      i = skip_past(i + 2, ">");
    } else if (rest.starts_with("</")) {
      const std::size_t e = skip_past(i + 2, ">");
      if (open.empty()) fail(i);
      out[open.back()].end = e;
      open.pop_back();
      i = e;
    } else {
      // a start tag: to the '>' outside quoted attribute values
      const std::size_t k = detail::start_tag_end(s, i);
      if (k >= s.size()) fail(i);
      ElementSpan span;
      span.begin = i;
      span.start_tag_end = k + 1;
      span.self_closing = s[k - 1] == '/';
      span.end = span.start_tag_end;
      out.push_back(span);
      if (!span.self_closing) open.push_back(out.size() - 1);
      i = k + 1;
    }
  }
  if (!open.empty()) fail(out[open.back()].begin);
  return out;
}

void number_elements(const tinyxml2::XMLElement* e,
                     std::unordered_map<const tinyxml2::XMLElement*, std::size_t>& index) {
  for (; e != nullptr; e = e->NextSiblingElement()) {
    const std::size_t n = index.size();
    index[e] = n;
    number_elements(e->FirstChildElement(), index);
  }
}

// the whitespace before `at` back to the line's start, or nullopt when the element does not
// start its line
std::optional<std::string> indentation(std::string_view s, std::size_t at) {
  std::size_t k = at;
  while (k > 0 && (s[k - 1] == ' ' || s[k - 1] == '\t')) --k;
  if (k > 0 && s[k - 1] != '\n') return std::nullopt;
  return std::string(s.substr(k, at - k));
}

// ---------------------------------------------------------------------------------------------
// URDF and SDF links

struct Resolver {
  std::filesystem::path dir;
  const std::vector<std::pair<std::string, std::string>>* packages;

  std::string resolve(std::string_view uri, const std::string& what) const {
    for (const std::string_view scheme : {"package://", "model://"}) {
      if (uri.starts_with(scheme)) {
        const std::string_view rest = uri.substr(scheme.size());
        const std::string_view package = rest.substr(0, rest.find('/'));
        for (const auto& [name, path] : *packages) {
          if (name == package) {
            const std::string_view tail =
                rest.size() > package.size() ? rest.substr(package.size() + 1) : std::string_view{};
            return (std::filesystem::path(path) / tail).lexically_normal().string();
          }
        }
        throw GeometryProblem{fmt::format(
            "{}: '{}' names package '{}', whose directory is not known; give it with {}", what,
            uri, package, setting("package_path", fmt::format("{}=DIR", package)))};
      }
    }
    if (uri.starts_with("file://")) uri.remove_prefix(7);
    if (uri.find("://") != std::string_view::npos) {
      throw GeometryProblem{fmt::format("{}: '{}': only package://, model://, file:// and "
                                        "file paths are read", what, uri)};
    }
    const std::filesystem::path p(uri);
    return (p.is_absolute() ? p : dir / p).lexically_normal().string();
  }
};

std::string what_of(const tinyxml2::XMLElement* geometry_owner, const char* shape) {
  std::string w = fmt::format("<{}>", geometry_owner->Name());
  if (const char* n = geometry_owner->Attribute("name")) w += fmt::format(" '{}'", n);
  return fmt::format("{} {} (line {})", w, shape, geometry_owner->GetLineNum());
}

// URDF <collision>/<visual>: <origin xyz rpy/> and <geometry> with box/cylinder/sphere/mesh
// The shape element of a <collision>/<visual>'s <geometry> (URDF and SDF nest it the same way).
const tinyxml2::XMLElement* geometry_shape(const tinyxml2::XMLElement* c) {
  const auto* g = c->FirstChildElement("geometry");
  const auto* shape = g == nullptr ? nullptr : g->FirstChildElement();
  if (shape == nullptr) {
    throw GeometryProblem{fmt::format("<{}> (line {}) has no <geometry> shape", c->Name(),
                                      c->GetLineNum())};
  }
  return shape;
}

void add_urdf_geometry(const tinyxml2::XMLElement* c, const Resolver& files, LinkGeometry& link) {
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero(), rpy = Eigen::Vector3d::Zero();
  if (const auto* o = c->FirstChildElement("origin")) {
    if (const char* t = o->Attribute("xyz")) {
      const auto v = parse_numbers(t, 3, "<origin> attribute 'xyz'");
      xyz = Eigen::Vector3d(v[0], v[1], v[2]);
    }
    if (const char* t = o->Attribute("rpy")) {
      const auto v = parse_numbers(t, 3, "<origin> attribute 'rpy'");
      rpy = Eigen::Vector3d(v[0], v[1], v[2]);
    }
  }
  const tinyxml2::XMLElement* shape = geometry_shape(c);
  const std::string type = shape->Name();
  const std::string what = what_of(c, type.c_str());
  auto attr = [&](const char* key, std::size_t count) {
    const char* t = shape->Attribute(key);
    if (t == nullptr) {
      throw GeometryProblem{fmt::format("{}: <{}> has no attribute '{}'", what, type, key)};
    }
    return parse_numbers(t, count, fmt::format("<{}> attribute '{}'", type, key));
  };
  std::optional<MassProperties> unit;
  double volume = 0;
  if (type == "box") {
    const auto v = attr("size", 3);
    unit = detail::catalogue_primitive("solid_box", 1.0, {v[0], v[1], v[2]}, what);
  } else if (type == "cylinder") {
    unit = detail::catalogue_primitive("solid_cylinder", 1.0, {attr("radius", 1)[0], attr("length", 1)[0]}, what);
  } else if (type == "sphere") {
    unit = detail::catalogue_primitive("solid_sphere", 1.0, {attr("radius", 1)[0]}, what);
  } else if (type == "mesh") {
    const char* file = shape->Attribute("filename");
    if (file == nullptr) throw GeometryProblem{fmt::format("{}: <mesh> has no attribute 'filename'", what)};
    Eigen::Vector3d scale = Eigen::Vector3d::Ones();
    if (shape->Attribute("scale") != nullptr) {
      const auto v = attr("scale", 3);
      scale = Eigen::Vector3d(v[0], v[1], v[2]);
    }
    unit = detail::mesh_solid(files.resolve(file, what), scale, 1.0, what, volume, link.warnings);
  } else {
    throw GeometryProblem{fmt::format("{}: unknown geometry <{}>; expected box, cylinder, sphere "
                                      "or mesh", what, type)};
  }
  link.volume += unit->mass();
  link.parts.push_back(unit->transformed(rotation_from_rpy(rpy), xyz));
}

// SDF <collision>/<visual>: <pose> and <geometry> with box/cylinder/sphere/capsule/ellipsoid/mesh
void add_sdf_geometry(const tinyxml2::XMLElement* c, const Resolver& files, LinkGeometry& link) {
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero(), rpy = Eigen::Vector3d::Zero();
  if (const auto* pose = c->FirstChildElement("pose")) {
    if (const char* rel = pose->Attribute("relative_to");
        rel != nullptr && link.name != rel) {
      throw GeometryProblem{fmt::format("<pose relative_to=\"{}\"> (line {}) is not supported; "
                                        "give the pose in the link frame", rel, pose->GetLineNum())};
    }
    if (const char* f = pose->Attribute("rotation_format");
        f != nullptr && std::string_view(f) != "euler_rpy") {
      throw GeometryProblem{fmt::format("<pose rotation_format=\"{}\"> (line {}) is not "
                                        "supported; use euler_rpy", f, pose->GetLineNum())};
    }
    const auto v = parse_numbers(pose->GetText(), 6, fmt::format("<pose> (line {})", pose->GetLineNum()));
    const char* deg = pose->Attribute("degrees");
    const double k = deg != nullptr && std::string_view(deg) == "true" ? std::numbers::pi / 180 : 1.0;
    xyz = Eigen::Vector3d(v[0], v[1], v[2]);
    rpy = k * Eigen::Vector3d(v[3], v[4], v[5]);
  }
  const tinyxml2::XMLElement* shape = geometry_shape(c);
  const std::string type = shape->Name();
  const std::string what = what_of(c, type.c_str());
  auto child = [&](const char* key, std::size_t count) {
    const auto* e = shape->FirstChildElement(key);
    if (e == nullptr) throw GeometryProblem{fmt::format("{}: <{}> has no <{}>", what, type, key)};
    return parse_numbers(e->GetText(), count, fmt::format("<{}> (line {})", key, e->GetLineNum()));
  };
  std::optional<MassProperties> unit;
  double volume = 0;
  if (type == "box") {
    const auto v = child("size", 3);
    unit = detail::catalogue_primitive("solid_box", 1.0, {v[0], v[1], v[2]}, what);
  } else if (type == "cylinder") {
    unit = detail::catalogue_primitive("solid_cylinder", 1.0, {child("radius", 1)[0], child("length", 1)[0]}, what);
  } else if (type == "sphere") {
    unit = detail::catalogue_primitive("solid_sphere", 1.0, {child("radius", 1)[0]}, what);
  } else if (type == "capsule") {
    // SDF's capsule: a cylinder of `length` with hemispherical caps of `radius` on its ends
    unit = detail::catalogue_primitive("solid_capsule", 1.0, {child("radius", 1)[0], child("length", 1)[0]}, what);
  } else if (type == "ellipsoid") {
    const auto v = child("radii", 3);
    unit = detail::catalogue_primitive("solid_ellipsoid", 1.0, {v[0], v[1], v[2]}, what);
  } else if (type == "mesh") {
    const auto* uri = shape->FirstChildElement("uri");
    if (uri == nullptr || uri->GetText() == nullptr) {
      throw GeometryProblem{fmt::format("{}: <mesh> has no <uri>", what)};
    }
    Eigen::Vector3d scale = Eigen::Vector3d::Ones();
    if (shape->FirstChildElement("scale") != nullptr) {
      const auto v = child("scale", 3);
      scale = Eigen::Vector3d(v[0], v[1], v[2]);
    }
    unit = detail::mesh_solid(files.resolve(uri->GetText(), what), scale, 1.0, what, volume, link.warnings);
  } else {
    throw GeometryProblem{fmt::format("{}: unknown geometry <{}>; expected box, cylinder, sphere, "
                                      "capsule, ellipsoid or mesh", what, type)};
  }
  link.volume += unit->mass();
  link.parts.push_back(unit->transformed(rotation_from_rpy(rpy), xyz));
}

void collect_links(const tinyxml2::XMLElement* e, InertialFormat format, const Resolver& files,
                   GeometrySource from, std::vector<LinkGeometry>& out) {
  for (const auto* c = e->FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) {
    if (std::string_view(c->Name()) != "link") {
      collect_links(c, format, files, from, out);
      continue;
    }
    LinkGeometry link;
    link.element = c;
    link.line = c->GetLineNum();
    if (const char* n = c->Attribute("name")) link.name = n;
    link.inertial = c->FirstChildElement("inertial");
    const char* kind = from == GeometrySource::kCollision ? "collision" : "visual";
    for (const auto* g = c->FirstChildElement(kind); g != nullptr; g = g->NextSiblingElement(kind)) {
      try {
        if (format == InertialFormat::urdf) {
          add_urdf_geometry(g, files, link);
        } else {
          add_sdf_geometry(g, files, link);
        }
      } catch (const GeometryProblem& p) {
        const std::string label = fmt::format("<{}> (line {})", g->Name(), g->GetLineNum());
        link.errors.push_back(p.text.starts_with(fmt::format("<{}>", g->Name()))
                                  ? p.text : fmt::format("{}: {}", label, p.text));
      }
    }
    out.push_back(std::move(link));
  }
}

// ---------------------------------------------------------------------------------------------
// classification of the old inertial

bool power_of_ten(double v) {
  if (!(v > 0)) return false;
  const double e = std::round(std::log10(v));
  return e >= -9 && e <= 0 && v == std::stod(fmt::format("1e{}", e));
}

std::optional<std::string> placeholder(const InertialEntry& old) {
  const Eigen::Matrix3d& I = old.inertia_com;
  if ((I.array() == 0).all()) return "zero inertia tensor";
  const bool diagonal = I(0, 1) == 0 && I(0, 2) == 0 && I(1, 2) == 0;
  if (diagonal && I(0, 0) == I(1, 1) && I(1, 1) == I(2, 2) && power_of_ten(I(0, 0))) {
    return fmt::format("inertia {} · identity{}", I(0, 0),
                       old.mass == 1 ? " with mass 1 kg" : "");
  }
  return std::nullopt;
}

// kg/m³ band of real materials, with margin: foams (~50) to tungsten alloys (~19 000)
constexpr double kMinDensity = 50;
constexpr double kMaxDensity = 25000;

MassProperties scaled(const MassProperties& mp, double k) {
  return MassProperties(k * mp.mass(), mp.com(), k * mp.inertia_com());
}

// ---------------------------------------------------------------------------------------------
// writing

std::string num(double v) { return fmt::format("{}", v + 0.0); }  // shortest round trip, no -0

std::string vec(const Eigen::Vector3d& v) {
  return fmt::format("{} {} {}", num(v.x()), num(v.y()), num(v.z()));
}

// the new inertial's text; `indent` of its own line and `unit` per level (both empty when the
// inertial does not start a line: then on one line)
std::string inertial_text(const MassProperties& mp, InertialFormat format, const std::string& indent,
                          const std::string& unit, const std::string& nl) {
  const Eigen::Matrix3d& I = mp.inertia_com();
  const std::string i1 = indent + unit, i2 = indent + unit + unit;
  switch (format) {
    case InertialFormat::urdf:
      return fmt::format(
          "<inertial>{0}{1}<origin xyz=\"{3}\" rpy=\"0 0 0\"/>{0}{1}<mass value=\"{4}\"/>{0}{1}"
          "<inertia ixx=\"{5}\" ixy=\"{6}\" ixz=\"{7}\" iyy=\"{8}\" iyz=\"{9}\" izz=\"{10}\"/>{0}{2}"
          "</inertial>",
          nl, i1, indent, vec(mp.com()), num(mp.mass()), num(I(0, 0)), num(I(0, 1)), num(I(0, 2)),
          num(I(1, 1)), num(I(1, 2)), num(I(2, 2)));
    case InertialFormat::mjcf:
      // MJCF fullinertia order: xx yy zz xy xz yz (tensor elements in the body frame)
      return fmt::format("<inertial pos=\"{}\" mass=\"{}\" fullinertia=\"{} {} {} {} {} {}\"/>",
                         vec(mp.com()), num(mp.mass()), num(I(0, 0)), num(I(1, 1)), num(I(2, 2)),
                         num(I(0, 1)), num(I(0, 2)), num(I(1, 2)));
    case InertialFormat::sdf:
      return fmt::format(
          "<inertial>{0}{1}<pose>{3} 0 0 0</pose>{0}{1}<mass>{4}</mass>{0}{1}<inertia>{0}"
          "{2}<ixx>{5}</ixx>{0}{2}<ixy>{6}</ixy>{0}{2}<ixz>{7}</ixz>{0}{2}<iyy>{8}</iyy>{0}"
          "{2}<iyz>{9}</iyz>{0}{2}<izz>{10}</izz>{0}{1}</inertia>{0}{11}</inertial>",
          nl, i1, i2, vec(mp.com()), num(mp.mass()), num(I(0, 0)), num(I(0, 1)), num(I(0, 2)),
          num(I(1, 1)), num(I(1, 2)), num(I(2, 2)), indent);
  }
  return {};
}

struct Edit {
  std::size_t at = 0;
  std::size_t remove = 0;
  std::string insert;
};

// "line 12", or "arm.xml:12" for a link of an <include>d file
std::string place(const FixedInertial& f, const std::string& source) {
  return f.file.empty() || f.file == source ? fmt::format("line {}", f.line)
                                            : fmt::format("{}:{}", f.file, f.line);
}

std::string display_name(const FixedInertial& f, const std::string& source) {
  return f.name.empty() ? fmt::format("(unnamed, {})", place(f, source)) : f.name;
}

}  // namespace

bool InertialFixResult::ok() const {
  return std::all_of(links.begin(), links.end(), [](const auto& l) { return l.errors.empty(); });
}

std::vector<std::string> InertialFixResult::errors() const {
  std::vector<std::string> out;
  for (const auto& l : links) {
    for (const auto& e : l.errors) {
      out.push_back(fmt::format("{}:{}: {} '{}': {}", l.file.empty() ? source : l.file, l.line,
                                format == InertialFormat::mjcf ? "body" : "link", l.name, e));
    }
  }
  return out;
}

std::pair<std::string, std::string> parse_package_path(const std::string& text) {
  const auto eq = text.find('=');
  RIGID_REQUIRE(eq != std::string::npos && eq > 0 && eq + 1 < text.size(),
                "{} expects NAME=DIR, got '{}'", setting("package_path", "NAME=DIR"), text);
  return {text.substr(0, eq), text.substr(eq + 1)};
}

void InertialFixResult::require_ok() const {
  if (ok()) return;
  const auto list = errors();
  RIGID_THROW("{} problem{} left inertials unfixed; nothing was written:\n  {}", list.size(),
              list.size() == 1 ? "" : "s", fmt::join(list, "\n  "));
}

namespace {

// One file of the model (the document, or an MJCF file it <include>s): its text, the byte
// positions of its elements and the edits made to it.
struct FileText {
  const std::string* text = nullptr;
  const tinyxml2::XMLElement* root = nullptr;
  std::vector<ElementSpan> spans;
  std::unordered_map<const tinyxml2::XMLElement*, std::size_t> span_of;
  std::string nl;  // its line ending
  std::vector<Edit> edits;

  [[nodiscard]] const ElementSpan& span(const tinyxml2::XMLElement* e) const {
    return spans[span_of.at(e)];
  }
};

FileText locate(const std::string& text, const std::string& file,
                const tinyxml2::XMLElement* root) {
  FileText f;
  f.text = &text;
  f.root = root;
  f.spans = element_spans(text, file);
  number_elements(root, f.span_of);
  if (f.span_of.size() != f.spans.size()) {
    rigid::detail::throw_error_at(SourceLocation{file, 0, 0},
                                  fmt::format("could not locate the {} elements in the text "
                                              "(found {}); the file is left as it is",
                                              f.span_of.size(), f.spans.size()));
  }
  f.nl = text.find("\r\n") != std::string::npos ? "\r\n" : "\n";
  return f;
}

// The text of `f` with its edits applied and each followed <include> element replaced by the
// elements of its file (their own edits applied): MuJoCo puts the included root's children in
// the include's place, so the written model is the same model in one file.
std::string render(const FileText& f, const std::map<const tinyxml2::XMLDocument*, FileText>& files,
                   const detail::MjcfDocument* mjcf) {
  std::vector<Edit> edits = f.edits;
  if (mjcf != nullptr) {
    for (const auto& [e, index] : f.span_of) {
      const tinyxml2::XMLElement* root = mjcf->included_root(e);
      if (root == nullptr) continue;
      const FileText& inner = files.at(root->GetDocument());
      const std::string text = render(inner, files, mjcf);
      // the root's content: every edit lies inside it, so its end moved by the growth
      const ElementSpan& r = inner.span(root);
      const std::size_t end_tag = inner.text->rfind("</", r.end - 1);
      const std::size_t end = end_tag + (text.size() - inner.text->size());
      std::string_view content = std::string_view(text).substr(r.start_tag_end, end - r.start_tag_end);
      const std::size_t first = content.find_first_not_of(" \t\r\n");
      content = first == std::string_view::npos
                    ? std::string_view{}
                    : content.substr(first, content.find_last_not_of(" \t\r\n") + 1 - first);
      const ElementSpan& span = f.spans[index];
      edits.push_back({span.begin, span.end - span.begin, std::string(content)});
    }
  }
  // front to back in one pass (replacing in place would move the tail once per edit: quadratic
  // in the number of links); they do not overlap (one per link, one per include). At the same
  // byte an insertion goes first, so that an inertial inserted there comes before what replaced
  // the element that starts there.
  std::sort(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) {
    return a.at != b.at ? a.at < b.at : a.remove < b.remove;
  });
  const std::string& text = *f.text;
  std::size_t size = text.size();
  for (const auto& e : edits) size += e.insert.size();
  std::string out;
  out.reserve(size);
  std::size_t done = 0;  // bytes of `text` copied or removed so far
  for (const auto& e : edits) {
    RIGID_ASSERT(e.at >= done);
    out.append(text, done, e.at - done);
    out += e.insert;
    done = e.at + e.remove;
  }
  out.append(text, done, std::string::npos);
  return out;
}

}  // namespace

InertialFixResult fix_inertials(const std::string& xml, const std::string& source,
                                const InertialFixOptions& options) {
  RIGID_REQUIRE(!options.density || (*options.density > 0 && std::isfinite(*options.density)),
                "density must be positive and finite, got {} kg/m³", options.density.value_or(0));
  tinyxml2::XMLDocument doc;
  detail::parse_xml(doc, xml, source);
  InertialFixResult result;
  result.source = source;
  result.format = detect_inertial_format(xml, source);
  const auto* root = doc.RootElement();
  const bool mjcf = result.format == InertialFormat::mjcf;
  // MJCF: its <include>s followed (the included files are read now)
  std::optional<detail::MjcfDocument> model;
  if (mjcf) model.emplace(root, source, true);
  const detail::MjcfDocument* mjcf_model = mjcf ? &*model : nullptr;
  const auto file_of = [&](const tinyxml2::XMLElement* e) -> const std::string& {
    return mjcf ? model->file_of(e) : source;
  };

  // every link with its geometry measured
  std::vector<LinkGeometry> links;
  if (mjcf) {
    links = detail::mjcf_links(*model);
  } else {
    const Resolver files{std::filesystem::path(source).parent_path(), &options.package_paths};
    collect_links(root, result.format, files, options.from, links);
  }
  for (const auto& name : options.only) {
    if (std::none_of(links.begin(), links.end(), [&](const auto& l) { return l.name == name; })) {
      std::vector<std::string> names;
      for (const auto& l : links) names.push_back(l.name);
      rigid::detail::throw_error_at(SourceLocation{source, 0, 0},
                                    fmt::format("no {} named '{}'; the file has: {}",
                                                result.format == InertialFormat::mjcf ? "body" : "link",
                                                name, fmt::join(names, ", ")));
    }
  }
  const double density = options.density.value_or(1000.0);
  bool density_assumed = false;

  // the text of every file, by its document: the main one and each included one
  std::map<const tinyxml2::XMLDocument*, FileText> files;
  files.emplace(&doc, locate(xml, source, root));
  std::vector<const tinyxml2::XMLElement*> includes;
  if (mjcf) {
    std::function<void(const tinyxml2::XMLElement*)> find = [&](const tinyxml2::XMLElement* e) {
      for (const auto* c = e->FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) {
        if (const auto* included = model->included_root(c)) {
          includes.push_back(c);
          files.emplace(included->GetDocument(),
                        locate(model->included_text(included), file_of(included), included));
          find(included);
        } else {
          find(c);
        }
      }
    };
    find(root);
  }
  const auto text_of = [&](const tinyxml2::XMLElement* e) -> FileText& {
    return files.at(e->GetDocument());
  };

  for (auto& link : links) {
    if (!options.only.empty() &&
        std::find(options.only.begin(), options.only.end(), link.name) == options.only.end()) {
      continue;
    }
    FixedInertial f;
    f.name = link.name;
    f.file = file_of(link.element);
    f.line = link.line;
    f.volume = link.volume;
    f.warnings = std::move(link.warnings);
    f.errors = std::move(link.errors);
    if (link.inertial != nullptr) {
      const bool more = mjcf ? model->children(link.element, "inertial").size() > 1
                             : link.inertial->NextSiblingElement("inertial") != nullptr;
      if (more) f.errors.push_back("more than one <inertial>; keep one");
      f.old = detail::read_inertial_element(link.inertial, result.format, link.name,
                                            file_of(link.inertial));
    }
    const bool has_geometry = !link.parts.empty();
    const bool old_valid = f.old && !f.old->problem;
    // a stated mass worth keeping: positive and finite, even beside an invalid tensor
    const bool mass_keepable = f.old && f.old->mass > 0 && std::isfinite(f.old->mass);

    // why the old inertial is replaced, or why it stays
    if (!f.old) {
      f.reason = "missing";
    } else if (f.old->problem) {
      f.reason = "invalid";
      f.detail = *f.old->problem;
    } else if (const auto p = placeholder(*f.old)) {
      f.reason = "placeholder";
      f.detail = *p;
    } else if (link.volume > 0 && (f.old->mass / link.volume < kMinDensity ||
                                   f.old->mass / link.volume > kMaxDensity)) {
      f.reason = "implausible density";
      f.detail = fmt::format("stated mass {} kg over the geometry's volume {:.6g} m³ is {:.4g} "
                             "kg/m³ (expected {} to {})", f.old->mass, link.volume,
                             f.old->mass / link.volume, kMinDensity, kMaxDensity);
    } else {
      f.reason = "recomputed";
    }
    if (!link.recompute && f.reason != "invalid") {
      if (f.reason == "placeholder" || f.reason == "implausible density") {
        f.warnings.push_back(fmt::format("{}: {}; kept ({})", f.reason, f.detail, link.keep_detail));
      }
      f.reason = "kept";
      f.detail = link.keep_detail;
    } else if (!has_geometry && f.errors.empty()) {
      if (!f.old) {
        f.reason = "kept";
        f.detail = link.has_massless_geometry ? "only massless geometry: left without inertial"
                                              : "no geometry and no inertial: left massless";
      } else if (old_valid) {
        f.warnings.push_back(fmt::format("{} ({}), but there is no geometry to compute from", f.reason, f.detail));
        f.reason = "kept";
        f.detail = "no geometry: the stated inertial is kept";
      } else {
        f.errors.push_back(fmt::format("{} inertial ({}) and no geometry to compute it from",
                                       f.reason, f.detail));
      }
    }

    if (f.reason != "kept" && f.errors.empty() && has_geometry) {
      MassProperties mp = combine(link.parts);
      if (!mjcf) {
        // parts are at density 1: their mass is their volume
        if (options.keep_mass && mass_keepable) {
          mp = scaled(mp, f.old->mass / mp.mass());
        } else {
          if (options.keep_mass) {
            f.warnings.push_back(fmt::format("no valid stated mass to keep: density {} kg/m³ used",
                                             density));
          }
          density_assumed = density_assumed || !options.density;
          mp = scaled(mp, density);
        }
      } else if (options.keep_mass && mass_keepable) {
        mp = scaled(mp, f.old->mass / mp.mass());
      }
      f.fixed = mp;

      // the edit: replace the old element, or insert one as the link's first child with the
      // indentation of its siblings (each in the file that holds the element)
      FileText& body_file = text_of(link.element);
      const std::string& body_text = *body_file.text;
      const ElementSpan& parent = body_file.span(link.element);
      const auto parent_indent = indentation(body_text, parent.begin);
      if (link.inertial != nullptr) {
        FileText& file = text_of(link.inertial);
        const ElementSpan& old = file.span(link.inertial);
        const auto own = indentation(*file.text, old.begin);
        std::string unit = "  ";
        if (own && parent_indent && own->size() > parent_indent->size() && own->starts_with(*parent_indent)) {
          unit = own->substr(parent_indent->size());
        } else if (own && own->find('\t') != std::string::npos) {
          unit = "\t";
        }
        file.edits.push_back({old.begin, old.end - old.begin,
                              own ? inertial_text(mp, result.format, *own, unit, file.nl)
                                  : inertial_text(mp, result.format, "", "", "")});
      } else {
        const std::string pi = parent_indent.value_or("");
        std::string child_indent = pi + "  ";
        if (const auto* first = link.element->FirstChildElement()) {
          if (const auto ci = indentation(body_text, body_file.span(first).begin)) child_indent = *ci;
        }
        std::string unit = "  ";
        if (child_indent.size() > pi.size() && child_indent.starts_with(pi)) {
          unit = child_indent.substr(pi.size());
        } else if (child_indent.find('\t') != std::string::npos) {
          unit = "\t";
        }
        // a link with geometry has children: its start tag is not self-closing
        RIGID_ASSERT(!parent.self_closing);
        body_file.edits.push_back(
            {parent.start_tag_end, 0,
             body_file.nl + child_indent +
                 inertial_text(mp, result.format, child_indent, unit, body_file.nl)});
      }
    }
    result.links.push_back(std::move(f));
  }
  if (density_assumed) {
    // with keep_mass the stated masses are kept already: the water density went only to the
    // links that state none (or an invalid one), and only a density helps them
    result.warnings.push_back(
        options.keep_mass
            ? fmt::format("no density given: {} kg/m³ (water) assumed for the geometry of every "
                          "link without a valid stated mass to keep; give the material's with {}",
                          density, setting("density", "RHO"))
            : fmt::format("no density given: {} kg/m³ (water) assumed for every geometry; give "
                          "the material's with {}, or keep the stated masses with {}",
                          density, setting("density", "RHO"), setting("keep_mass")));
  }
  for (const auto* c : includes) {
    const std::string& included = file_of(model->included_root(c));
    result.warnings.push_back(fmt::format(
        "{}:{}: <include file=\"{}\">: the fixed model is written as one file, with the "
        "included elements in its place; '{}' is not changed",
        file_of(c), c->GetLineNum(), c->Attribute("file"), included));
  }
  result.text = render(files.at(&doc), files, mjcf_model);
  return result;
}

InertialFixResult fix_inertials_file(const std::string& path, const InertialFixOptions& options) {
  // refuses a FIFO or device before opening it (opening a FIFO blocks until a writer comes)
  return fix_inertials(detail::read_model_file(path), path, options);
}

namespace {

std::string short_num(double v) { return fmt::format("{:.6g}", v + 0.0); }

nlohmann::json mass_json(double m, const Eigen::Vector3d& c, const Eigen::Matrix3d& I) {
  nlohmann::json j;
  j["mass"] = m;
  j["com"] = {c.x(), c.y(), c.z()};
  j["inertia_com"] = {{I(0, 0), I(0, 1), I(0, 2)}, {I(1, 0), I(1, 1), I(1, 2)},
                      {I(2, 0), I(2, 1), I(2, 2)}};
  return j;
}

}  // namespace

std::string fix_table_text(const InertialFixResult& r) {
  const char* kind = r.format == InertialFormat::mjcf ? "body" : "link";
  std::size_t width = 4;
  for (const auto& l : r.links) width = std::max(width, display_name(l, r.source).size());
  std::string out = fmt::format("{:<{}}  {:<19}  {:>22}  {:<32}  {}\n", kind, width, "reason",
                                "mass old -> new (kg)", "COM new (m)",
                                "inertia new about COM (xx yy zz xy xz yz, kg m^2)");
  for (const auto& l : r.links) {
    const std::string old_mass = l.old ? (l.old->problem && l.old->mass == 0 ? "?" : short_num(l.old->mass)) : "-";
    std::string new_mass = "-", com = "-", inertia = "-";
    if (l.fixed) {
      const auto& c = l.fixed->com();
      const auto& I = l.fixed->inertia_com();
      new_mass = short_num(l.fixed->mass());
      com = fmt::format("{} {} {}", short_num(c.x()), short_num(c.y()), short_num(c.z()));
      inertia = fmt::format("{} {} {} {} {} {}", short_num(I(0, 0)), short_num(I(1, 1)),
                            short_num(I(2, 2)), short_num(I(0, 1)), short_num(I(0, 2)),
                            short_num(I(1, 2)));
    }
    const std::string reason = l.errors.empty() ? l.reason : "NOT FIXED";
    out += fmt::format("{:<{}}  {:<19}  {:>22}  {:<32}  {}\n", display_name(l, r.source), width, reason,
                       old_mass + " -> " + new_mass, com, inertia);
  }
  for (const auto& l : r.links) {
    const std::string at = place(l, r.source);
    if (!l.detail.empty()) out += fmt::format("{} '{}' ({}): {}: {}\n", kind, l.name, at, l.reason, l.detail);
    for (const auto& w : l.warnings) out += fmt::format("{} '{}' ({}): warning: {}\n", kind, l.name, at, w);
  }
  for (const auto& w : r.warnings) out += fmt::format("warning: {}\n", w);
  for (const auto& e : r.errors()) out += fmt::format("error: {}\n", e);
  return out;
}

std::string fix_table_json(const InertialFixResult& r) {
  nlohmann::json j;
  j["file"] = rigid::escaped(r.source);  // a file name of any bytes (\xff) as valid UTF-8
  j["format"] = to_string(r.format);
  j["ok"] = r.ok();
  j["links"] = nlohmann::json::array();
  for (const auto& l : r.links) {
    nlohmann::json e;
    e["name"] = l.name;
    e["file"] = rigid::escaped(l.file);
    e["line"] = l.line;
    e["reason"] = l.reason;
    e["detail"] = l.detail;
    e["volume"] = l.volume;
    e["old"] = l.old ? mass_json(l.old->mass, l.old->com, l.old->inertia_com) : nlohmann::json();
    if (l.old && l.old->problem) e["old"]["problem"] = *l.old->problem;
    e["new"] = l.fixed ? mass_json(l.fixed->mass(), l.fixed->com(), l.fixed->inertia_com())
                       : nlohmann::json();
    e["warnings"] = l.warnings;
    e["errors"] = l.errors;
    j["links"].push_back(std::move(e));
  }
  j["warnings"] = r.warnings;
  j["errors"] = r.errors();
  // names and text read from the file are not checked for UTF-8: an invalid byte is replaced
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace rigid::io
