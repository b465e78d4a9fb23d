#include "rigid/mass/uncertainty.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "rigid/common/did_you_mean.hpp"
#include "rigid/common/error.hpp"

namespace rigid::mass {
namespace {

struct Unit {
  const char* name;
  double factor;  // to SI
  char kind;      // 'l' length, 'm' mass, 'd' density, '%' relative
};

// units accepted after a tolerance's number
constexpr Unit kUnits[] = {
    {"%", 0.01, '%'},      {"m", 1.0, 'l'},       {"cm", 1e-2, 'l'},     {"mm", 1e-3, 'l'},
    {"um", 1e-6, 'l'},     {"µm", 1e-6, 'l'},     {"in", 0.0254, 'l'},   {"kg", 1.0, 'm'},
    {"g", 1e-3, 'm'},      {"kg/m3", 1.0, 'd'},   {"kg/m³", 1.0, 'd'},   {"kg/m^3", 1.0, 'd'},
    {"kg/m2", 1.0, 'd'},   {"kg/m²", 1.0, 'd'},   {"kg/m^2", 1.0, 'd'},  {"kg/m", 1.0, 'd'},
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
  while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
  return s;
}

}  // namespace

std::vector<Tolerance> parse_tolerances(std::string_view text) {
  std::vector<Tolerance> out;
  std::size_t start = 0;
  const std::string all(text);
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    const std::string_view item = trim(text.substr(start, end - start));
    const auto where = [&] { return fmt::format("tolerance '{}' (at character {} of '{}')", item, start + 1, all); };
    const std::size_t eq = item.find('=');
    RIGID_REQUIRE(eq != std::string_view::npos && eq > 0,
                  "{}: expected name=±value[unit], e.g. dims=±0.1mm, density=±2%, mass=±5g", where());
    Tolerance t;
    t.name = std::string(trim(item.substr(0, eq)));
    std::string_view rest = trim(item.substr(eq + 1));
    for (const std::string_view sign : {std::string_view("\xC2\xB1"), std::string_view("+/-"), std::string_view("+-")}) {
      if (rest.substr(0, sign.size()) == sign) {
        rest.remove_prefix(sign.size());
        break;
      }
    }
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(rest.data(), rest.data() + rest.size(), v);
    RIGID_REQUIRE(ec == std::errc() && std::isfinite(v) && v >= 0.0,
                  "{}: expected a non-negative finite number after '=', as in {}=±0.1mm or {}=±2%",
                  where(), t.name, t.name);
    t.unit = std::string(trim(std::string_view(ptr, static_cast<std::size_t>(rest.data() + rest.size() - ptr))));
    double factor = 1.0;
    if (!t.unit.empty()) {
      const Unit* u = nullptr;
      for (const Unit& k : kUnits) {
        if (t.unit == k.name) u = &k;
      }
      std::vector<std::string> names;
      for (const Unit& k : kUnits) names.emplace_back(k.name);
      RIGID_REQUIRE(u != nullptr, "{}: unknown unit '{}'{}; expected one of {}", where(), t.unit,
                    did_you_mean_hint(t.unit, names), fmt::join(names, ", "));
      factor = u->factor;
      t.relative = u->kind == '%';
    }
    t.sigma = v * factor;
    out.push_back(std::move(t));
    start = end + 1;
  }
  return out;
}

Propagated propagate(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f, const Eigen::VectorXd& x,
                     const Eigen::VectorXd& sigma, std::span<const std::string> input_names) {
  RIGID_REQUIRE(x.size() == sigma.size(), "{} inputs but {} standard deviations", x.size(), sigma.size());
  const auto name = [&](Eigen::Index i) {
    return static_cast<std::size_t>(i) < input_names.size() ? input_names[static_cast<std::size_t>(i)]
                                                            : fmt::format("input {}", i);
  };
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    RIGID_REQUIRE(std::isfinite(sigma(i)) && sigma(i) >= 0.0,
                  "the standard deviation of {} must be finite and non-negative, got {}", name(i), sigma(i));
  }
  Propagated p;
  p.value = f(x);
  p.jacobian = Eigen::MatrixXd::Zero(p.value.size(), x.size());
  // central differences: error h²|f'''|/6 + ε|f|/h, balanced at h ~ ε^(1/3) times the scale
  const double kStep = std::cbrt(std::numeric_limits<double>::epsilon());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (sigma(i) == 0.0) continue;
    const double h = kStep * std::max(std::abs(x(i)), sigma(i));
    Eigen::VectorXd xp = x, xm = x;
    xp(i) += h;
    xm(i) -= h;
    try {
      p.jacobian.col(i) = (f(xp) - f(xm)) / (xp(i) - xm(i));
    } catch (const Error& e) {
      RIGID_THROW("cannot propagate the uncertainty of {}: at {} ± {} the body is refused: {}", name(i),
                  x(i), h, e.what());
    }
  }
  p.sigma = (p.jacobian.array().square().rowwise() * sigma.array().square().transpose()).rowwise().sum().sqrt();
  return p;
}

Eigen::Matrix<double, 10, 1> mass_properties_vector(const MassProperties& mp,
                                                    const std::optional<Eigen::Vector3d>& about) {
  const Eigen::Matrix3d I = about ? mp.inertia_about(*about) : mp.inertia_com();
  Eigen::Matrix<double, 10, 1> y;
  y << mp.mass(), mp.com(), I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2);
  return y;
}

