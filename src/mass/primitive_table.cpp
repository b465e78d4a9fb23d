#include "rigid/mass/primitive_table.hpp"

#include <algorithm>
#include <cctype>
#include <map>

#include <fmt/format.h>

#include "rigid/common/did_you_mean.hpp"
#include "rigid/common/error.hpp"
#include "rigid/mass/primitives.hpp"

namespace rigid::mass {
namespace {

// '-' and '_' are the same character in every name of the catalogue
std::string normalized(std::string_view name) {
  std::string s(name);
  std::replace(s.begin(), s.end(), '-', '_');
  return s;
}

// One row per primitive: its _with_mass and _with_density factories applied to the sizes
// in the order of the row's size names.
template <auto WithMass, auto WithDensity, std::size_t N>
MassProperties make_n(Amount amount, double value, std::span<const double> z,
                      std::span<const Eigen::Vector3d> /*points*/) {
  RIGID_ASSERT(z.size() == N);
  auto call = [&](auto f) {
    if constexpr (N == 1) return f(value, z[0]);
    else if constexpr (N == 2) return f(value, z[0], z[1]);
    else return f(value, z[0], z[1], z[2]);
  };
  return amount == Amount::kMass ? call(WithMass) : call(WithDensity);
}

MassProperties make_tetrahedron(Amount amount, double value, std::span<const double> /*sizes*/,
                                std::span<const Eigen::Vector3d> v) {
  RIGID_ASSERT(v.size() == 4);
  return amount == Amount::kMass ? solid_tetrahedron_with_mass(value, v[0], v[1], v[2], v[3])
                                 : solid_tetrahedron_with_density(value, v[0], v[1], v[2], v[3]);
}

PrimitiveSize size(std::string name, std::string help, std::vector<std::string> aliases = {}) {
  return PrimitiveSize{std::move(name), std::move(help), std::move(aliases), "m"};
}

// the diagonal inertia (xx, yy, zz) of a formula set, products of inertia 0
std::array<std::string, 6> diagonal(std::string xx, std::string yy, std::string zz) {
  return {std::move(xx), std::move(yy), std::move(zz), "0", "0", "0"};
}

}  // namespace

bool PrimitiveEntry::is_called(std::string_view n) const {
  const std::string key = normalized(n);
  if (key == name) return true;
  return std::any_of(aliases.begin(), aliases.end(), [&](const std::string& a) { return a == key; });
}

std::vector<std::string> PrimitiveEntry::names() const {
  std::vector<std::string> out{name};
  out.insert(out.end(), aliases.begin(), aliases.end());
  return out;
}

std::optional<std::size_t> PrimitiveEntry::size_index(std::string_view n) const {
  const std::string key = normalized(n);
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    if (sizes[i].name == key ||
        std::find(sizes[i].aliases.begin(), sizes[i].aliases.end(), key) != sizes[i].aliases.end()) {
      return i;
    }
  }
  return std::nullopt;
}

std::optional<std::size_t> PrimitiveEntry::point_index(std::string_view n) const {
  const std::string key = normalized(n);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i].name == key) return i;
  }
  return std::nullopt;
}

