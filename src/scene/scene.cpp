#include "rigid/scene/scene.hpp"
#include "rigid/scene/density_field.hpp"
#include "rigid/scene/robot_scene.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "rigid/common/did_you_mean.hpp"
#include "rigid/common/escape.hpp"
#include "rigid/common/number_literal.hpp"
#include "rigid/common/wording.hpp"
#include "rigid/io/run_output.hpp"
#include "rigid/lagrange/names.hpp"
#include "rigid/lagrange/system.hpp"
#include "rigid/mass/primitive_table.hpp"

namespace rigid::scene {
namespace {

using Keys = std::vector<std::string>;

const Keys kTopKeys = {"model", "parameters", "coordinates", "bodies", "constraints",
                       "potentials", "forces", "springs", "gravity", "simulation", "output",
                       "lagrangian", "velocity_constraints"};
const Keys kModelKeys = {"file", "pin_free_root", "inertia_from_geometry", "density",
                         "symbolic_inertia"};

// The parser keeps the file name and turns every toml++ position into a message that
// starts with file:line:col.
class Parser {
 public:
  explicit Parser(std::filesystem::path file, std::string_view text = {})
      : file_(std::move(file)), text_(text) {}

  [[nodiscard]] SourceLocation where(const toml::source_region& r) const {
    return {file_.string(), static_cast<int>(r.begin.line), static_cast<int>(r.begin.column)};
  }
  [[noreturn]] void fail(const toml::source_region& r, const std::string& message) const {
    detail::throw_error_at(where(r), message);
  }
  [[noreturn]] void fail(const toml::node& n, const std::string& message) const {
    fail(n.source(), message);
  }

  // Every key of `t` must be one of `allowed`; otherwise say which, where, and the closest.
  void check_keys(const toml::table& t, std::string_view context, const Keys& allowed) const {
    for (auto&& [key, value] : t) {
      if (std::find(allowed.begin(), allowed.end(), key.str()) != allowed.end()) continue;
      std::string msg = fmt::format("unknown key '{}' in {}", key.str(), context);
      if (&allowed != &kTopKeys &&
          std::find(kTopKeys.begin(), kTopKeys.end(), key.str()) != kTopKeys.end()) {
        // TOML puts every key after a [header] into that table: a classic slip.
        fail(key.source(), msg + fmt::format("; '{}' is a top-level key: move it above the first "
                                             "[table] header",
                                             key.str()));
      }
      if (auto guess = did_you_mean(key.str(), allowed)) msg += fmt::format("; did you mean '{}'?", *guess);
      msg += fmt::format(" (expected one of: {})", fmt::join(allowed, ", "));
      fail(key.source(), msg);
    }
  }

  static std::string_view type_name(const toml::node& n) {
    switch (n.type()) {
      case toml::node_type::string: return "a string";
      case toml::node_type::integer: return "an integer";
      case toml::node_type::floating_point: return "a number";
      case toml::node_type::boolean: return "a boolean";
      case toml::node_type::array: return "an array";
      case toml::node_type::table: return "a table";
      default: return "a date or time";
    }
  }

  [[nodiscard]] Expression expression(const toml::node& n, std::string_view what) const {
    Expression e;
    e.where = where(n.source());
    if (auto s = n.as_string()) {
      e.text = s->get();
      e.quoted = true;
      if (e.text.find_first_not_of(" \t") == std::string::npos) {
        fail(n, fmt::format("{} is an empty expression; expected a number or an expression", what));
      }
      return e;
    }
    if (n.is_number()) {
      const double v = finite(n, what);
      e.number = v;
      e.text = fmt::format("{}", v);
      return e;
    }
    fail(n, fmt::format("{} must be a number or an expression string, got {}", what, type_name(n)));
  }

  [[nodiscard]] const toml::node& required(const toml::table& t, const toml::source_region& at,
                                           std::string_view key, std::string_view context) const {
    const toml::node* n = t.get(key);
    if (n == nullptr) fail(at, fmt::format("{} is missing '{}'", context, key));
    return *n;
  }

  [[nodiscard]] std::string string(const toml::node& n, std::string_view what) const {
    if (auto s = n.as_string()) return s->get();
    fail(n, fmt::format("{} must be a string, got {}", what, type_name(n)));
  }