UncertainMassProperties primitive_uncertainty(std::string_view name, Amount amount, double value,
                                              const PrimitiveArguments& arguments, const Placement& placement,
                                              std::span<const Tolerance> tolerances,
                                              const std::optional<Eigen::Vector3d>& about) {
  const PrimitiveEntry& e = find_primitive(name);
  const MassProperties nominal = place(make_primitive(name, amount, value, arguments), placement);
  // inputs: the sizes in the catalogue's order, the points' coordinates, then the amount
  std::vector<double> sizes(e.sizes.size());
  for (const auto& [key, v] : arguments.sizes) sizes[*e.size_index(key)] = v;
  std::vector<Eigen::Vector3d> points(e.points.size());
  for (const auto& [key, p] : arguments.points) points[*e.point_index(key)] = p;
  const Eigen::Index n_sizes = static_cast<Eigen::Index>(sizes.size());
  const Eigen::Index n = n_sizes + 3 * static_cast<Eigen::Index>(points.size()) + 1;
  Eigen::VectorXd x(n), sigma = Eigen::VectorXd::Zero(n);
  std::vector<std::string> names;
  for (Eigen::Index i = 0; i < n_sizes; ++i) {
    x(i) = sizes[static_cast<std::size_t>(i)];
    names.push_back(e.sizes[static_cast<std::size_t>(i)].name);
  }
  for (std::size_t k = 0; k < points.size(); ++k) {
    for (int c = 0; c < 3; ++c) {
      x(n_sizes + 3 * static_cast<Eigen::Index>(k) + c) = points[k](c);
      names.push_back(fmt::format("{}.{}", e.points[k].name, "xyz"[c]));
    }
  }
  x(n - 1) = value;
  const std::string amount_name = amount == Amount::kMass ? "mass" : "density";
  names.push_back(amount_name);

  // dims first, then a size's own tolerance overrides it
  std::vector<std::string> known{"dims", "mass", "density"};
  if (!points.empty()) known.emplace_back("vertices");
  for (const auto& s : e.sizes) known.push_back(s.name);
  std::vector<std::string> seen;
  const auto sigma_of = [](const Tolerance& t, double nominal_value) {
    return t.relative ? t.sigma * std::abs(nominal_value) : t.sigma;
  };
  const auto require_unit = [&](const Tolerance& t, std::initializer_list<const char*> units, const char* kind) {
    if (t.relative || t.unit.empty()) return;
    for (const char* u : units) {
      if (t.unit == u) return;
    }
    RIGID_THROW("tolerance {}: '{}' is not a unit of {}; expected {} or %", t.name, t.unit, kind,
                fmt::join(units, ", "));
  };
  for (int pass = 0; pass < 2; ++pass) {
    for (const Tolerance& t : tolerances) {
      const bool is_dims = t.name == "dims";
      if ((pass == 0) != is_dims) continue;
      RIGID_REQUIRE(std::find(seen.begin(), seen.end(), t.name) == seen.end(), "tolerance {} is given twice", t.name);
      seen.push_back(t.name);
      if (is_dims) {
        require_unit(t, {"m", "cm", "mm", "um", "µm", "in"}, "length");
        for (Eigen::Index i = 0; i < n_sizes; ++i) sigma(i) = sigma_of(t, x(i));
      } else if (const auto i = e.size_index(t.name)) {
        require_unit(t, {"m", "cm", "mm", "um", "µm", "in"}, "length");
        sigma(static_cast<Eigen::Index>(*i)) = sigma_of(t, x(static_cast<Eigen::Index>(*i)));
      } else if (t.name == "vertices" && !points.empty()) {
        require_unit(t, {"m", "cm", "mm", "um", "µm", "in"}, "length");
        RIGID_REQUIRE(!t.relative, "tolerance vertices must be a length (e.g. ±0.05mm), not a percentage");
        for (Eigen::Index j = n_sizes; j < n - 1; ++j) sigma(j) = t.sigma;
      } else if (t.name == "mass" || t.name == "density") {
        RIGID_REQUIRE(t.name == amount_name,
                      "tolerance {} cannot be used: the {} primitive is given by its {}, so give {}=±…",
                      t.name, e.name, amount_name, amount_name);
        if (t.name == "mass") {
          require_unit(t, {"kg", "g"}, "mass");
        } else {
          require_unit(t, {"kg/m3", "kg/m³", "kg/m^3", "kg/m2", "kg/m²", "kg/m^2", "kg/m"}, "density");
        }
        sigma(n - 1) = sigma_of(t, value);
      } else {
        RIGID_THROW("unknown tolerance '{}'{}; the {} primitive takes {}", t.name, did_you_mean_hint(t.name, known),
                    e.name, fmt::join(known, ", "));
      }
    }
  }
  const auto f = [&](const Eigen::VectorXd& xi) -> Eigen::VectorXd {
    PrimitiveArguments a;
    for (Eigen::Index i = 0; i < n_sizes; ++i) a.sizes.emplace_back(e.sizes[static_cast<std::size_t>(i)].name, xi(i));
    for (std::size_t k = 0; k < points.size(); ++k) {
      a.points.emplace_back(e.points[k].name, xi.segment<3>(n_sizes + 3 * static_cast<Eigen::Index>(k)));
    }
    return mass_properties_vector(place(make_primitive(e.name, amount, xi(n - 1), a), placement), about);
  };
  const Propagated p = propagate(f, x, sigma, names);
  UncertainMassProperties out{nominal, p.value, p.sigma, {}};
  for (Eigen::Index i = 0; i < n; ++i) {
    if (sigma(i) > 0.0) out.inputs.push_back(names[static_cast<std::size_t>(i)]);
  }
  return out;
}

}  // namespace rigid::mass