// The closed forms are the textbook ones [Goldstein2002, §5.3; Hibbeler, inside back cover]
// written as expressions; tests/lagrange/primitive_formulas_test.cpp evaluates every one of
// them against the C++ factories of primitives.cpp, which are derived independently.
const std::vector<PrimitiveEntry>& primitive_table() {
  static const std::vector<PrimitiveEntry> table = [] {
    const std::string V = "kg/m³", A = "kg/m²";
    std::vector<PrimitiveEntry> t;
    t.push_back({"solid_sphere", {"sphere"}, "solid sphere, centred", {size("radius", "radius")}, {}, V,
                 {"rho*4/3*pi*radius^3", {"0", "0", "0"},
                  diagonal("2/5*m*radius^2", "2/5*m*radius^2", "2/5*m*radius^2")},
                 &make_n<&solid_sphere_with_mass, &solid_sphere_with_density, 1>});
    t.push_back({"thick_spherical_shell", {"spherical_shell"}, "solid shell between two spheres, centred",
                 {size("inner_radius", "inner radius"), size("outer_radius", "outer radius")}, {}, V,
                 {"rho*4/3*pi*(outer_radius^3 - inner_radius^3)", {"0", "0", "0"},
                  diagonal("2/5*m*(outer_radius^5 - inner_radius^5)/(outer_radius^3 - inner_radius^3)",
                           "2/5*m*(outer_radius^5 - inner_radius^5)/(outer_radius^3 - inner_radius^3)",
                           "2/5*m*(outer_radius^5 - inner_radius^5)/(outer_radius^3 - inner_radius^3)")},
                 &make_n<&thick_spherical_shell_with_mass, &thick_spherical_shell_with_density, 2>});
    t.push_back({"thin_spherical_shell", {"hollow_sphere"}, "spherical surface, centred (density in kg/m²)",
                 {size("radius", "radius")}, {}, A,
                 {"rho*4*pi*radius^2", {"0", "0", "0"},
                  diagonal("2/3*m*radius^2", "2/3*m*radius^2", "2/3*m*radius^2")},
                 &make_n<&thin_spherical_shell_with_mass, &thin_spherical_shell_with_density, 1>});
    t.push_back({"solid_ellipsoid", {"ellipsoid"}, "solid ellipsoid, semi-axes along x, y, z, centred",
                 {size("semi_x", "semi-axis along x", {"semi_axes_0"}),
                  size("semi_y", "semi-axis along y", {"semi_axes_1"}),
                  size("semi_z", "semi-axis along z", {"semi_axes_2"})},
                 {}, V,
                 {"rho*4/3*pi*semi_x*semi_y*semi_z", {"0", "0", "0"},
                  diagonal("m*(semi_y^2 + semi_z^2)/5", "m*(semi_x^2 + semi_z^2)/5", "m*(semi_x^2 + semi_y^2)/5")},
                 &make_n<&solid_ellipsoid_with_mass, &solid_ellipsoid_with_density, 3>});
    t.push_back({"solid_box", {"box", "cuboid"}, "solid box, edges along x, y, z, centred",
                 {size("lx", "edge along x", {"size_0"}), size("ly", "edge along y", {"size_1"}),
                  size("lz", "edge along z", {"size_2"})},
                 {}, V,
                 {"rho*lx*ly*lz", {"0", "0", "0"},
                  diagonal("m*(ly^2 + lz^2)/12", "m*(lx^2 + lz^2)/12", "m*(lx^2 + ly^2)/12")},
                 &make_n<&solid_box_with_mass, &solid_box_with_density, 3>});
    t.push_back({"solid_cylinder", {"cylinder"}, "solid cylinder, axis z, centred",
                 {size("radius", "radius"), size("height", "height", {"length"})}, {}, V,
                 {"rho*pi*radius^2*height", {"0", "0", "0"},
                  diagonal("m*(3*radius^2 + height^2)/12", "m*(3*radius^2 + height^2)/12", "m*radius^2/2")},
                 &make_n<&solid_cylinder_with_mass, &solid_cylinder_with_density, 2>});
    t.push_back({"thick_tube", {"tube", "thick_walled_tube"}, "thick-walled tube, axis z, centred",
                 {size("inner_radius", "inner radius"), size("outer_radius", "outer radius"),
                  size("height", "height", {"length"})},
                 {}, V,
                 {"rho*pi*(outer_radius^2 - inner_radius^2)*height", {"0", "0", "0"},
                  diagonal("m*(3*(inner_radius^2 + outer_radius^2) + height^2)/12",
                           "m*(3*(inner_radius^2 + outer_radius^2) + height^2)/12",
                           "m*(inner_radius^2 + outer_radius^2)/2")},
                 &make_n<&thick_tube_with_mass, &thick_tube_with_density, 3>});
    t.push_back({"thin_cylindrical_shell", {"cylindrical_shell"},
                 "thin open cylindrical surface, axis z, centred (density in kg/m²)",
                 {size("radius", "radius"), size("height", "height", {"length"})}, {}, A,
                 {"rho*2*pi*radius*height", {"0", "0", "0"},
                  diagonal("m*(radius^2/2 + height^2/12)", "m*(radius^2/2 + height^2/12)", "m*radius^2")},
                 &make_n<&thin_cylindrical_shell_with_mass, &thin_cylindrical_shell_with_density, 2>});
    // lateral surface (area 2πrh, a share h/(h + r) of the mass) and two end disks (2πr²)
    t.push_back({"capped_cylindrical_shell", {"closed_cylindrical_shell"},
                 "thin cylindrical surface with end disks, axis z, centred (density in kg/m²)",
                 {size("radius", "radius"), size("height", "height", {"length"})}, {}, A,
                 {"rho*2*pi*radius*(height + radius)", {"0", "0", "0"},
                  diagonal("m*(height*(radius^2/2 + height^2/12) + radius*(radius^2/4 + height^2/4))/(height + radius)",
                           "m*(height*(radius^2/2 + height^2/12) + radius*(radius^2/4 + height^2/4))/(height + radius)",
                           "m*radius^2*(height + radius/2)/(height + radius)")},
                 &make_n<&capped_cylindrical_shell_with_mass, &capped_cylindrical_shell_with_density, 2>});
    t.push_back({"solid_cone", {"cone"}, "solid cone, base at z = 0, apex at z = height",
                 {size("radius", "base radius"), size("height", "height")}, {}, V,
                 {"rho*pi*radius^2*height/3", {"0", "0", "height/4"},
                  diagonal("m*(3*radius^2/20 + 3*height^2/80)", "m*(3*radius^2/20 + 3*height^2/80)",
                           "3/10*m*radius^2")},
                 &make_n<&solid_cone_with_mass, &solid_cone_with_density, 2>});
    // with a = bottom, b = top radius: V = πh(a² + ab + b²)/3, z_c = h(a² + 2ab + 3b²)/(4(a² + ab + b²)),
    // I_zz = 3m(a⁴ + a³b + a²b² + ab³ + b⁴)/(10(a² + ab + b²)), I_xx about the base
    // 3m(a⁴ + … + b⁴)/(20(a² + ab + b²)) + m h²(a² + 3ab + 6b²)/(10(a² + ab + b²)), then shifted
    const std::string S2 = "(bottom_radius^2 + bottom_radius*top_radius + top_radius^2)";
    const std::string S4 =
        "(bottom_radius^4 + bottom_radius^3*top_radius + bottom_radius^2*top_radius^2 + "
        "bottom_radius*top_radius^3 + top_radius^4)";
    const std::string zc = "height*(bottom_radius^2 + 2*bottom_radius*top_radius + 3*top_radius^2)/(4*" + S2 + ")";
    const std::string Ixx = "m*(3*" + S4 + "/(20*" + S2 + ") + height^2*(bottom_radius^2 + 3*bottom_radius*top_radius + "
                            "6*top_radius^2)/(10*" + S2 + ")) - m*(" + zc + ")^2";
    t.push_back({"solid_frustum", {"frustum"}, "solid conical frustum, bottom at z = 0, top at z = height",
                 {size("bottom_radius", "radius at z = 0"), size("top_radius", "radius at z = height"),
                  size("height", "height")},
                 {}, V,
                 {"rho*pi*height*" + S2 + "/3", {"0", "0", zc}, diagonal(Ixx, Ixx, "3*m*" + S4 + "/(10*" + S2 + ")")},
                 &make_n<&solid_frustum_with_mass, &solid_frustum_with_density, 3>});
    // a cylinder of length l (share l/(l + 4r/3) of the mass) and two hemispheres
    t.push_back({"solid_capsule", {"capsule"}, "solid capsule, axis z, centred (total length = length + 2 radius)",
                 {size("radius", "radius"), size("length", "length of the cylindrical part")}, {}, V,
                 {"rho*pi*radius^2*(length + 4*radius/3)", {"0", "0", "0"},
                  diagonal("m*(length*(length^2/12 + radius^2/4) + 4*radius/3*(2*radius^2/5 + length^2/4 + "
                           "3*length*radius/8))/(length + 4*radius/3)",
                           "m*(length*(length^2/12 + radius^2/4) + 4*radius/3*(2*radius^2/5 + length^2/4 + "
                           "3*length*radius/8))/(length + 4*radius/3)",
                           "m*(length*radius^2/2 + 4*radius/3*2*radius^2/5)/(length + 4*radius/3)")},
                 &make_n<&solid_capsule_with_mass, &solid_capsule_with_density, 2>});
    t.push_back({"solid_torus", {"torus"}, "solid torus, axis z, centred",
                 {size("major_radius", "radius of the centre circle"), size("minor_radius", "radius of the tube")},
                 {}, V,
                 {"rho*2*pi^2*major_radius*minor_radius^2", {"0", "0", "0"},
                  diagonal("m*(major_radius^2/2 + 5*minor_radius^2/8)", "m*(major_radius^2/2 + 5*minor_radius^2/8)",
                           "m*(major_radius^2 + 3*minor_radius^2/4)")},
                 &make_n<&solid_torus_with_mass, &solid_torus_with_density, 2>});
    t.push_back({"thin_rod", {"rod"}, "thin rod along z, centred (density in kg/m)",
                 {size("length", "length")}, {}, "kg/m",
                 {"rho*length", {"0", "0", "0"}, diagonal("m*length^2/12", "m*length^2/12", "0")},
                 &make_n<&thin_rod_with_mass, &thin_rod_with_density, 1>});
    t.push_back({"thin_rectangular_plate", {"plate", "rectangular_plate"},
                 "thin rectangular plate in the xy-plane, edges lx along x and ly along y, centred (kg/m²)",
                 {size("lx", "edge along x", {"size_0"}), size("ly", "edge along y", {"size_1"})}, {}, A,
                 {"rho*lx*ly", {"0", "0", "0"}, diagonal("m*ly^2/12", "m*lx^2/12", "m*(lx^2 + ly^2)/12")},
                 &make_n<&thin_rectangular_plate_with_mass, &thin_rectangular_plate_with_density, 2>});
    t.push_back({"thin_disk", {"disk", "disc"}, "thin disk in the xy-plane, centred (kg/m²)",
                 {size("radius", "radius")}, {}, A,
                 {"rho*pi*radius^2", {"0", "0", "0"}, diagonal("m*radius^2/4", "m*radius^2/4", "m*radius^2/2")},
                 &make_n<&thin_disk_with_mass, &thin_disk_with_density, 1>});
    // a circle of matter (a wire hoop, a bicycle rim): the thin limit of the torus (minor radius
    // → 0) and the ring of the textbooks; "ring" alone, not "torus", since the torus is solid
    t.push_back({"thin_ring", {"hoop", "ring", "thin_hoop"},
                 "thin ring (hoop) of the given radius in the xy-plane, axis z, centred (density in kg/m)",
                 {size("radius", "radius of the circle")}, {}, "kg/m",
                 {"rho*2*pi*radius", {"0", "0", "0"}, diagonal("m*radius^2/2", "m*radius^2/2", "m*radius^2")},
                 &make_n<&thin_ring_with_mass, &thin_ring_with_density, 1>});
    t.push_back({"solid_tetrahedron", {"tetrahedron"},
                 "solid tetrahedron with the given vertices (coordinates kept)", {},
                 {{"v0", "vertex 0"}, {"v1", "vertex 1"}, {"v2", "vertex 2"}, {"v3", "vertex 3"}}, V,
                 {}, &make_tetrahedron});
    return t;
  }();
  return table;
}