  [[nodiscard]] std::string identifier(const toml::node& n, std::string_view what) const {
    std::string s = string(n, what);
    const bool ok = !s.empty() && (std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_') &&
                    std::all_of(s.begin(), s.end(), [](char c) {
                      return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
                    });
    if (!ok) {
      fail(n, fmt::format("{} '{}' is not a valid name; expected letters, digits and '_', "
                          "starting with a letter",
                          what, escaped(s)));
    }
    return s;
  }

  [[nodiscard]] double number(const toml::node& n, std::string_view what) const {
    if (!n.is_number()) fail(n, fmt::format("{} must be a number, got {}", what, type_name(n)));
    return finite(n, what);
  }

  // The double of a TOML number: a float as written (finite), an integer only if a double holds
  // it exactly (|n| ≤ 2^53; above, toml++ gives no double and the value would be rounded).
  [[nodiscard]] double finite(const toml::node& n, std::string_view what) const {
    if (auto i = n.as_integer()) {
      const std::int64_t v = i->get();
      constexpr std::int64_t kExact = std::int64_t{1} << 53;
      if (v > kExact || v < -kExact) {
        fail(n, fmt::format("{} is the integer {}, beyond the integers a double holds exactly (|n| ≤ "
                            "2^53 = {}); write it as a float (e.g. {:.16e}) to accept rounding",
                            what, v, kExact, static_cast<double>(v)));
      }
      return static_cast<double>(v);
    }
    const double v = n.as_floating_point()->get();
    // toml++ rounds 1e-400 to 0 and keeps 2.2e-309 as a subnormal: the literal as written says
    // whether the double holds its value
    if (auto problem = literal_range_problem(literal_at(n.source()))) {
      fail(n, fmt::format("{}: {}", what, *problem));
    }
    if (!std::isfinite(v)) fail(n, fmt::format("{} is {}; expected a finite number", what, v));
    return v;
  }

  // The number literal that starts at `r` in the file's text (empty when the text is unknown).
  [[nodiscard]] std::string_view literal_at(const toml::source_region& r) const {
    std::size_t offset = 0;
    for (std::size_t line = 1; line < r.begin.line && offset != std::string_view::npos; ++line) {
      offset = text_.find('\n', offset);
      if (offset != std::string_view::npos) ++offset;
    }
    if (offset == std::string_view::npos || r.begin.column < 1) return {};
    offset += r.begin.column - 1;
    return offset < text_.size() ? leading_literal(text_.substr(offset)) : std::string_view{};
  }

  [[nodiscard]] bool boolean(const toml::node& n, std::string_view what) const {
    if (auto b = n.as_boolean()) return b->get();
    fail(n, fmt::format("{} must be true or false, got {}", what, type_name(n)));
  }

  [[nodiscard]] const toml::array& array(const toml::node& n, std::string_view what,
                                         std::size_t size) const {
    const toml::array* a = n.as_array();
    if (a == nullptr) fail(n, fmt::format("{} must be an array of {}, got {}", what, size, type_name(n)));
    if (a->size() != size) {
      fail(n, fmt::format("{} must have {} elements, got {}", what, size, a->size()));
    }
    return *a;
  }

  [[nodiscard]] std::array<double, 3> vector3(const toml::node& n, std::string_view what) const {
    const auto& a = array(n, what, 3);  // three elements: a[i] (unchecked) is never null
    return {number(a[0], what), number(a[1], what), number(a[2], what)};
  }

  [[nodiscard]] std::array<Expression, 3> expression3(const toml::node& n, std::string_view what) const {
    const auto& a = array(n, what, 3);
    return {expression(*a.get(0), what), expression(*a.get(1), what), expression(*a.get(2), what)};
  }

  [[nodiscard]] const toml::table& table(const toml::node& n, std::string_view what) const {
    if (auto t = n.as_table()) return *t;
    fail(n, fmt::format("{} must be a table, got {}", what, type_name(n)));
  }

  // [[name]] arrays of tables; a single [name] table is reported as the wrong form.
  template <typename F>
  void each_table(const toml::table& root, std::string_view key, F&& f) const {
    const toml::node* n = root.get(key);
    if (n == nullptr) return;
    const toml::array* a = n->as_array();
    if (a == nullptr) {
      fail(*n, fmt::format("'{}' must be an array of tables, written [[{}]], got {}", key, key,
                           type_name(*n)));
    }
    std::size_t i = 0;
    for (const toml::node& e : *a) {
      ++i;
      if (!e.is_table()) {
        fail(e, fmt::format("entry {} of '{}' must be a table, got {}", i, key, type_name(e)));
      }
      f(*e.as_table(), i);
    }
  }

  const std::filesystem::path& file() const { return file_; }

  // An expression written as a TOML string, with `where` at its first character: a
  // multi-line string ("""…""" or '''…''', whose first line break is not part of it) starts
  // after its delimiter, so that positions inside it (line breaks counted) point into the file.
  [[nodiscard]] Expression multiline_expression(const toml::node& n, std::string_view what) const {
    Expression e = expression(n, what);
    if (!e.quoted || text_.empty()) return e;
    // the offset of the node's line and column in the text (toml++ counts from 1, in bytes)
    std::size_t offset = 0;
    for (int line = 1; line < e.where.line && offset != std::string_view::npos; ++line) {
      offset = text_.find('\n', offset);
      if (offset != std::string_view::npos) ++offset;
    }
    if (offset == std::string_view::npos) return e;
    offset += static_cast<std::size_t>(e.where.column - 1);
    const std::string_view rest = offset < text_.size() ? text_.substr(offset) : std::string_view{};
    if (!(rest.starts_with("\"\"\"") || rest.starts_with("'''"))) return e;  // '…' or "…": one column
    e.quoted = false;
    if (rest.substr(3).starts_with("\n") || rest.substr(3).starts_with("\r\n")) {
      e.where.line += 1;
      e.where.column = 1;
    } else {
      e.where.column += 3;
    }
    return e;
  }

 private:
  std::filesystem::path file_;
  std::string_view text_;
};

// |v| without overflow or underflow in the squares (components up to 1e308): scaled by the
// largest component first.
double safe_norm(const std::array<double, 3>& v) {
  const double scale = std::max({std::abs(v[0]), std::abs(v[1]), std::abs(v[2])});
  if (!(scale > 0)) return 0.0;
  const double x = v[0] / scale, y = v[1] / scale, z = v[2] / scale;
  return scale * std::sqrt(x * x + y * y + z * z);
}

// The largest initial rotation angle (rad): a million turns, where its rounding is still below
// 1e-9 rad.
constexpr double kMaxAngle = 2 * 3.141592653589793 * 1e6;

// A size alias "<group>_<digit>" (size_0, semi_axes_1) makes "<group>" a key that takes an
// array: size = [lx, ly, lz] gives size_0, size_1, size_2.
std::optional<std::string> vector_group(const std::string& alias) {
  const auto u = alias.rfind('_');
  if (u == std::string::npos || u + 2 != alias.size() || !std::isdigit(static_cast<unsigned char>(alias.back()))) {
    return std::nullopt;
  }
  return alias.substr(0, u);
}

// The primitive keys of a body, from the catalogue: every size name and alias, the array
// groups, and the vertices of the shapes given by points.
const Keys kDimensionKeys = [] {
  Keys k;
  auto add = [&](const std::string& key) {
    if (std::find(k.begin(), k.end(), key) == k.end()) k.push_back(key);
  };
  for (const mass::PrimitiveEntry& e : mass::primitive_table()) {
    for (const mass::PrimitiveSize& sz : e.sizes) {
      add(sz.name);
      for (const std::string& a : sz.aliases) {
        add(a);
        if (auto g = vector_group(a)) add(*g);
      }
    }
    for (const mass::PrimitivePoint& pt : e.points) add(pt.name);
  }
  return k;
}();
const Keys kMeshKeys = {"units", "shell", "thickness", "fill_holes"};
const Keys kBodyKeys = [] {
  Keys k = {"name", "primitive", "mesh", "inertia", "point_masses", "mass", "density",
            "density_field", "position", "rotation", "parent", "joints", "free", "initial_position",
            "initial_quaternion", "initial_rotation", "initial_velocity", "angular_velocity",
            "pivot"};
  k.insert(k.end(), kMeshKeys.begin(), kMeshKeys.end());
  k.insert(k.end(), kDimensionKeys.begin(), kDimensionKeys.end());
  return k;
}();

// The sizes and vertices of the body's primitive, each checked against the catalogue entry
// (an unknown size names the ones the shape takes); an array key (size = [..]) is split.
void parse_primitive(const Parser& p, const toml::table& t, const std::string& context, MassSpec& m) {
  const toml::node& name_node = *t.get("primitive");
  const std::string name = p.string(name_node, context + " primitive");
  const mass::PrimitiveEntry* entry = nullptr;
  try {
    entry = &mass::find_primitive(name);
  } catch (const Error& e) {
    p.fail(name_node, fmt::format("{} primitive: {}", context, e.what()));
  }
  m.primitive = entry->name;
  std::vector<std::string> takes;
  for (const auto& sz : entry->sizes) takes.push_back(sz.name);
  for (const auto& pt : entry->points) takes.push_back(pt.name);
  const std::string takes_text = takes.empty() ? "nothing" : fmt::format("{}", fmt::join(takes, ", "));
  auto size_of = [&](const std::string& key, const toml::source_region& at) {
    const auto i = entry->size_index(key);
    if (!i) {
      p.fail(at, fmt::format("'{}' is not a size of primitive '{}'{}; it takes {} (m)", key, entry->name,
                             did_you_mean_hint(key, takes), takes_text));
    }
    return entry->sizes[*i].name;
  };
  for (auto&& [k, node] : t) {
    const std::string key(k.str());
    if (std::find(kDimensionKeys.begin(), kDimensionKeys.end(), key) == kDimensionKeys.end()) continue;
    if (entry->point_index(key)) {
      m.vertices.emplace_back(entry->points[*entry->point_index(key)].name,
                            p.expression3(node, fmt::format("{} {} (x, y, z in m)", context, key)));
      continue;
    }
    if (const toml::array* a = node.as_array()) {
      // vector sizes (size = [x, y, z], semi_axes = [a, b, c]) become key_0, key_1, ...
      std::size_t i = 0;
      for (const toml::node& e : *a) {
        m.dimensions.emplace_back(size_of(fmt::format("{}_{}", key, i++), k.source()),
                                  p.expression(e, fmt::format("{} {}", context, key)));
      }
    } else {
      m.dimensions.emplace_back(size_of(key, k.source()), p.expression(node, fmt::format("{} {}", context, key)));
    }
  }
}

void parse_mass(const Parser& p, const toml::table& t, const std::string& context, Body& body) {
  MassSpec& m = body.mass;
  m.where = body.where;
  const int sources = (t.contains("primitive") ? 1 : 0) + (t.contains("mesh") ? 1 : 0) +
                      (t.contains("inertia") ? 1 : 0) + (t.contains("point_masses") ? 1 : 0);
  if (sources != 1) {
    p.fail(t.source(), fmt::format("{} needs exactly one of 'primitive', 'mesh', 'inertia' or "
                                   "'point_masses' to give its mass properties, got {}",
                                   context, sources));
  }
  if (auto n = t.get("mass")) m.mass = p.expression(*n, context + " mass");
  if (auto n = t.get("density")) m.density = p.expression(*n, context + " density");
  for (const auto& key : kDimensionKeys) {
    if (auto n = t.get(key); n != nullptr && !t.contains("primitive")) {
      p.fail(*n, fmt::format("'{}' in {} is a primitive's size, but the body has no 'primitive'", key, context));
    }
  }
  for (const auto& key : kMeshKeys) {
    if (auto n = t.get(key); n != nullptr && !t.contains("mesh")) {
      p.fail(*n, fmt::format("'{}' in {} goes with 'mesh', but the body has no 'mesh'", key, context));
    }
  }
  if (auto n = t.get("density_field")) {
    // ρ(x, y, z): a string (an expression of x, y, z), with a primitive that has a cubature
    if (!n->is_string()) {
      p.fail(*n, fmt::format("{} density_field must be an expression string of x, y, z (kg/m³), "
                             "got {}", context, Parser::type_name(*n)));
    }
    m.density_field = p.expression(*n, context + " density_field");
    if (t.contains("mass") || t.contains("density")) {
      p.fail(*n, fmt::format("{}: density_field gives the mass; it takes no 'mass' or 'density'", context));
    }
    const std::string primitive = t.contains("primitive") ? p.string(*t.get("primitive"), context + " primitive") : "";
    const mass::PrimitiveEntry* entry = nullptr;
    if (!primitive.empty()) {
      try {
        entry = &mass::find_primitive(primitive);
      } catch (const Error&) {
        entry = nullptr;  // refused with its own message by parse_primitive
      }
    }
    if (entry != nullptr && !takes_density_field(entry->name)) {
      p.fail(*n, fmt::format("{}: density_field is integrated over a box, a cylinder, a sphere or "
                             "a closed mesh, not a {}; give it a constant 'density'",
                             context, entry->name));
    }
    if (!t.contains("primitive") && !t.contains("mesh")) {
      p.fail(*n, fmt::format("{}: density_field goes with 'primitive' (box, cylinder or sphere) "
                             "or 'mesh' (a closed one)", context));
    }
    for (const char* key : {"shell", "thickness"}) {
      if (t.contains(key)) {
        p.fail(*n, fmt::format("{}: density_field is the density of a solid; a mesh with '{}' is "
                               "a shell: give it a constant 'density'", context, key));
      }
    }
  }
  const bool needs_amount = (t.contains("primitive") || t.contains("mesh")) && !m.density_field;
  if (needs_amount && m.mass.has_value() == m.density.has_value()) {
    p.fail(t.source(), fmt::format("{} needs exactly one of 'mass' (kg) and 'density' (kg/m³){}",
                                   context, m.mass ? ", not both" : ""));
  }
  if (!needs_amount && (m.density || (m.mass && t.contains("point_masses")))) {
    p.fail(t.source(), fmt::format("{}: 'mass'/'density' go with 'primitive' or 'mesh'; 'inertia' "
                                   "carries its own mass and point masses each have one",
                                   context));
  }
  if (t.contains("primitive")) {
    m.kind = MassSpec::Kind::kPrimitive;
    parse_primitive(p, t, context, m);
  } else if (auto mesh = t.get("mesh")) {
    m.kind = MassSpec::Kind::kMesh;
    std::filesystem::path f = p.string(*mesh, context + " mesh");
    m.mesh_file = f.is_absolute() ? f : p.file().parent_path() / f;
    if (auto u = t.get("units")) m.units = p.string(*u, context + " units");
    if (auto n = t.get("shell")) m.shell = p.boolean(*n, context + " shell");
    if (auto n = t.get("fill_holes")) m.fill_holes = p.boolean(*n, context + " fill_holes");
    if (auto n = t.get("thickness")) m.thickness = p.expression(*n, context + " thickness (m)");
  } else if (auto inertia = t.get("inertia")) {
    m.kind = MassSpec::Kind::kExplicit;
    const toml::table& it = p.table(*inertia, context + " inertia");
    const std::string ic = context + " inertia";
    p.check_keys(it, ic, {"mass", "com", "ixx", "iyy", "izz", "ixy", "ixz", "iyz"});
    m.mass = p.expression(p.required(it, inertia->source(), "mass", ic), ic + " mass");
    if (auto c = it.get("com")) {
      m.com = p.expression3(*c, ic + " com");
    } else {
      for (auto& e : m.com) e = Expression{"0", p.where(inertia->source()), 0.0, false};
    }
    for (std::size_t i = 0; i < 6; ++i) {
      const auto& e = lagrange::BodyMass::kInertiaElements[i];
      if (auto v = it.get(e.name)) {
        m.inertia[i] = p.expression(*v, ic + " " + e.name);
      } else if (e.row == e.col) {
        p.fail(inertia->source(), fmt::format("{} is missing '{}' (kg·m², about the COM)", ic, e.name));
      } else {
        m.inertia[i] = Expression{"0", p.where(inertia->source()), 0.0, false};
      }
    }
  } else {
    m.kind = MassSpec::Kind::kPointMasses;
    const toml::node& pm = *t.get("point_masses");
    const toml::array* a = pm.as_array();
    if (a == nullptr || a->empty()) {
      p.fail(pm, fmt::format("{} point_masses must be a non-empty array of {{mass, position}} tables",
                             context));
    }
    for (const toml::node& e : *a) {
      const toml::table& pt = p.table(e, context + " point mass");
      p.check_keys(pt, context + " point mass", {"mass", "position"});
      PointMass point;
      point.mass = p.expression(p.required(pt, e.source(), "mass", context + " point mass"), "mass");
      point.position = p.expression3(p.required(pt, e.source(), "position", context + " point mass"),
                                     "position");
      m.points.push_back(std::move(point));
    }
  }
}

// [[bodies.joints]]: exactly one of turn (rad) or slide (m), an expression; axis (required,
// non-zero, normalised here); anchor (m, default 0; a turn's only).
void parse_joints(const Parser& p, const toml::node& n, const std::string& context, Body& body) {
  const toml::array* a = n.as_array();
  if (a == nullptr) {
    p.fail(n, fmt::format("{} joints must be an array of tables, written [[bodies.joints]] under "
                          "the body, got {}",
                          context, Parser::type_name(n)));
  }
  std::size_t i = 0;
  for (const toml::node& e : *a) {
    const std::string ctx = fmt::format("{} joint {}", context, ++i);
    const toml::table& jt = p.table(e, ctx);
    p.check_keys(jt, ctx, {"turn", "slide", "axis", "anchor"});
    Joint j;
    j.where = p.where(e.source());
    const toml::node* turn = jt.get("turn");
    const toml::node* slide = jt.get("slide");
    if (turn != nullptr && slide != nullptr) {
      p.fail(*slide, fmt::format("{} has both 'turn' and 'slide'; a joint is one of them (add a "
                                 "second [[bodies.joints]] for the other)",
                                 ctx));
    }
    if (turn == nullptr && slide == nullptr) {
      p.fail(e, fmt::format("{} is missing 'turn' or 'slide': the angle (rad) it turns about its "
                            "axis, or the distance (m) it slides along it",
                            ctx));
    }
    j.kind = turn != nullptr ? Joint::Kind::kTurn : Joint::Kind::kSlide;
    j.amount = p.expression(turn != nullptr ? *turn : *slide,
                            ctx + (turn != nullptr ? " turn" : " slide"));
    const toml::node& axis = p.required(jt, e.source(), "axis", ctx);
    j.axis = p.vector3(axis, ctx + " axis");
    const double len = safe_norm(j.axis);
    if (!(len > 0)) p.fail(axis, fmt::format("{} axis is zero; expected a non-zero vector", ctx));
    const double scale = std::max({std::abs(j.axis[0]), std::abs(j.axis[1]), std::abs(j.axis[2])});
    for (double& c : j.axis) c = c / scale / (len / scale);
    if (auto an = jt.get("anchor")) {
      if (slide != nullptr) {
        p.fail(*an, fmt::format("{} slides, and a slide has no anchor (only a turn is about an "
                                "axis through a point); remove 'anchor'",
                                ctx));
      }
      j.anchor = p.vector3(*an, ctx + " anchor");
    }
    body.joints.push_back(std::move(j));
  }
}

void parse_pose(const Parser& p, const toml::table& t, const std::string& context, Body& body) {
  if (auto f = t.get("free")) body.free = p.boolean(*f, context + " free");
  const Keys free_keys = {"initial_position", "initial_quaternion", "initial_rotation",
                          "initial_velocity", "angular_velocity", "pivot"};
  if (body.free) {
    for (const char* key : {"position", "rotation"}) {
      if (auto n = t.get(key)) {
        p.fail(*n, fmt::format("{} is free, so its pose is a state, not an expression: use "
                               "'initial_position' and 'initial_quaternion' or 'initial_rotation' "
                               "instead of '{}'",
                               context, key));
      }
    }
    for (const char* key : {"parent", "joints"}) {
      if (auto n = t.get(key)) {
        p.fail(*n, fmt::format("{} is free, so it hangs from nothing: '{}' is for bodies posed by "
                               "[[coordinates]]",
                               context, key));
      }
    }
    if (auto n = t.get("initial_position")) body.initial_position = p.vector3(*n, "initial_position");
    if (auto n = t.get("initial_velocity")) body.initial_velocity = p.vector3(*n, "initial_velocity");
    if (auto n = t.get("angular_velocity")) body.angular_velocity = p.vector3(*n, "angular_velocity");
    if (auto n = t.get("pivot")) body.pivot = p.vector3(*n, "pivot");
    if (t.contains("initial_quaternion") && t.contains("initial_rotation")) {
      p.fail(*t.get("initial_rotation"),
             "give the initial orientation once: 'initial_quaternion' or 'initial_rotation', not both");
    }
    if (auto n = t.get("initial_quaternion")) {
      const auto& a = p.array(*n, "initial_quaternion (w, x, y, z)", 4);
      double norm2 = 0;
      for (std::size_t i = 0; i < 4; ++i) {
        body.initial_orientation[i] = p.number(*a.get(i), "initial_quaternion");
        norm2 += body.initial_orientation[i] * body.initial_orientation[i];
      }
      if (std::abs(std::sqrt(norm2) - 1.0) > 1e-9) {
        p.fail(*n, fmt::format("initial_quaternion (w, x, y, z) has norm {}; expected a unit "
                               "quaternion (|q| within 1e-9 of 1)",
                               std::sqrt(norm2)));
      }
    }
    if (auto n = t.get("initial_rotation")) {
      const toml::table& rt = p.table(*n, "initial_rotation");
      p.check_keys(rt, "initial_rotation", {"axis", "angle"});
      const auto axis = p.vector3(p.required(rt, n->source(), "axis", "initial_rotation"), "axis");
      const double angle = p.number(p.required(rt, n->source(), "angle", "initial_rotation"), "angle");
      const double len = safe_norm(axis);
      if (!(len > 0)) p.fail(*n, "initial_rotation axis is zero; expected a non-zero vector");
      if (!(std::abs(angle) <= kMaxAngle)) {
        p.fail(*n, fmt::format("initial_rotation angle {} rad is more than a million turns; expected "
                               "|angle| ≤ {:.6g} rad",
                               angle, kMaxAngle));
      }
      const double scale = std::max({std::abs(axis[0]), std::abs(axis[1]), std::abs(axis[2])});
      const double s = std::sin(angle / 2) / (len / scale) / scale;
      body.initial_orientation = {std::cos(angle / 2), axis[0] * s, axis[1] * s, axis[2] * s};
    }
    return;
  }
  for (const auto& key : free_keys) {
    if (auto n = t.get(key)) {
      p.fail(*n, fmt::format("'{}' is for free bodies; {} has a pose given by 'position' and "
                             "'rotation' (set free = true to make it a free body)",
                             key, context));
    }
  }
  if (auto n = t.get("position")) {
    body.position = p.expression3(*n, context + " position");
  } else {
    for (auto& e : body.position) e = Expression{"0", body.where, 0.0, false};
  }
  if (auto n = t.get("rotation")) {
    const toml::array* a = n->as_array();
    if (a == nullptr) {
      p.fail(*n, fmt::format("{} rotation must be an array of {{axis = [x, y, z], angle = ...}} "
                             "tables, applied left to right",
                             context));
    }
    for (const toml::node& e : *a) {
      const toml::table& rt = p.table(e, context + " rotation");
      p.check_keys(rt, context + " rotation", {"axis", "angle"});
      AxisRotation r;
      r.axis = p.vector3(p.required(rt, e.source(), "axis", context + " rotation"), "axis");
      const double len = safe_norm(r.axis);
      if (!(len > 0)) p.fail(*rt.get("axis"), "rotation axis is zero; expected a non-zero vector");
      const double scale = std::max({std::abs(r.axis[0]), std::abs(r.axis[1]), std::abs(r.axis[2])});
      for (double& c : r.axis) c = c / scale / (len / scale);
      r.angle = p.expression(p.required(rt, e.source(), "angle", context + " rotation"), "angle");
      body.rotations.push_back(std::move(r));
    }
  }
  if (auto n = t.get("parent")) {
    body.parent = p.identifier(*n, context + " parent");
    body.parent_where = p.where(n->source());
  }
  if (auto n = t.get("joints")) parse_joints(p, *n, context, body);
}

// [[output.metrics]]: every key checked, and the keys a kind does not take refused by name.
void parse_metrics(const Parser& p, const toml::node& node, std::vector<MetricSpec>& out) {
  using Kind = MetricSpec::Kind;
  static const std::vector<std::pair<std::string, Kind>> kKinds = {
      {"crossing", Kind::kCrossing}, {"extremum", Kind::kExtremum}, {"period", Kind::kPeriod},
      {"max", Kind::kMax},           {"min", Kind::kMin},           {"final", Kind::kFinal},
      {"drift", Kind::kDrift}};
  const toml::array* a = node.as_array();
  if (a == nullptr) {
    p.fail(node, fmt::format("[output] metrics must be an array of tables, written [[output.metrics]], "
                             "got {}",
                             Parser::type_name(node)));
  }
  std::size_t i = 0;
  for (const toml::node& e : *a) {
    ++i;
    const std::string ctx = fmt::format("[[output.metrics]] entry {}", i);
    const toml::table& t = p.table(e, ctx);
    p.check_keys(t, ctx, {"name", "kind", "column", "value", "direction", "k", "extremum", "report", "unit"});
    MetricSpec m;
    m.where = p.where(e.source());
    m.name = p.identifier(p.required(t, e.source(), "name", ctx), ctx + " name");
    for (const MetricSpec& other : out) {
      if (other.name == m.name) {
        p.fail(*t.get("name"), fmt::format("{}: a metric named '{}' is already defined (at {}:{}); "
                                           "metric names must be distinct",
                                           ctx, m.name, other.where.line, other.where.column));
      }
    }
    const std::string what = fmt::format("metric '{}'", m.name);
    const toml::node& kind_node = p.required(t, e.source(), "kind", what);
    const std::string kind = p.string(kind_node, what + " kind");
    std::vector<std::string> kinds;
    for (const auto& [n, k] : kKinds) kinds.push_back(n);
    const auto found = std::find_if(kKinds.begin(), kKinds.end(), [&](const auto& nk) { return nk.first == kind; });
    if (found == kKinds.end()) {
      p.fail(kind_node, fmt::format("{}: unknown kind '{}'{}; expected one of: {}", what, kind,
                                    did_you_mean_hint(kind, kinds), fmt::join(kinds, ", ")));
    }
    m.kind = found->second;
    const toml::node& column = p.required(t, e.source(), "column", what);
    m.column = p.string(column, what + " column");
    m.column_where = p.where(column.source());
    // the keys each kind takes beyond name, kind, column and unit
    auto only_for = [&](const char* key, std::initializer_list<Kind> takes, const char* kinds_text) {
      const toml::node* n = t.get(key);
      if (n != nullptr && std::find(takes.begin(), takes.end(), m.kind) == takes.end()) {
        p.fail(*n, fmt::format("{}: '{}' goes with kind {}, not '{}'", what, key, kinds_text, kind));
      }
      return n;
    };
    if (auto n = only_for("value", {Kind::kCrossing, Kind::kPeriod}, "crossing or period")) {
      m.level = p.number(*n, what + " value");
    }
    m.direction = m.kind == Kind::kPeriod ? MetricSpec::Direction::kUp : MetricSpec::Direction::kAny;
    if (auto n = only_for("direction", {Kind::kCrossing, Kind::kPeriod}, "crossing or period")) {
      const std::string d = p.string(*n, what + " direction");
      if (d == "up") {
        m.direction = MetricSpec::Direction::kUp;
      } else if (d == "down") {
        m.direction = MetricSpec::Direction::kDown;
      } else if (d == "any") {
        m.direction = MetricSpec::Direction::kAny;
      } else {
        p.fail(*n, fmt::format("{}: direction '{}' is not one of up (from below the value to above), "
                               "down, any{}",
                               what, d, did_you_mean_hint(d, {"up", "down", "any"})));
      }
    }
    if (auto n = only_for("k", {Kind::kCrossing, Kind::kExtremum, Kind::kPeriod}, "crossing, extremum or period")) {
      const auto* k = n->as_integer();
      if (k == nullptr || k->get() < 1 || k->get() > 1'000'000'000) {
        p.fail(*n, fmt::format("{}: k must be a whole number from 1 (the first event) to 1e9, got {}", what,
                               k == nullptr ? std::string(Parser::type_name(*n)) : fmt::format("{}", k->get())));
      }
      m.k = static_cast<std::size_t>(k->get());
    } else if (m.kind != Kind::kPeriod) {
      m.k = 1;
    }
    if (auto n = only_for("extremum", {Kind::kExtremum}, "extremum")) {
      const std::string x = p.string(*n, what + " extremum");
      if (x != "max" && x != "min") {
        p.fail(*n, fmt::format("{}: extremum '{}' is not max or min{}", what, x, did_you_mean_hint(x, {"max", "min"})));
      }
      m.maximum = x == "max";
    }
    if (auto n = only_for("report", {Kind::kExtremum}, "extremum")) {
      const std::string r = p.string(*n, what + " report");
      if (r != "time" && r != "value") {
        p.fail(*n, fmt::format("{}: report '{}' is not time (s) or value (the column's){}", what, r,
                               did_you_mean_hint(r, {"time", "value"})));
      }
      m.report_value = r == "value";
    }
    if (auto n = t.get("unit")) {
      m.unit = p.string(*n, what + " unit");
      m.unit_given = true;
    }
    out.push_back(std::move(m));
  }
}

// The names an expression may use (parameters, coordinates and bodies), each claimed once.
class NameClaims {
 public:
  explicit NameClaims(const Parser& p) : p_(p) {}

