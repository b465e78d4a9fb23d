// MJCF bodies measured from their geoms with MuJoCo's compiler rules (MuJoCo's XML reference,
// "compiler", "default", "geom", "mesh"): a geom's attributes come from the geom, else from its
// class (the geom's `class`, else the nearest enclosing body's `childclass`, else "main"),
// defaults nest; a geom has the mass ρ·V (density default 1000 kg/m³) or its `mass`
// attribute; sizes are half sizes; `fromto` places capsules, cylinders, boxes and ellipsoids
// along a segment; orientations follow <compiler angle eulerseq>.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <map>
#include <numbers>
#include <string_view>

#include <fmt/format.h>
#include <tinyxml2.h>

#include "detail/fix_geometry.hpp"
#include "detail/xml_parse.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/wording.hpp"
#include "rigid/lie/euler.hpp"
#include "rigid/lie/so3.hpp"

namespace rigid::io::detail {
namespace {

using Attributes = MjcfAttributes;
using Compiler = MjcfCompiler;
using Defaults = MjcfDefaults;

struct MeshAsset {
  std::string file;
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  int line = 0;
};

void merge(Attributes& into, const tinyxml2::XMLElement* e) {
  for (const auto* a = e->FirstAttribute(); a != nullptr; a = a->Next()) {
    into[a->Name()] = a->Value();
  }
}

void read_defaults(const tinyxml2::XMLElement* d, const std::string& parent, Defaults& out,
                   const MjcfDocument& doc) {
  const char* cls = d->Attribute("class");
  std::string name = cls != nullptr ? cls : (parent.empty() ? "main" : "");
  if (name.empty()) doc.refuse(d, "a nested <default> needs a 'class' attribute");
  for (auto* kind : {&out.geom, &out.mesh, &out.joint}) {
    if (!parent.empty()) {
      (*kind)[name] = (*kind)[parent];
    } else {
      (*kind)[name];
    }
  }
  for (const auto* c : doc.children(d)) {
    const std::string_view n = c->Name();
    if (n == "geom") merge(out.geom[name], c);
    if (n == "mesh") merge(out.mesh[name], c);
    if (n == "joint") merge(out.joint[name], c);
    if (n == "default") read_defaults(c, name, out, doc);
  }
}

// the compiler settings that change a body's frame or inertia
void read_compiler_element(const tinyxml2::XMLElement* e, const MjcfDocument& doc, Compiler& c) {
  if (const char* a = e->Attribute("angle")) {
    const std::string_view v = a;
    if (v != "degree" && v != "radian") {
      doc.refuse(e, fmt::format("<compiler> angle=\"{}\": expected \"degree\" or \"radian\"", v));
    }
    c.degrees = v == "degree";
  }
  if (const char* a = e->Attribute("eulerseq")) c.eulerseq = a;
  if (const char* a = e->Attribute("meshdir")) c.meshdir = a;
  if (const char* a = e->Attribute("assetdir")) c.assetdir = a;
  if (const char* a = e->Attribute("inertiafromgeom")) {
    const std::string_view v = a;
    if (v != "auto" && v != "true" && v != "false") {
      doc.refuse(e, fmt::format("<compiler> inertiafromgeom=\"{}\": expected \"auto\", "
                                "\"true\" or \"false\"", v));
    }
    c.inertiafromgeom = a;
  }
  if (const char* a = e->Attribute("exactmeshinertia")) c.exact_mesh_inertia = std::string_view(a) == "true";
  if (const char* a = e->Attribute("inertiagrouprange")) {
    try {
      const auto v = parse_numbers(a, 2, "<compiler> attribute 'inertiagrouprange'");
      c.group_min = v[0];
      c.group_max = v[1];
    } catch (const GeometryProblem& p) {
      doc.refuse(e, p.text);
    }
  }
  // settings that rescale or bound the compiled inertias: the file's inertials would not
  // be the model's, so they are refused rather than silently ignored
  for (const char* rescale : {"settotalmass", "boundmass", "boundinertia"}) {
    if (const char* a = e->Attribute(rescale)) {
      double v = 0;
      if (e->QueryDoubleAttribute(rescale, &v) != tinyxml2::XML_SUCCESS || v > 0) {
        doc.refuse(e, fmt::format("<compiler> {}=\"{}\" changes every body's compiled "
                                  "inertia; remove it to compute the inertials from the "
                                  "geoms", rescale, a));
      }
    }
  }
  if (const char* a = e->Attribute("balanceinertia"); a != nullptr && std::string_view(a) == "true") {
    doc.refuse(e, "<compiler> balanceinertia=\"true\" changes compiled inertias; remove it "
                  "to compute the inertials from the geoms");
  }
}

void refuse_unfollowed(const tinyxml2::XMLElement* e, const MjcfDocument& doc) {
  for (const auto* c : doc.children(e)) {
    const std::string_view n = c->Name();
    if (n == "include") {
      doc.refuse(c, "<include> is not supported: give the model as one file (MuJoCo's "
                    "compile sample writes the merged model: mujoco-compile model.xml "
                    "merged.xml)");
    }
    if (n == "frame" || n == "replicate" || n == "attach" || n == "composite" || n == "flexcomp") {
      doc.refuse(c, fmt::format("<{}> is not supported: the bodies it makes are MuJoCo's "
                                "compiler's; give them as bodies and geoms (mujoco-compile "
                                "model.xml merged.xml writes them out)", n));
    }
    refuse_unfollowed(c, doc);
  }
}

std::filesystem::path mesh_directory(const Compiler& c, const std::string& source) {
  const std::filesystem::path model_dir = std::filesystem::path(source).parent_path();
  const std::string& dir = !c.meshdir.empty() ? c.meshdir : c.assetdir;
  if (dir.empty()) return model_dir;
  const std::filesystem::path p(dir);
  return p.is_absolute() ? p : model_dir / p;
}

std::map<std::string, MeshAsset, std::less<>> read_meshes(const MjcfDocument& doc,
                                                          const Defaults& defaults,
                                                          const Compiler& compiler) {
  std::map<std::string, MeshAsset, std::less<>> out;
  // MuJoCo: meshdir is relative to the main file's directory, as includes are
  const std::filesystem::path dir = mesh_directory(compiler, doc.source());
  for (const auto* asset : doc.children(doc.root(), "asset")) {
    for (const auto* m : doc.children(asset, "mesh")) {
      const char* cls = m->Attribute("class");
      const auto d = defaults.mesh.find(cls != nullptr ? cls : "main");
      Attributes attrs = d == defaults.mesh.end() ? Attributes{} : d->second;
      merge(attrs, m);
      MeshAsset a;
      a.line = m->GetLineNum();
      const auto file = attrs.find("file");
      // an inline mesh (vertex/face attributes) or one offset by refpos/refquat: not followed
      for (const char* unsupported : {"vertex", "face", "refpos", "refquat"}) {
        if (attrs.count(unsupported) != 0) {
          doc.refuse(m, fmt::format("<mesh> attribute '{}' is not supported; give the mesh "
                                    "as a file in its own frame", unsupported));
        }
      }
      if (file == attrs.end()) continue;  // a mesh without a file is refused where a geom uses it
      const std::filesystem::path f(file->second);
      a.file = (f.is_absolute() ? f : dir / f).lexically_normal().string();
      if (const auto s = attrs.find("scale"); s != attrs.end()) {
        try {
          const auto v = parse_numbers(s->second.c_str(), 3, "<mesh> attribute 'scale'");
          a.scale = Eigen::Vector3d(v[0], v[1], v[2]);
        } catch (const GeometryProblem& p) {
          doc.refuse(m, p.text);
        }
      }
      const auto name = attrs.find("name");
      // MuJoCo names an unnamed mesh after its file, without directory and extension
      out[name != attrs.end() ? name->second : f.stem().string()] = a;
    }
  }
  return out;
}

// the rotation that takes z to `v` along the great circle (MuJoCo's z2quat, which `fromto` and
// `zaxis` use); an antiparallel v turns by π about x
Eigen::Matrix3d z_to(const Eigen::Vector3d& v) {
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d axis = z.cross(v);
  const double s = axis.norm();
  if (s < 1e-10) {
    axis = Eigen::Vector3d::UnitX();
  } else {
    axis /= s;
  }
  return SO3d::from_axis_angle(axis, std::atan2(s, v.z())).matrix();
}

Eigen::Matrix3d quaternion_rotation(const char* text) {
  const auto v = parse_numbers(text, 4, "attribute 'quat'");
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
  if (!(n > 0) || !std::isfinite(n)) {
    throw GeometryProblem{fmt::format("attribute 'quat': expected a non-zero quaternion w x y "
                                      "z, got '{}'", text)};
  }
  return SO3d::from_quaternion(v[0], v[1], v[2], v[3]).matrix();  // normalised, as MuJoCo does
}

Eigen::Matrix3d euler_rotation(const char* text, const Compiler& compiler, double angle_unit) {
  const auto v = parse_numbers(text, 3, "attribute 'euler'");
  const std::string& seq = compiler.eulerseq;
  const bool lower = std::all_of(seq.begin(), seq.end(), [](char c) { return std::islower(static_cast<unsigned char>(c)); });
  const bool upper = std::all_of(seq.begin(), seq.end(), [](char c) { return std::isupper(static_cast<unsigned char>(c)); });
  if (!lower && !upper) {
    throw GeometryProblem{fmt::format("<compiler> eulerseq=\"{}\" mixes rotating and fixed "
                                      "axes; not supported", seq)};
  }
  // MuJoCo: lower case = rotating (intrinsic) axes, upper case = fixed (extrinsic) axes
  try {
    return from_euler(Eigen::Vector3d(v[0], v[1], v[2]) * angle_unit,
                      EulerConvention::parse(seq, lower))
        .matrix();
  } catch (const Error& e) {
    throw GeometryProblem{fmt::format("<compiler> eulerseq=\"{}\": {}", seq, e.what())};
  }
}

Eigen::Matrix3d xyaxes_rotation(const char* text) {
  const std::string what = "attribute 'xyaxes'";
  const auto v = parse_numbers(text, 6, what);
  Eigen::Vector3d x(v[0], v[1], v[2]), y(v[3], v[4], v[5]);
  if (!(x.norm() > 0)) throw GeometryProblem{fmt::format("{}: zero x axis", what)};
  x.normalize();
  y -= x.dot(y) * x;
  if (!(y.norm() > 1e-10)) throw GeometryProblem{fmt::format("{}: y axis parallel to x", what)};
  y.normalize();
  Eigen::Matrix3d R;
  R << x, y, x.cross(y);
  return R;
}

}  // namespace

std::optional<Eigen::Matrix3d> mjcf_orientation(const tinyxml2::XMLElement* e,
                                                const MjcfCompiler& compiler) {
  const char* given = nullptr;
  int count = 0;
  for (const char* key : {"quat", "axisangle", "euler", "xyaxes", "zaxis"}) {
    if (e->Attribute(key) != nullptr) {
      given = key;
      ++count;
    }
  }
  if (count > 1) {
    throw GeometryProblem{"more than one orientation attribute (quat, axisangle, euler, "
                          "xyaxes, zaxis); MuJoCo accepts one"};
  }
  if (given == nullptr) return std::nullopt;
  const double angle_unit = compiler.degrees ? std::numbers::pi / 180.0 : 1.0;
  const std::string_view key = given;
  const char* text = e->Attribute(given);
  if (key == "quat") return quaternion_rotation(text);
  if (key == "euler") return euler_rotation(text, compiler, angle_unit);
  if (key == "xyaxes") return xyaxes_rotation(text);
  if (key == "axisangle") {
    const auto v = parse_numbers(text, 4, "attribute 'axisangle'");
    const Eigen::Vector3d axis(v[0], v[1], v[2]);
    if (!(axis.norm() > 0)) throw GeometryProblem{"attribute 'axisangle': zero axis"};
    return SO3d::from_axis_angle(axis.normalized(), v[3] * angle_unit).matrix();
  }
  const auto v = parse_numbers(text, 3, "attribute 'zaxis'");
  const Eigen::Vector3d z(v[0], v[1], v[2]);
  if (!(z.norm() > 0)) throw GeometryProblem{"attribute 'zaxis': zero axis"};
  return z_to(z.normalized());
}

namespace {

class GeomReader {
 public:
  GeomReader(const Compiler& compiler, const Defaults& defaults,
             const std::map<std::string, MeshAsset, std::less<>>& meshes)
      : compiler_(compiler), defaults_(defaults), meshes_(meshes) {}