const PrimitiveEntry& find_primitive(std::string_view name) {
  const auto& table = primitive_table();
  auto it = std::find_if(table.begin(), table.end(), [&](const PrimitiveEntry& e) { return e.is_called(name); });
  if (it != table.end()) return *it;
  std::vector<std::string> names;
  for (const auto& e : table) {
    for (const auto& n : e.names()) names.push_back(n);
  }
  std::vector<std::string> canonical;
  for (const auto& e : table) canonical.push_back(e.name);
  throw Error(fmt::format("unknown primitive '{}'{}; expected one of: {} (or an alias: see the "
                          "primitive catalogue)",
                          name, did_you_mean_hint(normalized(name), names), fmt::join(canonical, ", ")));
}

MassProperties make_primitive(std::string_view name, Amount amount, double value,
                              const PrimitiveArguments& arguments) {
  const PrimitiveEntry& e = find_primitive(name);
  std::vector<std::string> expected;
  for (const auto& s : e.sizes) expected.push_back(s.name);
  for (const auto& p : e.points) expected.push_back(p.name);
  const std::string takes = expected.empty() ? "no sizes" : fmt::format("{}", fmt::join(expected, ", "));
  std::vector<double> z(e.sizes.size());
  std::vector<bool> given(e.sizes.size(), false);
  for (const auto& [key, v] : arguments.sizes) {
    const auto i = e.size_index(key);
    if (!i) {
      throw Error(fmt::format("primitive '{}' has no size '{}'{}; it takes {} (m)", e.name, key,
                              did_you_mean_hint(normalized(key), expected), takes));
    }
    if (given[*i]) throw Error(fmt::format("primitive '{}': size '{}' is given twice", e.name, e.sizes[*i].name));
    z[*i] = v;
    given[*i] = true;
  }
  std::vector<Eigen::Vector3d> pts(e.points.size());
  std::vector<bool> have(e.points.size(), false);
  for (const auto& [key, p] : arguments.points) {
    const auto i = e.point_index(key);
    if (!i) {
      throw Error(fmt::format("primitive '{}' has no point '{}'{}; it takes {} (m)", e.name, key,
                              did_you_mean_hint(normalized(key), expected), takes));
    }
    if (have[*i]) throw Error(fmt::format("primitive '{}': point '{}' is given twice", e.name, e.points[*i].name));
    pts[*i] = p;
    have[*i] = true;
  }
  for (std::size_t i = 0; i < z.size(); ++i) {
    if (!given[i]) {
      throw Error(fmt::format("primitive '{}' is missing its size '{}' ({}, m); it takes {} (m)", e.name,
                              e.sizes[i].name, e.sizes[i].help, takes));
    }
  }
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (!have[i]) {
      throw Error(fmt::format("primitive '{}' is missing its point '{}' ({} as x, y, z in m); it takes {}",
                              e.name, e.points[i].name, e.points[i].help, takes));
    }
  }
  return e.make(amount, value, z, pts);
}

