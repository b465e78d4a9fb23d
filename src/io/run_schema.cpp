#include "rigid/io/run_schema.hpp"

#include <algorithm>
#include <array>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "detail/schema_json.hpp"
#include "rigid/common/did_you_mean.hpp"
#include "rigid/common/error.hpp"

namespace rigid::io {
namespace {

constexpr std::array<std::pair<RunKind, std::string_view>, 2> kKinds{
    {{RunKind::kCoordinates, "coordinates"}, {RunKind::kFreeBodies, "free_bodies"}}};

struct QuantityInfo {
  Quantity quantity;
  std::string_view name;
  std::string_view unit;
};

constexpr std::array<QuantityInfo, 15> kQuantities{{
    {Quantity::kTime, "time", "s"},
    {Quantity::kCoordinate, "coordinate", ""},
    {Quantity::kCoordinateRate, "coordinate_rate", ""},
    {Quantity::kPosition, "position", "m"},
    {Quantity::kOrientation, "orientation", ""},
    {Quantity::kVelocity, "velocity", "m/s"},
    {Quantity::kAngularVelocity, "angular_velocity", "rad/s"},
    {Quantity::kAngularMomentum, "angular_momentum", "kg·m²/s"},
    {Quantity::kEnergy, "energy", "J"},
    {Quantity::kJacobi, "jacobi", "J"},
    {Quantity::kMultiplier, "multiplier", ""},
    {Quantity::kConstraintResidual, "constraint_residual", ""},
    {Quantity::kVelocityMultiplier, "velocity_multiplier", ""},
    {Quantity::kVelocityConstraintResidual, "velocity_constraint_residual", ""},
    {Quantity::kConjugateMomentum, "conjugate_momentum", ""},
}};

const QuantityInfo& info(Quantity q) {
  for (const QuantityInfo& i : kQuantities) {
    if (i.quantity == q) return i;
  }
  RIGID_THROW("unknown quantity {}", static_cast<int>(q));
}

template <class Table>
std::vector<std::string> names_of(const Table& table) {
  std::vector<std::string> out;
  for (const auto& entry : table) {
    if constexpr (requires { entry.name; }) {
      out.emplace_back(entry.name);
    } else {
      out.emplace_back(entry.second);
    }
  }
  return out;
}

}  // namespace

std::string_view to_string(RunKind kind) {
  for (const auto& [k, name] : kKinds) {
    if (k == kind) return name;
  }
  return "?";
}

RunKind parse_run_kind(std::string_view name) {
  for (const auto& [k, n] : kKinds) {
    if (n == name) return k;
  }
  const std::vector<std::string> names = names_of(kKinds);
  throw Error(fmt::format("unknown run kind '{}'{}; expected {}", name,
                          did_you_mean_hint(name, names), fmt::join(names, " or ")));
}

std::string_view to_string(Quantity quantity) { return info(quantity).name; }

Quantity parse_quantity(std::string_view name) {
  for (const QuantityInfo& i : kQuantities) {
    if (i.name == name) return i.quantity;
  }
  const std::vector<std::string> names = names_of(kQuantities);
  throw Error(fmt::format("unknown quantity '{}'{}; expected one of: {}", name,
                          did_you_mean_hint(name, names), fmt::join(names, ", ")));
}

std::string_view unit_of(Quantity quantity) { return info(quantity).unit; }

std::vector<std::string> RunSchema::column_names() const {
  std::vector<std::string> out;
  out.reserve(columns.size());
  for (const Column& c : columns) out.push_back(c.name);
  return out;
}

const Column* RunSchema::find(std::string_view name) const {
  const auto it =
      std::find_if(columns.begin(), columns.end(), [&](const Column& c) { return c.name == name; });
  return it == columns.end() ? nullptr : &*it;
}

const Column* RunSchema::find(Quantity quantity, std::string_view owner,
                              std::string_view component) const {
  const auto it = std::find_if(columns.begin(), columns.end(), [&](const Column& c) {
    return c.quantity == quantity && c.owner == owner && c.component == component;
  });
  return it == columns.end() ? nullptr : &*it;
}

RunSchema RunSchema::select(std::span<const std::string> names) const {
  RunSchema out = *this;
  out.columns.clear();
  for (const std::string& n : names) {
    const Column* c = find(n);
    if (c == nullptr) {
      throw Error(fmt::format("the run has no column '{}'{} (columns: {})", n,
                              did_you_mean_hint(n, column_names()),
                              fmt::join(column_names(), ", ")));
    }
    out.columns.push_back(*c);
  }
  return out;
}

Column body_column(Quantity quantity, const std::string& owner, std::string_view component) {
  const bool quaternion = quantity == Quantity::kOrientation;
  const std::string_view prefix = quaternion                               ? "q"
                                  : quantity == Quantity::kVelocity        ? "v"
                                  : quantity == Quantity::kAngularVelocity ? "w"
                                  : quantity == Quantity::kAngularMomentum ? "L"
                                                                           : "";
  return Column{fmt::format("{}.{}{}", owner, prefix, component), quantity, owner,
                std::string(component), std::string(unit_of(quantity))};
}

namespace detail {

nlohmann::ordered_json schema_to_json(const RunSchema& schema) {
  nlohmann::ordered_json j;
  j["kind"] = to_string(schema.kind);
  nlohmann::ordered_json columns = nlohmann::ordered_json::array();
  for (const Column& c : schema.columns) {
    columns.push_back({{"name", c.name},
                       {"quantity", to_string(c.quantity)},
                       {"owner", c.owner},
                       {"component", c.component},
                       {"unit", c.unit}});
  }
  j["columns"] = std::move(columns);
  for (const auto& [key, list] :
       {std::pair{"parameters", &schema.parameters}, std::pair{"diagnostics", &schema.diagnostics},
        std::pair{"metrics", &schema.metrics}}) {
    nlohmann::ordered_json units = nlohmann::ordered_json::object();
    for (const Scalar& s : *list) units[s.name] = s.unit;
    j[key] = std::move(units);
  }
  return j;
}

}  // namespace detail

std::string schema_json(const RunSchema& schema) { return detail::schema_to_json(schema).dump(2); }

RunSchema parse_schema_json(std::string_view text, std::string_view source) {
  auto refuse = [&](const std::string& what) -> RunSchema {
    throw Error(fmt::format(
        "{}: the run's schema {}; expected the \"schema\" a run writes into summary.json", source,
        what));
  };
  nlohmann::ordered_json j;
  try {
    j = nlohmann::ordered_json::parse(text);
  } catch (const nlohmann::json::exception&) {
    return refuse("is not JSON");
  }
  RunSchema s;
  try {
    s.kind = parse_run_kind(j.at("kind").get<std::string>());
    for (const auto& c : j.at("columns")) {
      s.columns.push_back(Column{
          c.at("name").get<std::string>(), parse_quantity(c.at("quantity").get<std::string>()),
          c.at("owner").get<std::string>(), c.at("component").get<std::string>(),
          c.at("unit").get<std::string>()});
    }
    for (const auto& [key, list] :
         {std::pair{"parameters", &s.parameters}, std::pair{"diagnostics", &s.diagnostics},
          std::pair{"metrics", &s.metrics}}) {
      for (const auto& [name, unit] : j.at(key).items()) {
        list->push_back({name, unit.get<std::string>()});
      }
    }
  } catch (const nlohmann::json::exception&) {
    return refuse("lacks a field or has one of the wrong type");
  } catch (const Error& e) {
    return refuse(fmt::format("is not valid: {}", e.what()));
  }
  return s;
}

}  // namespace rigid::io