  // one geom of a body, measured in the body frame (nothing for a geom outside
  // inertiagrouprange or without mass)
  // `file`: the geom's file where it is not its body's (an <include> inside the body)
  void add(const tinyxml2::XMLElement* g, const std::string& childclass, LinkGeometry& link,
           const std::string& file = {}) const {
    std::string what = "geom";
    if (const char* n = g->Attribute("name")) what = fmt::format("geom '{}'", n);
    what += file.empty() ? fmt::format(" (line {})", g->GetLineNum())
                         : fmt::format(" ({}:{})", file, g->GetLineNum());
    try {
      measure(g, childclass, what, link);
    } catch (const GeometryProblem& p) {
      if (p.text.starts_with(what)) throw;
      throw GeometryProblem{fmt::format("{}: {}", what, p.text)};
    }
  }

 private:
  void measure(const tinyxml2::XMLElement* g, const std::string& childclass,
               const std::string& what, LinkGeometry& link) const {
    const char* own_class = g->Attribute("class");
    const std::string cls = own_class != nullptr ? own_class : childclass;
    const auto d = defaults_.geom.find(cls);
    if (d == defaults_.geom.end()) {
      throw GeometryProblem{fmt::format("unknown default class '{}'", cls)};
    }
    const Attributes& def = d->second;
    auto attr = [&](const char* key) -> const char* {
      if (const char* own = g->Attribute(key)) return own;
      const auto it = def.find(key);
      return it == def.end() ? nullptr : it->second.c_str();
    };
    auto number = [&](const char* key, double fallback) {
      const char* t = attr(key);
      return t == nullptr ? fallback : parse_numbers(t, 1, fmt::format("attribute '{}'", key))[0];
    };

    if (const double group = number("group", 0);
        group < compiler_.group_min || group > compiler_.group_max) {
      return;  // MuJoCo's compiler leaves it out of the body's inertia
    }
    const std::string type = attr("type") != nullptr ? attr("type") : "sphere";
    std::vector<double> size;
    if (const char* s = attr("size")) size = parse_numbers(s, 0, "attribute 'size'");
    size.resize(std::max<std::size_t>(size.size(), 3), 0.0);

    // pose in the body frame
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    Eigen::Matrix3d R = orientation(g, def);
    if (const char* t = attr("pos")) {
      const auto v = parse_numbers(t, 3, "attribute 'pos'");
      p = Eigen::Vector3d(v[0], v[1], v[2]);
    }
    if (const char* t = attr("fromto")) {
      if (type != "capsule" && type != "cylinder" && type != "box" && type != "ellipsoid") {
        throw GeometryProblem{fmt::format("fromto works with capsule, cylinder, box and "
                                          "ellipsoid geoms, not type=\"{}\"", type)};
      }
      const auto v = parse_numbers(t, 6, "attribute 'fromto'");
      const Eigen::Vector3d a(v[0], v[1], v[2]), b(v[3], v[4], v[5]);
      const Eigen::Vector3d axis = b - a;
      if (!(axis.norm() > 0)) {
        throw GeometryProblem{fmt::format("fromto=\"{}\" has zero length", t)};
      }
      p = 0.5 * (a + b);
      R = z_to(axis);
      // the half length along the segment replaces the geom's last size; a box or ellipsoid
      // along a segment has size[0] as its half size across it in both directions (what
      // MuJoCo 2.2's compiler does: it reads no size[1] there)
      if (type == "capsule" || type == "cylinder") {
        size[1] = 0.5 * axis.norm();
      } else {
        if (size[1] != 0 && size[1] != size[0]) {
          link.warnings.push_back(fmt::format(
              "{}: a {} along fromto has size[0] = {} across it in both directions (MuJoCo's "
              "rule); size[1] = {} is not used", what, type, size[0], size[1]));
        }
        size[1] = size[0];
        size[2] = 0.5 * axis.norm();
      }
    }

    // the shape in its own frame at density 1 (mass = volume), then its density or mass
    double volume = 0;
    std::optional<MassProperties> unit;
    if (type == "sphere") {
      unit = catalogue_primitive("solid_sphere", 1.0, {size[0]}, what);
    } else if (type == "capsule") {
      unit = catalogue_primitive("solid_capsule", 1.0, {size[0], 2 * size[1]}, what);
    } else if (type == "cylinder") {
      unit = catalogue_primitive("solid_cylinder", 1.0, {size[0], 2 * size[1]}, what);
    } else if (type == "box") {
      unit = catalogue_primitive("solid_box", 1.0, {2 * size[0], 2 * size[1], 2 * size[2]}, what);
    } else if (type == "ellipsoid") {
      unit = catalogue_primitive("solid_ellipsoid", 1.0, {size[0], size[1], size[2]}, what);
    } else if (type == "mesh") {
      if (const char* shell = attr("shellinertia"); shell != nullptr && std::string_view(shell) == "true") {
        throw GeometryProblem{"shellinertia=\"true\" is not supported: the mesh is measured as a "
                              "solid; give the body an <inertial> instead"};
      }
      const char* mesh = attr("mesh");
      if (mesh == nullptr) throw GeometryProblem{fmt::format("{} has no 'mesh' attribute", what)};
      const auto m = meshes_.find(std::string_view(mesh));
      if (m == meshes_.end()) {
        throw GeometryProblem{fmt::format("{}: no <mesh> asset named '{}' with a file", what, mesh)};
      }
      double v = 0;
      unit = mesh_solid(m->second.file, m->second.scale, 1.0, what, v, link.warnings);
      if (!compiler_.exact_mesh_inertia) {
        // MuJoCo 2.x's default ("legacy") sums |volume| of pyramids from the surface centroid,
        // which is not the solid's inertia unless every face sees that point from outside
        link.warnings.push_back(fmt::format(
            "{}: the exact solid inertia of mesh '{}' is written; MuJoCo's legacy mesh inertia "
            "(the default without <compiler exactmeshinertia=\"true\">) can differ from it",
            what, mesh));
      }
    } else {
      throw GeometryProblem{fmt::format(
          "{}: type=\"{}\" has no volume to measure; expected sphere, capsule, cylinder, box, "
          "ellipsoid or mesh (give the body an <inertial> instead)", what, type)};
    }
    volume = unit->mass();
    link.volume += volume;
    // MuJoCo: a `mass` attribute replaces the density (ρ = mass / V)
    const double density = number("density", 1000.0);
    const double mass = attr("mass") != nullptr ? number("mass", 0.0) : density * volume;
    if (!(mass >= 0) || !std::isfinite(mass)) {
      throw GeometryProblem{fmt::format("{}: mass {} kg (density {} kg/m³): expected a "
                                        "non-negative finite value", what, mass, density)};
    }
    if (mass == 0) {
      link.has_massless_geometry = true;
      return;
    }
    const double k = mass / volume;
    const MassProperties in_geom(mass, unit->com(), k * unit->inertia_com());
    link.parts.push_back(in_geom.transformed(R, p));
  }