MassProperties make_primitive(std::string_view name, Amount amount, double value,
                              std::span<const std::pair<std::string, double>> sizes) {
  PrimitiveArguments args;
  for (const auto& [key, v] : sizes) args.sizes.emplace_back(std::string(key.data(), key.size()), v);
  return make_primitive(name, amount, value, args);
}

namespace {

bool is_name_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; }

// `text` with every whole identifier found in `values` replaced by "(value)"
std::string substitute(const std::string& text, const std::map<std::string, std::string>& values) {
  std::string out;
  std::size_t i = 0;
  while (i < text.size()) {
    if (std::isalpha(static_cast<unsigned char>(text[i])) != 0 || text[i] == '_') {
      std::size_t j = i;
      while (j < text.size() && is_name_char(text[j])) ++j;
      const std::string word = text.substr(i, j - i);
      auto it = values.find(word);
      out += it != values.end() ? "(" + it->second + ")" : word;
      i = j;
    } else {
      out += text[i++];
    }
  }
  return out;
}

}  // namespace

std::array<std::string, 10> primitive_expressions(const PrimitiveEntry& entry, Amount amount,
                                                  const std::string& amount_text,
                                                  std::span<const std::string> sizes) {
  RIGID_REQUIRE(!entry.formulas.mass.empty(), "primitive '{}' has no closed form in expressions",
                entry.name);
  RIGID_REQUIRE(sizes.size() == entry.sizes.size(), "primitive '{}' takes {} sizes, got {}", entry.name,
                entry.sizes.size(), sizes.size());
  std::map<std::string, std::string> values;
  for (std::size_t i = 0; i < sizes.size(); ++i) values[entry.sizes[i].name] = sizes[i];
  if (amount == Amount::kDensity) values["rho"] = amount_text;
  const std::string mass = amount == Amount::kMass ? amount_text : substitute(entry.formulas.mass, values);
  values["m"] = mass;
  std::array<std::string, 10> out;
  out[0] = mass;
  for (std::size_t k = 0; k < 3; ++k) out[1 + k] = substitute(entry.formulas.com[k], values);
  for (std::size_t k = 0; k < 6; ++k) out[4 + k] = substitute(entry.formulas.inertia[k], values);
  return out;
}