  // claims `name` for the `what` declared at `at`; refuses a name that is not an identifier
  // (every scene kind: a quoted TOML key may hold ESC or BEL, echoed to the terminal), a name in
  // use, 't' (time) and the other names expressions reserve (pi, the function names)
  void claim(const std::string& name, const toml::node& at, std::string_view what) {
    const bool identifier =
        !name.empty() && (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_') &&
        std::all_of(name.begin(), name.end(),
                    [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
    if (!identifier) {
      p_.fail(at, fmt::format("{} name '{}' is not a valid name; expected letters, digits and '_', "
                              "starting with a letter",
                              what, escaped(name)));
    }
    const auto it = std::find(names_.begin(), names_.end(), name);
    if (it != names_.end()) {
      const std::string& origin = origins_[static_cast<std::size_t>(it - names_.begin())];
      p_.fail(at, fmt::format("{} '{}' is already defined{}; names of parameters, coordinates and "
                              "bodies must be distinct",
                              what, name, origin.empty() ? "" : " (" + origin + ")"));
    }
    if (name == "t") p_.fail(at, fmt::format("{} may not be called 't' (that is time)", what));
    if (lagrange::is_reserved_name(name)) {
      p_.fail(at, fmt::format("{} may not be called '{}': expressions reserve it (pi and the "
                              "function names sin, cos, tan, asin, acos, atan, exp, log, sqrt, "
                              "abs, sinh, cosh, tanh); rename the {}",
                              what, name, what));
    }
    names_.push_back(name);
    origins_.emplace_back();
  }

  // a name declared outside the scene file (a coordinate of its [model]), said as `origin`
  void reserve(const std::string& name, std::string origin) {
    names_.push_back(name);
    origins_.push_back(std::move(origin));
  }

 private:
  const Parser& p_;
  std::vector<std::string> names_;    // every name an expression may use, for clashes
  std::vector<std::string> origins_;  // per name: where it comes from when not from the file
};

// [parameters]: name = expression, in the file's order.
void parse_parameters(const toml::table& root, const Parser& p, NameClaims& names, Scene& s) {
  auto n = root.get("parameters");
  if (n == nullptr) return;
  const toml::table& t = p.table(*n, "[parameters]");
  for (auto&& [key, value] : t) {
    const std::string name(key.str());
    names.claim(name, value, "parameter");
    s.parameters.push_back({name, p.expression(value, "parameter " + name)});
  }
  // toml++ keeps keys sorted; the file's order is the one a reader expects (and the
  // order in which parameters may refer to earlier ones).
  std::stable_sort(s.parameters.begin(), s.parameters.end(), [](const Parameter& a, const Parameter& b) {
    return std::pair(a.value.where.line, a.value.where.column) <
           std::pair(b.value.where.line, b.value.where.column);
  });
}

// [[coordinates]] of a scene with [model]: each entry names a joint coordinate of the model and
// sets its initial value and velocity (those it leaves out keep the model's: q = ref, q̇ = 0).
void parse_model_coordinates(const toml::table& root, const Parser& p, Scene& s) {
  std::vector<std::string> joints;
  for (const Coordinate& c : s.coordinates) joints.push_back(c.name);
  std::vector<const toml::node*> set_by(s.coordinates.size(), nullptr);
  p.each_table(root, "coordinates", [&](const toml::table& t, std::size_t i) {
    const std::string ctx = fmt::format("[[coordinates]] entry {}", i);
    const toml::node& name_node = p.required(t, t.source(), "name", ctx);
    const std::string name = p.identifier(name_node, "coordinate name");
    const auto it = std::find(joints.begin(), joints.end(), name);
    const bool ball = it != joints.end() &&
                      s.coordinates[static_cast<std::size_t>(it - joints.begin())].kind == Coordinate::Kind::kBall;
    // a ball's (or a free joint's turning part's) state is an orientation and an angular velocity
    if (ball) {
      p.check_keys(t, fmt::format("{} (the ball coordinate '{}')", ctx, name),
                   {"name", "orientation", "angular_velocity"});
    } else {
      p.check_keys(t, ctx, {"name", "initial", "velocity"});
    }
    if (it == joints.end()) {
      p.fail(name_node, fmt::format("{}: '{}' is not a joint of the model '{}'; in a scene with "
                                    "[model], [[coordinates]] set the initial values of the "
                                    "model's joints ({}){}",
                                    ctx, name, s.model->file.string(), fmt::join(joints, ", "),
                                    did_you_mean_hint(name, joints)));
    }
    const auto k = static_cast<std::size_t>(it - joints.begin());
    if (set_by[k] != nullptr) {
      p.fail(name_node, fmt::format("{}: coordinate '{}' is already set at line {}; give each "
                                    "coordinate one entry",
                                    ctx, name, set_by[k]->source().begin.line));
    }
    set_by[k] = &name_node;
    Coordinate& c = s.coordinates[k];
    if (ball) {
      if (auto n = t.get("orientation")) {
        const std::string what = name + " orientation (a unit quaternion [w, x, y, z])";
        const auto& a = p.array(*n, what, 4);
        for (std::size_t e = 0; e < 4; ++e) c.orientation[e] = p.expression(*a.get(e), what);
      }
      if (auto n = t.get("angular_velocity")) {
        c.angular_velocity = p.expression3(*n, name + " angular_velocity (in the body's frame, rad/s)");
      }
      return;
    }
    if (auto n = t.get("initial")) c.initial = p.expression(*n, name + " initial");
    if (auto n = t.get("velocity")) c.velocity = p.expression(*n, name + " velocity");
  });
}

// [[coordinates]]: name, initial and velocity (both 0 when left out).
void parse_coordinates(const toml::table& root, const Parser& p, NameClaims& names, Scene& s) {
  if (s.model) {
    parse_model_coordinates(root, p, s);
    return;
  }
  p.each_table(root, "coordinates", [&](const toml::table& t, std::size_t i) {
    const std::string ctx = fmt::format("[[coordinates]] entry {}", i);
    p.check_keys(t, ctx, {"name", "initial", "velocity"});
    Coordinate c;
    c.where = p.where(t.source());
    const toml::node& name = p.required(t, t.source(), "name", ctx);
    c.name = p.identifier(name, "coordinate name");
    names.claim(c.name, name, "coordinate");
    c.initial = t.contains("initial") ? p.expression(*t.get("initial"), c.name + " initial")
                                      : Expression{"0", c.where, 0.0, false};
    c.velocity = t.contains("velocity") ? p.expression(*t.get("velocity"), c.name + " velocity")
                                        : Expression{"0", c.where, 0.0, false};
    s.coordinates.push_back(std::move(c));
  });
}

// [[bodies]]: a name (body<i> when left out), the mass and the pose.
void parse_bodies(const toml::table& root, const Parser& p, NameClaims& names, Scene& s) {
  if (const toml::node* b = root.get("bodies"); b != nullptr && s.model) {
    p.fail(*b, fmt::format("a scene with [model] takes its bodies from the model file '{}'; adding "
                           "[[bodies]] to a model's tree is not supported: add them to the model "
                           "file as links, or write the whole scene with [[bodies]] and no [model]",
                           s.model->file.string()));
  }
  p.each_table(root, "bodies", [&](const toml::table& t, std::size_t i) {
    Body b;
    b.where = p.where(t.source());
    if (auto n = t.get("name")) {
      b.name = p.identifier(*n, "body name");
      names.claim(b.name, *n, "body");
    } else {
      b.name = fmt::format("body{}", i);
    }
    const std::string ctx = fmt::format("body '{}'", b.name);
    p.check_keys(t, ctx, kBodyKeys);
    parse_mass(p, t, ctx, b);
    parse_pose(p, t, ctx, b);
    s.bodies.push_back(std::move(b));
  });
}

// The two ends of a spring or a rope: body_a (required) and point_a, body_b and point_b.
template <typename T>
void parse_ends(const toml::table& t, const Parser& p, const std::string& ctx, T& out) {
  const toml::node& body_a = p.required(t, t.source(), "body_a", ctx);
  out.body_a = p.string(body_a, "body_a");
  if (out.body_a.empty()) p.fail(body_a, ctx + " body_a is empty; expected the name of a body");
  if (auto n = t.get("point_a")) out.point_a = p.vector3(*n, "point_a");
  if (auto n = t.get("body_b")) out.body_b = p.string(*n, "body_b");
  if (auto n = t.get("point_b")) out.point_b = p.vector3(*n, "point_b");
}

// [[constraints]], [[potentials]], [[forces]]: a name (or the coordinate a force acts on) and
// an expression; a constraint may say how it is drawn (`rope`, into `ropes`).
void parse_named_expressions(const toml::table& root, const Parser& p, std::string_view key,
                             std::string_view name_key, std::vector<NamedExpression>& out,
                             std::vector<Rope>* ropes = nullptr) {
  p.each_table(root, key, [&](const toml::table& t, std::size_t i) {
    const std::string ctx = fmt::format("[[{}]] entry {}", key, i);
    if (ropes != nullptr) {
      p.check_keys(t, ctx, {std::string(name_key), "expression", "rope"});
    } else {
      p.check_keys(t, ctx, {std::string(name_key), "expression"});
    }
    NamedExpression e;
    if (auto n = t.get(name_key)) {
      e.name = p.string(*n, ctx + " " + std::string(name_key));
    } else if (name_key == "coordinate") {
      p.fail(t.source(), ctx + " is missing 'coordinate' (the coordinate the force acts on)");
    } else {
      e.name = fmt::format("{}{}", key.substr(0, key.size() - 1), i);
    }
    e.expression = p.expression(p.required(t, t.source(), "expression", ctx), ctx + " expression");
    if (const toml::node* r = ropes != nullptr ? t.get("rope") : nullptr) {
      const std::string rctx = ctx + " rope";
      const toml::table& rt = p.table(*r, rctx);
      p.check_keys(rt, rctx, {"body_a", "point_a", "body_b", "point_b"});
      Rope rope;
      rope.constraint = e.name;
      rope.where = p.where(rt.source());
      parse_ends(rt, p, rctx, rope);
      ropes->push_back(std::move(rope));
    }
    out.push_back(std::move(e));
  });
}

// [[velocity_constraints]]: Σ A q̇ + a = 0 as coefficients per coordinate and a term.
void parse_velocity_constraints(const toml::table& root, const Parser& p, Scene& s) {
  p.each_table(root, "velocity_constraints", [&](const toml::table& t, std::size_t i) {
    const std::string ctx = fmt::format("[[velocity_constraints]] entry {}", i);
    p.check_keys(t, ctx, {"name", "coefficients", "term"});
    VelocityConstraint vc;
    vc.where = p.where(t.source());
    vc.name = t.contains("name") ? p.identifier(*t.get("name"), "velocity constraint name")
                                 : fmt::format("velocity_constraint{}", i);
    if (auto c = t.get("coefficients")) {
      const toml::table& ct = p.table(*c, ctx + " coefficients");
      std::vector<std::string> coords;
      for (const auto& co : s.coordinates) coords.push_back(co.name);
      for (auto&& [key, value] : ct) {
        const std::string coord(key.str());
        if (coords.empty()) {
          // nothing to list: say what kind of scene takes velocity constraints
          p.fail(key.source(), fmt::format("{} coefficients: '{}' is not a coordinate: the scene "
                                           "has no coordinates; velocity constraints act on the "
                                           "generalized coordinates of a scene posed by "
                                           "[[coordinates]] or a robot [model] (a scene of free "
                                           "bodies has none)",
                                           ctx, coord));
        }
        if (std::find(coords.begin(), coords.end(), coord) == coords.end()) {
          p.fail(key.source(), fmt::format("{} coefficients: '{}' is not a coordinate{}; expected "
                                           "one of: {}",
                                           ctx, coord, did_you_mean_hint(coord, coords),
                                           fmt::join(coords, ", ")));
        }
        vc.coefficients.push_back({coord, p.expression(value, fmt::format("{} coefficient of {}", ctx, coord))});
      }
    }
    if (auto n = t.get("term")) vc.term = p.expression(*n, ctx + " term");
    if (vc.coefficients.empty() && !vc.term) {
      p.fail(t.source(), ctx + " has no velocity in it; expected coefficients = {<coordinate> = "
                               "\"A(q, t)\", ...} (and optionally term = \"a(q, t)\") for "
                               "Σ A q̇ + a = 0");
    }
    s.velocity_constraints.push_back(std::move(vc));
  });
}

// [[springs]]: two bodies' points, a stiffness and a rest length (0 when left out).
void parse_springs(const toml::table& root, const Parser& p, Scene& s) {
  p.each_table(root, "springs", [&](const toml::table& t, std::size_t i) {
    const std::string ctx = fmt::format("[[springs]] entry {}", i);
    p.check_keys(t, ctx, {"body_a", "point_a", "body_b", "point_b", "stiffness", "rest_length"});
    Spring sp;
    sp.where = p.where(t.source());
    parse_ends(t, p, ctx, sp);
    sp.stiffness = p.expression(p.required(t, t.source(), "stiffness", ctx), "stiffness");
    sp.rest_length = t.contains("rest_length") ? p.expression(*t.get("rest_length"), "rest_length")
                                               : Expression{"0", sp.where, 0.0, false};
    s.springs.push_back(std::move(sp));
  });
}

// lagrangian = "…" (an expression string) and gravity = [x, y, z] (0 when left out; a
// [model]'s gravity, which the key replaces).
void parse_lagrangian_and_gravity(const toml::table& root, const Parser& p, Scene& s) {
  if (auto n = root.get("lagrangian")) {
    if (!n->is_string()) {
      p.fail(*n, fmt::format("lagrangian must be an expression string such as \"m*l^2/2*theta_dot^2 + "
                             "m*g*l*cos(theta)\", got {}", Parser::type_name(*n)));
    }
    if (s.lagrangian) {
      p.fail(*n, fmt::format("the model '{}' has a lagrangian of its own, its joints' armature "
                             "(a/2*q_dot^2 per joint); a scene's lagrangian cannot be added to it: "
                             "write its terms as [[potentials]] or [[forces]]",
                             s.model->file.string()));
    }
    s.lagrangian = p.multiline_expression(*n, "lagrangian");
  }
  if (auto n = root.get("gravity")) {
    s.gravity = p.expression3(*n, "gravity (m/s², world frame)");
  } else if (!s.model) {
    for (auto& e : s.gravity) e = Expression{"0", {s.file.string(), 0, 0}, 0.0, false};
  }
}

// [simulation] (required without [model], whose default is t_end = 5 s): t_end, and
// optionally integrator, dt, tolerance and output_dt.
void parse_simulation(const toml::table& root, const Parser& p, Scene& s) {
  const toml::node* sim = root.get("simulation");
  if (sim == nullptr && s.model) return;
  s.simulation = Simulation{};
  if (sim == nullptr) {
    p.fail(root.source(), "the scene has no [simulation] table; expected at least t_end (s)");
  }
  const toml::table& st = p.table(*sim, "[simulation]");
  p.check_keys(st, "[simulation]", {"t_end", "integrator", "dt", "tolerance", "output_dt"});
  s.simulation.where = p.where(sim->source());
  s.simulation.t_end = p.expression(p.required(st, sim->source(), "t_end", "[simulation]"), "t_end");
  if (auto n = st.get("integrator")) s.simulation.integrator = p.string(*n, "integrator");
  if (auto n = st.get("dt")) s.simulation.dt = p.expression(*n, "dt");
  if (auto n = st.get("tolerance")) s.simulation.tolerance = p.expression(*n, "tolerance");
  if (auto n = st.get("output_dt")) s.simulation.output_dt = p.expression(*n, "output_dt");
}

// [output] max_memory: a positive number of bytes or a size such as "512MiB".
void parse_max_memory(const Parser& p, const toml::node& m, Output& output) {
  output.max_memory_where = p.where(m.source());
  if (auto i = m.as_integer(); i != nullptr && i->get() > 0) {
    output.max_memory = static_cast<std::uint64_t>(i->get());
  } else if (auto text = m.as_string()) {
    try {
      output.max_memory = io::parse_memory_size(text->get());
    } catch (const Error& e) {
      p.fail(m, fmt::format("[output] max_memory: {}", e.what()));
    }
  } else {
    p.fail(m, fmt::format("[output] max_memory must be a positive number of bytes or a size such "
                          "as \"512MiB\", got {}",
                          m.is_integer() ? "a number ≤ 0" : Parser::type_name(m)));
  }
}

// [output] formats: csv, npy or json, in place of the default list.
void parse_output_formats(const Parser& p, const toml::node& f, Output& output) {
  const toml::array* a = f.as_array();
  if (a == nullptr) p.fail(f, "formats must be an array of strings such as [\"csv\", \"npy\", \"json\"]");
  output.formats.clear();
  // an empty list would leave a run nothing to write: refused here, so check and run agree
  if (a->empty()) p.fail(f, "formats = [] selects no output format; give at least one of csv, npy, json");
  const Keys known = {"csv", "npy", "json"};
  for (const toml::node& e : *a) {
    std::string fmt_name = p.string(e, "output format");
    if (std::find(known.begin(), known.end(), fmt_name) == known.end()) {
      std::string msg = fmt::format("unknown output format '{}'", fmt_name);
      if (auto g = did_you_mean(fmt_name, known)) msg += fmt::format("; did you mean '{}'?", *g);
      p.fail(e, msg + " (expected csv, npy or json)");
    }
    output.formats.push_back(std::move(fmt_name));
  }
}

// [output]: directory, formats, quantities, max_memory and metrics.
void parse_output(const toml::table& root, const Parser& p, Scene& s) {
  auto n = root.get("output");
  if (n == nullptr) return;
  const toml::table& ot = p.table(*n, "[output]");
  p.check_keys(ot, "[output]", {"directory", "formats", "quantities", "max_memory", "metrics"});
  if (auto m = ot.get("metrics")) parse_metrics(p, *m, s.output.metrics);
  if (auto m = ot.get("max_memory")) parse_max_memory(p, *m, s.output);
  if (auto q = ot.get("quantities")) {
    const toml::array* a = q->as_array();
    if (a == nullptr) {
      p.fail(*q, "quantities must be an array of column names or patterns such as [\"theta\", \"*.x\"]");
    }
    s.output.quantities_where = p.where(q->source());
    for (const toml::node& e : *a) s.output.quantities.push_back(p.string(e, "output quantity"));
  }
  if (auto d = ot.get("directory")) s.output.directory = p.string(*d, "output directory");
  if (auto f = ot.get("formats")) parse_output_formats(p, *f, s.output);
}

// A scene is either free bodies or bodies posed by coordinates: refuses a mix, and a scene
// with neither.
void check_scene_kind(const toml::table& root, const Parser& p, const Scene& s) {
  const bool any_free = std::any_of(s.bodies.begin(), s.bodies.end(), [](const Body& b) { return b.free; });
  if (any_free) {
    for (const Body& b : s.bodies) {
      if (!b.free) {
        detail::throw_error_at(b.where, fmt::format("body '{}' has no 'free = true' but other bodies "
                                                    "do; a scene is either free bodies or bodies "
                                                    "posed by coordinates",
                                                    b.name));
      }
    }
    if (!s.coordinates.empty()) {
      detail::throw_error_at(s.coordinates.front().where,
                             "a scene of free bodies has no [[coordinates]]; their state is the "
                             "pose and twist given in each body");
    }
    if (s.lagrangian) {
      detail::throw_error_at(s.lagrangian->where,
                             "a lagrangian is a function of [[coordinates]]; a scene of free bodies "
                             "has none (their state is the pose and twist given in each body)");
    }
  } else if (s.coordinates.empty()) {
    p.fail(root.source(), "the scene has no [[coordinates]] and no free bodies; expected at least "
                          "one coordinate (name, initial, velocity) or a body with free = true");
  }
}

// Every parent is a body posed by coordinates and declared before the body that names it.
void check_parents(const Scene& s) {
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    const Body& b = s.bodies[i];
    if (b.parent.empty()) continue;
    const auto it = std::find_if(s.bodies.begin(), s.bodies.end(),
                                 [&](const Body& o) { return o.name == b.parent; });
    if (it == s.bodies.end()) {
      std::vector<std::string> bodies;
      for (std::size_t k = 0; k < i; ++k) bodies.push_back(s.bodies[k].name);
      std::string msg =
          fmt::format("body '{}': parent '{}' is no body of the scene", b.name, b.parent);
      if (auto g = did_you_mean(b.parent, bodies)) msg += fmt::format("; did you mean '{}'?", *g);
      msg += bodies.empty() ? std::string("; it is the first body, so it hangs from the world: "
                                          "leave out 'parent'")
                            : fmt::format(" (bodies declared before it: {})", fmt::join(bodies, ", "));
      detail::throw_error_at(b.parent_where, msg);
    }
    const auto k = static_cast<std::size_t>(it - s.bodies.begin());
    if (k == i) {
      detail::throw_error_at(b.parent_where, fmt::format("body '{}' names itself as its parent; "
                                                         "expected a body declared before it",
                                                         b.name));
    }
    if (k > i) {
      detail::throw_error_at(b.parent_where,
                             fmt::format("body '{}': parent '{}' is declared after it (line {}); "
                                         "declare a parent before the bodies that hang from it",
                                         b.name, b.parent, it->where.line));
    }
    if (it->free) {
      detail::throw_error_at(b.parent_where,
                             fmt::format("body '{}': parent '{}' is a free body; a body hangs only "
                                         "from a body posed by [[coordinates]]",
                                         b.name, b.parent));
    }
  }
}

// Every force names a coordinate (a ball coordinate's, one of its velocity's entries:
// <ball>_wx, _wy, _wz) and every spring's and rope's bodies exist.
void check_references(const Scene& s) {
  std::vector<std::string> targets;
  for (const Coordinate& c : s.coordinates) {
    if (c.kind == Coordinate::Kind::kBall) {
      for (const char* axis : {"_wx", "_wy", "_wz"}) targets.push_back(c.name + axis);
    } else {
      targets.push_back(c.name);
    }
  }
  for (const NamedExpression& f : s.forces) {
    if (std::find(targets.begin(), targets.end(), f.name) != targets.end()) continue;
    std::string msg = fmt::format("force on unknown coordinate '{}'", f.name);
    const bool balls = std::any_of(s.coordinates.begin(), s.coordinates.end(), [](const Coordinate& c) {
      return c.kind == Coordinate::Kind::kBall;
    });
    if (balls) msg += " (a force on a ball coordinate names an entry of its angular velocity: <ball>_wx, _wy or _wz)";
    if (auto g = did_you_mean(f.name, targets)) msg += fmt::format("; did you mean '{}'?", *g);
    detail::throw_error_at(f.expression.where, msg);
  }
  auto check_ends = [&](const auto& ends, std::string_view what) {
    for (const std::string* name : {&ends.body_a, &ends.body_b}) {
      if (name->empty()) continue;
      const bool known = std::any_of(s.bodies.begin(), s.bodies.end(),
                                     [&](const Body& b) { return b.name == *name; });
      if (!known) {
        std::vector<std::string> bodies;
        for (const auto& b : s.bodies) bodies.push_back(b.name);
        std::string msg = fmt::format("{} attached to unknown body '{}'", what, *name);
        if (auto g = did_you_mean(*name, bodies)) msg += fmt::format("; did you mean '{}'?", *g);
        detail::throw_error_at(ends.where, msg);
      }
    }
  };
  for (const Spring& sp : s.springs) check_ends(sp, "spring");
  for (const Rope& r : s.ropes) check_ends(r, fmt::format("rope of constraint '{}'", r.constraint));
}

// The text of `file`, a regular file of at most kMaxSceneFileBytes: `what` names it in messages
// ("scene file"), `holder` says what the cap is for ("a scene"), `expected` what the file should
// be ("a TOML file").
std::string read_input_file(const std::filesystem::path& file, std::string_view what,
                            std::string_view holder, std::string_view expected) {
  // only a regular file of at most kMaxSceneFileBytes is read: a device (/dev/zero), a FIFO or
  // a directory would otherwise be read without end, or fail with the system's words
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(file, ec);
  if (ec || !std::filesystem::exists(st)) {
    throw Error(fmt::format("cannot open {} '{}': {}", what, file.string(),
                            ec ? ec.message() : "no such file"));
  }
  if (std::filesystem::is_directory(st)) {
    throw Error(fmt::format("{} '{}' is a directory; expected {}", what, file.string(), expected));
  }
  if (!std::filesystem::is_regular_file(st)) {
    throw Error(fmt::format("{} '{}' is not a regular file (a device, a pipe or a socket); "
                            "expected {}",
                            what, file.string(), expected));
  }
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (!ec && size > kMaxSceneFileBytes) {
    throw Error(fmt::format("{} '{}' has {} bytes, more than the {} (16 MiB) {} may have", what,
                            file.string(), size, kMaxSceneFileBytes, holder));
  }
  std::ifstream in(file, std::ios::binary);
  if (!in.good()) {
    throw Error(fmt::format("cannot open {} '{}': {}", what, file.string(), std::strerror(errno)));
  }
  // read in chunks up to one byte past the cap (the file may have grown since it was measured)
  std::string text;
  char chunk[65536];
  while (text.size() <= kMaxSceneFileBytes && in.read(chunk, sizeof chunk).gcount() > 0) {
    text.append(chunk, static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) {
    throw Error(fmt::format("cannot read {} '{}': {}", what, file.string(), std::strerror(errno)));
  }
  if (text.size() > kMaxSceneFileBytes) {
    throw Error(fmt::format("{} '{}' has more than the {} bytes (16 MiB) {} may have", what,
                            file.string(), kMaxSceneFileBytes, holder));
  }
  return text;
}

// The settings a model option was given, for messages: `pin_free_root = true`, density 500 kg/m³.
std::string model_options_text(const ModelOptions& o) {
  std::vector<std::string> given;
  auto flag = [&](const char* key, const std::optional<bool>& v) {
    if (v) given.push_back(*v ? setting(key) : fmt::format("{} = false", key));
  };
  flag("pin_free_root", o.pin_free_root);
  flag("inertia_from_geometry", o.inertia_from_geometry);
  flag("symbolic_inertia", o.symbolic_inertia);
  if (o.density) given.push_back(fmt::format("density {} kg/m³", *o.density));
  return fmt::format("{}", fmt::join(given, ", "));
}

// [model]: the robot model file the scene is built on (relative to the scene file's directory)
// and how it is read; `options` override the section's settings. The scene starts as the model's
// (rigid/scene/robot_scene.hpp), and its coordinates are claimed for the scene's names.
void parse_model_section(const toml::node& node, const Parser& p, const ModelOptions& options,
                         NameClaims& names, Scene& s) {
  const toml::table& t = p.table(node, "[model]");
  p.check_keys(t, "[model]", kModelKeys);
  const toml::node& file_node = p.required(t, node.source(), "file", "[model]");
  const std::filesystem::path given = p.string(file_node, "[model] file");
  if (given.empty()) {
    p.fail(file_node, "[model] file is empty; expected the path of a URDF or MJCF file (relative "
                      "to the scene file's directory)");
  }
  ModelSection section;
  section.file = given.is_absolute() ? given : (p.file().parent_path() / given).lexically_normal();
  section.where = p.where(file_node.source());
  ModelOptions read;  // the section's settings, then the options over them
  if (auto n = t.get("pin_free_root")) read.pin_free_root = p.boolean(*n, "[model] pin_free_root");
  if (auto n = t.get("inertia_from_geometry")) {
    read.inertia_from_geometry = p.boolean(*n, "[model] inertia_from_geometry");
  }
  if (auto n = t.get("symbolic_inertia")) {
    read.symbolic_inertia = p.boolean(*n, "[model] symbolic_inertia");
  }
  const toml::node* density = t.get("density");
  if (density != nullptr) {
    const double rho = p.number(*density, "[model] density (kg/m³)");
    if (!(rho > 0)) {
      p.fail(*density, fmt::format("[model] density is {} kg/m³; expected a number > 0 (kg/m³)", rho));
    }
    read.density = rho;
  }
  if (options.pin_free_root) read.pin_free_root = options.pin_free_root;
  if (options.inertia_from_geometry) read.inertia_from_geometry = options.inertia_from_geometry;
  if (options.density) read.density = options.density;
  if (options.symbolic_inertia) read.symbolic_inertia = options.symbolic_inertia;
  if (density != nullptr && !options.density && !read.inertia_from_geometry.value_or(false)) {
    p.fail(*density, "[model] density is the density of the links' collision geometry when their "
                     "inertials are computed from it: set inertia_from_geometry = true with it "
                     "(without it, the links keep the inertials the file states)");
  }
  // the file itself: its reading errors at the `file` value, its content's at its own lines
  std::string text;
  try {
    text = read_input_file(section.file, "model file", "a model file", "a URDF or MJCF file");
  } catch (const Error& e) {
    p.fail(file_node, fmt::format("[model] file: {}", e.what()));
  }
  if (!looks_like_xml(text)) {
    p.fail(file_node, fmt::format("[model] file '{}' is not XML (its first character is not '<'); "
                                  "expected a URDF or MJCF file",
                                  section.file.string()));
  }
  Scene m = scene_from_robot_file(text, section.file, read, p.file());
  const io::RobotReadOptions ro = robot_read_options(read, section.file);
  section.pin_free_root = ro.pin_free_root;
  section.inertia_from_geometry = ro.inertia_from_geometry;
  section.density = ro.density;
  section.symbolic_inertia = read.symbolic_inertia.value_or(false);
  m.model = std::move(section);
  for (const Coordinate& c : m.coordinates) {
    names.reserve(c.name, fmt::format("a joint coordinate of the model, {}", to_string(c.where)));
  }
  for (const Parameter& q : m.parameters) {
    names.reserve(q.name, fmt::format("an inertial parameter of the model (symbolic_inertia), {}",
                                      to_string(q.value.where)));
  }
  s = std::move(m);
}

Scene parse_document(const toml::table& root, const Parser& p, const ModelOptions& options) {
  Scene s;
  s.file = p.file();
  p.check_keys(root, "the scene", kTopKeys);
  NameClaims names(p);  // every name an expression may use, for clashes

  if (const toml::node* model = root.get("model")) {
    parse_model_section(*model, p, options, names, s);
  } else if (!options.empty()) {
    const std::string given = model_options_text(options);
    throw Error(fmt::format("{}: {} {} to a robot model file (URDF, MJCF) given as the scene or "
                            "named by a [model] section; this TOML scene has no [model]",
                            p.file().string(), given,
                            given.find(", ") == std::string::npos ? "applies" : "apply"));
  }
  parse_parameters(root, p, names, s);
  parse_coordinates(root, p, names, s);
  parse_bodies(root, p, names, s);
  parse_named_expressions(root, p, "constraints", "name", s.constraints, &s.ropes);
  parse_named_expressions(root, p, "potentials", "name", s.potentials);
  parse_named_expressions(root, p, "forces", "coordinate", s.forces);
  parse_velocity_constraints(root, p, s);
  parse_springs(root, p, s);
  parse_lagrangian_and_gravity(root, p, s);
  parse_simulation(root, p, s);
  parse_output(root, p, s);

  // cross-references
  check_parents(s);
  check_scene_kind(root, p, s);
  check_references(s);
  return s;
}

}  // namespace

Expression Expression::of(double value, SourceLocation where) {
  return Expression{fmt::format("{}", value), std::move(where), value, false};
}

SourceLocation Expression::at(std::size_t offset) const {
  SourceLocation loc = where;
  if (loc.column > 0) loc.column += static_cast<int>(offset) + (quoted ? 1 : 0);
  return loc;
}

bool Scene::is_free_body_scene() const {
  return !bodies.empty() && bodies.front().free;
}

namespace {

// The column (from 1) where `literal` starts on the line of `r`, at or before r's column; 0 when
// it is not found there.
int literal_start(std::string_view text, const toml::source_region& r, std::string_view literal) {
  std::size_t offset = 0;
  for (std::size_t line = 1; line < r.begin.line && offset != std::string_view::npos; ++line) {
    offset = text.find('\n', offset);
    if (offset != std::string_view::npos) ++offset;
  }
  if (offset == std::string_view::npos || literal.empty()) return 0;
  const std::string_view line = text.substr(offset, text.find('\n', offset) - offset);
  const std::size_t at = line.rfind(literal, r.begin.column > 0 ? r.begin.column - 1 : 0);
  return at == std::string_view::npos ? 0 : static_cast<int>(at) + 1;
}

// The first number literal in `text` (a --set value) that no double holds, as
// literal_range_problem says it.
std::optional<std::string> first_literal_problem(std::string_view text) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    const bool starts = std::isdigit(static_cast<unsigned char>(text[i])) != 0 &&
                        (i == 0 || !(std::isalnum(static_cast<unsigned char>(text[i - 1])) != 0 ||
                                     text[i - 1] == '_' || text[i - 1] == '.'));
    if (!starts) continue;
    const std::string_view literal = leading_literal(text.substr(i));
    if (auto problem = literal_range_problem(literal)) return problem;
    i += literal.empty() ? 0 : literal.size() - 1;
  }
  return std::nullopt;
}

}  // namespace

Scene parse_scene(std::string_view toml_text, const std::filesystem::path& file,
                  const ModelOptions& model) {
  Parser p(file, toml_text);
  toml::table root;
  try {
    root = toml::parse(toml_text, file.string());
  } catch (const toml::parse_error& e) {
    // toml++ says "Error while parsing key-value pair: cannot redefine …": the reason, with the
    // construct it was reading as context
    std::string_view text = e.description();
    std::string context;
    constexpr std::string_view kLead = "Error while parsing ";
    if (text.starts_with(kLead)) {
      const auto colon = text.find(": ");
      if (colon != std::string_view::npos) {
        context = fmt::format(" in a {}", text.substr(kLead.size(), colon - kLead.size()));
        text.remove_prefix(colon + 2);
      }
    }
    // toml++ refuses a float that overflows ("'1e400' could not be interpreted as a value") at
    // its end: said as the literal's range, at the literal's start
    if (context == " in a floating-point" && text.starts_with("'")) {
      const std::string_view literal = text.substr(1, text.find('\'', 1) - 1);
      if (auto problem = literal_range_problem(literal)) {
        SourceLocation at = p.where(e.source());
        const auto start = literal_start(toml_text, e.source(), literal);
        if (start > 0) at.column = start;
        detail::throw_error_at(at, *problem);
      }
    }
    detail::throw_error_at(p.where(e.source()), fmt::format("TOML syntax error{}: {}", context, text));
  }
  return parse_document(root, p, model);
}

Scene load_scene(const std::filesystem::path& file, const ModelOptions& model) {
  const std::string text = read_input_file(file, "scene file", "a scene", "a TOML file");
  // a robot model file (URDF, MJCF) is a scene of its joints (rigid/scene/robot_scene.hpp)
  if (looks_like_xml(text)) return scene_from_robot_file(text, file, model, file);
  return parse_scene(text, file, model);
}

namespace {

// The [simulation] keys an override may set.
const Keys kSimulationOverrides = {"t_end", "dt", "tolerance", "output_dt", "integrator"};
// A free body's initial state: the file's key and its short alias (the same setting).
const std::array<std::pair<const char*, const char*>, 4> kFreeBodyOverrides = {{
    {"initial_position", "position"},
    {"initial_velocity", "velocity"},
    {"angular_velocity", "omega"},
    {"initial_quaternion", "quaternion"},
}};

std::string trimmed(std::string_view s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t");
  return std::string(s.substr(b, e - b + 1));
}

// A scalar value as the file would hold it: a number, or an expression of the parameters.
Expression override_expression(const std::string& value, const std::string& assignment) {
  Expression e{value, {fmt::format("override '{}'", assignment), 0, 0}, std::nullopt, false};
  if (auto problem = literal_range_problem(value)) {
    throw Error(fmt::format("override '{}': {}", assignment, *problem));
  }
  double v = 0;
  const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
  if (ec == std::errc() && end == value.data() + value.size() && std::isfinite(v)) e.number = v;
  return e;
}

// A vector value "[a, b, c]" of `size` finite numbers, read as a TOML array.
template <std::size_t N>
std::array<double, N> override_vector(const std::string& value, const std::string& assignment,
                                      const std::string& what) {
  auto refuse = [&](const std::string& why) -> std::array<double, N> {
    throw Error(fmt::format("override '{}': {} {}; expected {} numbers such as [{}]", assignment, what, why, N,
                            N == 3 ? "0, 1, 0" : "1, 0, 0, 0"));
  };
  toml::table t;
  try {
    t = toml::parse("v = " + value);
  } catch (const toml::parse_error&) {
    // toml++ refuses 1e400 outright: said as the literal's range
    if (auto problem = first_literal_problem(value)) return refuse(*problem);
    return refuse(fmt::format("'{}' is not an array", value));
  }
  const toml::array* a = t.get("v") != nullptr ? t.get("v")->as_array() : nullptr;
  if (a == nullptr) return refuse(fmt::format("'{}' is not an array", value));
  if (a->size() != N) return refuse(fmt::format("has {} elements", a->size()));
  std::array<double, N> out{};
  for (std::size_t i = 0; i < N; ++i) {
    const toml::node* e = a->get(i);
    // the element as written ("v = " is 4 columns before the value): 1e-400 would be read as 0
    if (e != nullptr && e->source().begin.line == 1 && e->source().begin.column > 4) {
      const std::string_view written =
          leading_literal(std::string_view(value).substr(e->source().begin.column - 5));
      if (auto problem = literal_range_problem(written)) {
        return refuse(fmt::format("element {} {}", i + 1, *problem));
      }
    }
    // an integer or a float (toml++ converts an integer that a double holds exactly)
    const std::optional<double> v = e != nullptr && e->is_number() ? e->value<double>() : std::nullopt;
    if (!v || !std::isfinite(*v)) return refuse(fmt::format("element {} is not a finite number", i + 1));
    out[i] = *v;
  }
  return out;
}

// A quaternion value "[w, x, y, z]" of unit norm (within 1e-9), for the setting `what`.
std::array<double, 4> override_unit_quaternion(const std::string& value, const std::string& assignment,
                                               const std::string& what) {
  const auto q = override_vector<4>(value, assignment, what + " (w, x, y, z)");
  const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (std::abs(norm - 1.0) > 1e-9) {
    throw Error(fmt::format("override '{}': {} has norm {}; expected a unit quaternion (|q| within "
                            "1e-9 of 1)",
                            assignment, what, norm));
  }
  return q;
}

const Coordinate* find_coordinate(const Scene& s, std::string_view name) {
  for (const Coordinate& c : s.coordinates) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

Body* find_free_body(Scene& s, std::string_view name) {
  for (Body& b : s.bodies) {
    if (b.free && b.name == name) return &b;
  }
  return nullptr;
}

std::string free_body_names_text(const std::string& body) {
  std::vector<std::string> names;
  for (const auto& [key, alias] : kFreeBodyOverrides) names.push_back(fmt::format("'{}.{}'", body, alias));
  return fmt::format("{}", fmt::join(names, ", "));
}

}  // namespace

std::vector<std::string> override_names(const Scene& scene) {
  std::vector<std::string> names;
  for (const Parameter& p : scene.parameters) names.push_back(p.name);
  for (const std::string& k : kSimulationOverrides) names.push_back("simulation." + k);
  for (const Coordinate& c : scene.coordinates) {
    if (c.kind == Coordinate::Kind::kBall) {
      names.push_back(c.name + ".orientation");
      names.push_back(c.name + ".angular_velocity");
      continue;
    }
    names.push_back(c.name + ".initial");
    names.push_back(c.name + ".velocity");
  }
  for (const Body& b : scene.bodies) {
    if (!b.free) continue;
    for (const auto& [key, alias] : kFreeBodyOverrides) {
      names.push_back(b.name + "." + key);
      names.push_back(b.name + "." + alias);
    }
  }
  return names;
}

void apply_overrides(Scene& scene, const std::vector<std::string>& assignments) {
  for (const std::string& a : assignments) {
    const auto eq = a.find('=');
    const std::string name = eq == std::string::npos ? std::string() : trimmed(std::string_view(a).substr(0, eq));
    const std::string value = eq == std::string::npos ? std::string() : trimmed(std::string_view(a).substr(eq + 1));
    if (name.empty() || value.empty()) {
      throw Error(fmt::format("override '{}' is not of the form name=value (e.g. theta.initial=0.2, "
                              "simulation.t_end=20)",
                              escaped(a)));
    }
    // names are identifiers, dotted (a control character in a --set or sweep axis name was
    // echoed to the terminal, a newline split runs.csv's header): refused before any lookup
    const bool dotted_identifier = [&] {
      std::size_t start = 0;
      while (true) {
        const std::size_t dot = std::min(name.find('.', start), name.size());
        const std::string_view part = std::string_view(name).substr(start, dot - start);
        if (part.empty() || !(std::isalpha(static_cast<unsigned char>(part[0])) || part[0] == '_') ||
            !std::all_of(part.begin(), part.end(),
                         [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; })) {
          return false;
        }
        if (dot == name.size()) return true;
        start = dot + 1;
      }
    }();
    if (!dotted_identifier) {
      throw Error(fmt::format("override '{}': '{}' is not a valid name; expected a parameter, "
                              "simulation.<key> or <coordinate or body>.<key>, of letters, digits, '_' "
                              "and '.'",
                              escaped(a), escaped(name)));
    }
    // a parameter by its plain name
    auto param = std::find_if(scene.parameters.begin(), scene.parameters.end(),
                              [&](const Parameter& p) { return p.name == name; });
    if (param != scene.parameters.end()) {
      param->value = override_expression(value, a);
      continue;
    }
    const auto dot = name.find('.');
    const std::string owner = name.substr(0, dot);
    const std::string key = dot == std::string::npos ? std::string() : name.substr(dot + 1);
    if (dot != std::string::npos && owner == "simulation" &&
        std::find(kSimulationOverrides.begin(), kSimulationOverrides.end(), key) != kSimulationOverrides.end()) {
      Simulation& sim = scene.simulation;
      if (key == "integrator") {
        std::string v = value;
        if (v.size() >= 2 && (v.front() == '"' || v.front() == '\'') && v.back() == v.front()) v = v.substr(1, v.size() - 2);
        sim.integrator = v;
      } else if (key == "t_end") {
        sim.t_end = override_expression(value, a);
      } else if (key == "dt") {
        sim.dt = override_expression(value, a);
      } else if (key == "tolerance") {
        sim.tolerance = override_expression(value, a);
      } else {
        sim.output_dt = override_expression(value, a);
      }
      continue;
    }
    const auto coordinate = dot == std::string::npos
                                ? scene.coordinates.end()
                                : std::find_if(scene.coordinates.begin(), scene.coordinates.end(),
                                               [&](const Coordinate& c) { return c.name == owner; });
    const bool ball = coordinate != scene.coordinates.end() && coordinate->kind == Coordinate::Kind::kBall;
    if (!ball && coordinate != scene.coordinates.end() && (key == "initial" || key == "velocity")) {
      (key == "initial" ? coordinate->initial : coordinate->velocity) = override_expression(value, a);
      continue;
    }
    if (ball && (key == "orientation" || key == "angular_velocity")) {
      // a ball coordinate's state (a robot's ball or free joint): numbers, as a free body's
      auto expressions = [&](const auto& numbers) {
        std::array<Expression, std::tuple_size_v<std::decay_t<decltype(numbers)>>> out;
        for (std::size_t k = 0; k < out.size(); ++k) {
          out[k] = Expression::of(numbers[k], {fmt::format("override '{}'", a), 0, 0});
        }
        return out;
      };
      if (key == "angular_velocity") {
        coordinate->angular_velocity = expressions(override_vector<3>(value, a, owner + ".angular_velocity"));
        continue;
      }
      coordinate->orientation = expressions(override_unit_quaternion(value, a, owner + ".orientation"));
      continue;
    }
    if (Body* b = dot != std::string::npos ? find_free_body(scene, owner) : nullptr) {
      const auto setting = std::find_if(kFreeBodyOverrides.begin(), kFreeBodyOverrides.end(),
                                        [&](const auto& ka) { return key == ka.first || key == ka.second; });
      if (setting != kFreeBodyOverrides.end()) {
        const std::string what = fmt::format("{}.{}", owner, setting->first);
        if (setting == kFreeBodyOverrides.begin()) {
          b->initial_position = override_vector<3>(value, a, what);
        } else if (setting == kFreeBodyOverrides.begin() + 1) {
          b->initial_velocity = override_vector<3>(value, a, what);
        } else if (setting == kFreeBodyOverrides.begin() + 2) {
          b->angular_velocity = override_vector<3>(value, a, what);
        } else {
          b->initial_orientation = override_unit_quaternion(value, a, what);
        }
        continue;
      }
    }
    // unknown: say what the name is if it names something that is set through its keys
    const std::vector<std::string> names = override_names(scene);
    std::string why;
    const Coordinate* named = find_coordinate(scene, name);
    if (ball || (named != nullptr && named->kind == Coordinate::Kind::kBall)) {
      why = fmt::format("'{}' is a ball coordinate: set '{}.orientation' or '{}.angular_velocity'", owner, owner, owner);
    } else if (named != nullptr) {
      why = fmt::format("'{}' is a coordinate: set '{}.initial' or '{}.velocity'", name, name, name);
    } else if (find_free_body(scene, name) != nullptr) {
      why = fmt::format("'{}' is a free body: set {}", name, free_body_names_text(name));
    } else if (name == "simulation") {
      why = fmt::format("set one of its keys: simulation.{}", fmt::join(kSimulationOverrides, ", simulation."));
    } else {
      const bool is_body = std::any_of(scene.bodies.begin(), scene.bodies.end(), [&](const Body& b) { return b.name == owner; });
      why = fmt::format("the scene has no parameter, setting or initial condition '{}'{}", name,
                        did_you_mean_hint(name, names));
      if (is_body && find_free_body(scene, owner) == nullptr) {
        why += fmt::format(" (body '{}' is posed by the coordinates: set their initial values)", owner);
      }
    }
    throw Error(fmt::format("override '{}': {} (names: {})", a, why, fmt::join(names, ", ")));
  }
}

}  // namespace rigid::scene