  // the geom's own orientation attribute (at most one), else a quat from its class
  Eigen::Matrix3d orientation(const tinyxml2::XMLElement* g, const Attributes& def) const {
    if (const auto own = mjcf_orientation(g, compiler_)) return *own;
    const auto q = def.find("quat");
    if (q == def.end()) return Eigen::Matrix3d::Identity();
    return quaternion_rotation(q->second.c_str());
  }

  const Compiler& compiler_;
  const Defaults& defaults_;
  const std::map<std::string, MeshAsset, std::less<>>& meshes_;
};

void collect_bodies(const tinyxml2::XMLElement* parent, const std::string& childclass,
                    const GeomReader& reader, const MjcfDocument& doc, const Compiler& compiler,
                    std::vector<LinkGeometry>& out) {
  for (const auto* b : doc.children(parent, "body")) {
    LinkGeometry link;
    link.element = b;
    link.line = b->GetLineNum();
    if (const char* n = b->Attribute("name")) link.name = n;
    const char* cc = b->Attribute("childclass");
    const std::string cls = cc != nullptr ? cc : childclass;
    const auto inertials = doc.children(b, "inertial");
    link.inertial = inertials.empty() ? nullptr : inertials.front();
    if (compiler.inertiafromgeom == "false") {
      link.recompute = false;
      link.keep_detail = "<compiler inertiafromgeom=\"false\">: MuJoCo uses the <inertial> as it is";
    } else if (compiler.inertiafromgeom == "auto" && link.inertial != nullptr) {
      link.recompute = false;
      link.keep_detail = "<compiler inertiafromgeom=\"auto\">: MuJoCo uses a body's own <inertial>";
    }
    for (const auto* g : doc.children(b, "geom")) {
      try {
        const std::string& file = doc.file_of(g);
        reader.add(g, cls, link, file == doc.file_of(b) ? std::string() : file);
      } catch (const GeometryProblem& p) {
        link.errors.push_back(p.text);
      }
    }
    out.push_back(std::move(link));
    collect_bodies(b, cls, reader, doc, compiler, out);
  }
}

std::vector<LinkGeometry> measured_bodies(const MjcfDocument& doc) {
  const Compiler compiler = read_mjcf_compiler(doc);
  const Defaults defaults = read_mjcf_defaults(doc);
  const auto meshes = read_meshes(doc, defaults, compiler);
  const GeomReader reader(compiler, defaults, meshes);
  std::vector<LinkGeometry> out;
  for (const auto* w : doc.children(doc.root(), "worldbody")) {
    collect_bodies(w, "main", reader, doc, compiler, out);
  }
  return out;
}

}  // namespace

std::string read_model_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  RIGID_REQUIRE_AS("read_model_file", !ec && fs::exists(st), "'{}' does not exist", path);
  RIGID_REQUIRE_AS("read_model_file", fs::is_regular_file(st),
                   "'{}' is not a regular file (a directory, FIFO or device); expected a model "
                   "file", path);
  const std::uintmax_t size = fs::file_size(path, ec);
  RIGID_REQUIRE_AS("read_model_file", !ec && size <= kMaxModelFileBytes,
                   "'{}' is {} bytes; a model file of at most {} MiB is read", path, size,
                   kMaxModelFileBytes >> 20u);
  std::ifstream in(path, std::ios::binary);
  RIGID_REQUIRE_AS("read_model_file", in.good(), "cannot open '{}' for reading", path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

MjcfDocument::MjcfDocument(const tinyxml2::XMLElement* root, std::string source,
                           bool follow_includes)
    : root_(root), source_(std::move(source)) {
  file_names_[root->GetDocument()] = source_;
  if (follow_includes) {
    std::vector<std::string> seen;
    load_includes(root, seen);
  }
}

MjcfDocument::~MjcfDocument() = default;

const std::string& MjcfDocument::file_of(const tinyxml2::XMLElement* e) const {
  const auto it = file_names_.find(e->GetDocument());
  return it == file_names_.end() ? source_ : it->second;
}

const tinyxml2::XMLElement* MjcfDocument::included_root(const tinyxml2::XMLElement* include) const {
  const auto it = include_roots_.find(include);
  return it == include_roots_.end() ? nullptr : it->second;
}

const std::string& MjcfDocument::included_text(const tinyxml2::XMLElement* root) const {
  return included_texts_.at(root);
}

void MjcfDocument::refuse(const tinyxml2::XMLElement* e, const std::string& message) const {
  rigid::detail::throw_error_at(SourceLocation{file_of(e), e->GetLineNum(), 0}, message);
}

// every <include> below e, depth first, each file read and parsed once
void MjcfDocument::load_includes(const tinyxml2::XMLElement* e, std::vector<std::string>& seen) {
  for (const auto* c = e->FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) {
    if (std::string_view(c->Name()) != "include") {
      load_includes(c, seen);
      continue;
    }
    const char* file = c->Attribute("file");
    if (file == nullptr || *file == '\0') refuse(c, "<include> has no 'file' attribute");
    const std::filesystem::path dir = std::filesystem::path(source_).parent_path();
    const std::string path = (dir / file).lexically_normal().string();
    if (std::find(seen.begin(), seen.end(), path) != seen.end() ||
        path == std::filesystem::path(source_).lexically_normal().string()) {
      refuse(c, fmt::format("<include file=\"{}\">: '{}' is already part of the model; MuJoCo "
                            "includes a file at most once", file, path));
    }
    seen.push_back(path);
    std::string text;
    try {
      text = read_model_file(path);
    } catch (const Error& err) {
      refuse(c, fmt::format("<include file=\"{}\">: {} (the path is relative to the main "
                            "file's directory, as MuJoCo reads it)", file,
                            strip_function_names(err.what())));
    }
    auto included = std::make_unique<tinyxml2::XMLDocument>();
    parse_xml(*included, text, path);
    const tinyxml2::XMLElement* root = included->RootElement();
    if (root->FirstChildElement() == nullptr) {
      rigid::detail::throw_error_at(SourceLocation{path, root->GetLineNum(), 0},
                                    fmt::format("<{}>, included from {}:{}, has no elements; "
                                                "MuJoCo inserts at least one", root->Name(),
                                                file_of(c), c->GetLineNum()));
    }
    file_names_[included.get()] = path;
    include_roots_[c] = root;
    included_texts_[root] = std::move(text);
    included_docs_.push_back(std::move(included));
    load_includes(root, seen);
  }
}

void MjcfDocument::append_children(const tinyxml2::XMLElement* e, std::string_view name,
                                   std::vector<const tinyxml2::XMLElement*>& out) const {
  for (const auto* c = e->FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) {
    if (const auto it = include_roots_.find(c); it != include_roots_.end()) {
      append_children(it->second, name, out);
    } else if (name.empty() || name == c->Name()) {
      out.push_back(c);
    }
  }
}

std::vector<const tinyxml2::XMLElement*> MjcfDocument::children(const tinyxml2::XMLElement* e,
                                                                std::string_view name) const {
  std::vector<const tinyxml2::XMLElement*> out;
  append_children(e, name, out);
  return out;
}

MjcfCompiler read_mjcf_compiler(const MjcfDocument& doc) {
  Compiler c;
  for (const auto* e : doc.children(doc.root(), "compiler")) read_compiler_element(e, doc, c);
  return c;
}

MjcfDefaults read_mjcf_defaults(const MjcfDocument& doc) {
  Defaults defaults;
  defaults.geom["main"];
  defaults.mesh["main"];
  defaults.joint["main"];
  for (const auto* d : doc.children(doc.root(), "default")) read_defaults(d, "", defaults, doc);
  return defaults;
}

std::vector<LinkGeometry> mjcf_links(const tinyxml2::XMLElement* root, const std::string& source) {
  const MjcfDocument doc(root, source, false);
  refuse_unfollowed(root, doc);
  return measured_bodies(doc);
}

std::vector<LinkGeometry> mjcf_links(const MjcfDocument& doc) {
  // an <include> left in the tree is one this document did not follow
  refuse_unfollowed(doc.root(), doc);
  return measured_bodies(doc);
}

}  // namespace rigid::io::detail