std::array<std::string, 10> point_mass_expressions(std::span<const PointMassText> points) {
  RIGID_REQUIRE(!points.empty(), "point masses: expected at least one point");
  auto paren = [](const std::string& text) { return "(" + text + ")"; };
  std::array<std::string, 10> out;
  std::string& total = out[0];
  std::array<std::string, 3> moment;
  for (const PointMassText& p : points) {
    total += (total.empty() ? "" : " + ") + paren(p.mass);
    for (std::size_t k = 0; k < 3; ++k) {
      moment[k] += (moment[k].empty() ? "" : " + ") + paren(p.mass) + "*" + paren(p.position[k]);
    }
  }
  for (std::size_t k = 0; k < 3; ++k) out[1 + k] = paren(moment[k]) + "/" + paren(total);
  // the elements xx yy zz xy xz yz: a diagonal one is the sum of the other two squares, an
  // off-diagonal one minus the product
  static constexpr std::size_t kRow[6] = {0, 1, 2, 0, 0, 1}, kCol[6] = {0, 1, 2, 1, 2, 2};
  for (std::size_t k = 0; k < 6; ++k) {
    std::string sum;
    for (const PointMassText& p : points) {
      std::array<std::string, 3> d;
      for (std::size_t a = 0; a < 3; ++a) {
        d[a] = paren(paren(p.position[a]) + " - " + paren(out[1 + a]));
      }
      const std::size_t r = kRow[k], c = kCol[k];
      const std::string term = r == c ? fmt::format("{}^2 + {}^2", d[(r + 1) % 3], d[(r + 2) % 3])
                                      : fmt::format("-{}*{}", d[r], d[c]);
      sum += (sum.empty() ? "" : " + ") + paren(p.mass) + "*" + paren(term);
    }
    out[4 + k] = sum;
  }
  return out;
}

}  // namespace rigid::mass
