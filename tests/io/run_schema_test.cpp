#include "rigid/io/run_schema.hpp"

#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "rigid/io/run_output.hpp"
#include "support/expect_error.hpp"

namespace rigid::io {
namespace {

RunSchema sample_schema() {
  RunSchema s;
  s.kind = RunKind::kFreeBodies;
  s.columns.push_back({"t", Quantity::kTime, "", "", "s"});
  for (const char* c : {"x", "y", "z"}) {
    s.columns.push_back(body_column(Quantity::kPosition, "b", c));
  }
  for (const char* c : {"w", "x", "y", "z"}) {
    s.columns.push_back(body_column(Quantity::kOrientation, "b", c));
  }
  for (const char* c : {"x", "y", "z"}) {
    s.columns.push_back(body_column(Quantity::kAngularMomentum, "b", c));
  }
  s.columns.push_back({"energy", Quantity::kEnergy, "", "", "J"});
  s.parameters = {
      {"zeta", ""}, {"b_mass", "kg"}, {"a", ""}};  // not alphabetical: order must survive
  s.diagnostics = {{"energy_initial", "J"}, {"b.orthonormality_max", ""}};
  s.metrics = {{"flip", "s"}};
  return s;
}

TEST(RunSchema, KindsAndQuantitiesReadBackFromTheirNames) {
  for (const RunKind k : {RunKind::kCoordinates, RunKind::kFreeBodies}) {
    EXPECT_EQ(parse_run_kind(to_string(k)), k);
  }
  EXPECT_EQ(to_string(RunKind::kFreeBodies), "free_bodies");
  for (int q = 0; q <= static_cast<int>(Quantity::kConjugateMomentum); ++q) {
    EXPECT_EQ(parse_quantity(to_string(static_cast<Quantity>(q))), static_cast<Quantity>(q));
  }
  EXPECT_RIGID_ERROR((void)parse_run_kind("free_body"), "did you mean 'free_bodies'");
  EXPECT_RIGID_ERROR((void)parse_quantity("energie"), "unknown quantity 'energie'");
}

// The units are SI and the names follow docs/scene-format.md's columns.
TEST(RunSchema, BodyColumnsAreNamedAndUnitedAsTheTrajectoryIs) {
  EXPECT_EQ(body_column(Quantity::kPosition, "racket", "x").name, "racket.x");
  EXPECT_EQ(body_column(Quantity::kOrientation, "racket", "w").name, "racket.qw");
  EXPECT_EQ(body_column(Quantity::kVelocity, "racket", "z").name, "racket.vz");
  EXPECT_EQ(body_column(Quantity::kAngularVelocity, "racket", "y").name, "racket.wy");
  EXPECT_EQ(body_column(Quantity::kAngularMomentum, "racket", "x").name, "racket.Lx");
  EXPECT_EQ(body_column(Quantity::kAngularVelocity, "racket", "y").unit, "rad/s");
  EXPECT_EQ(body_column(Quantity::kAngularMomentum, "racket", "x").unit, "kg·m²/s");
  EXPECT_EQ(unit_of(Quantity::kVelocity), "m/s");
  EXPECT_EQ(unit_of(Quantity::kJacobi), "J");
  EXPECT_EQ(unit_of(Quantity::kCoordinate), "");  // a scene does not say what q measures
}

TEST(RunSchema, FindsColumnsByNameAndByQuantityOwnerAndComponent) {
  const RunSchema s = sample_schema();
  ASSERT_NE(s.find("b.qz"), nullptr);
  EXPECT_EQ(s.find("b.qz")->quantity, Quantity::kOrientation);
  EXPECT_EQ(s.find(Quantity::kAngularMomentum, "b", "y"), s.find("b.Ly"));
  EXPECT_EQ(s.find(Quantity::kAngularMomentum, "c", "y"), nullptr);
  EXPECT_EQ(s.find("b.wx"), nullptr);
}

TEST(RunSchema, SelectKeepsTheGivenColumnsInOrderAndRefusesOthers) {
  const RunSchema s = sample_schema();
  const std::vector<std::string> names = {"t", "energy", "b.x"};
  const RunSchema picked = s.select(names);
  EXPECT_EQ(picked.column_names(), names);
  EXPECT_EQ(picked.parameters, s.parameters);
  EXPECT_EQ(picked.columns[1].unit, "J");
  const std::vector<std::string> bad = {"t", "energyy"};
  EXPECT_RIGID_ERROR((void)s.select(bad), "did you mean 'energy'");
}

TEST(RunSchema, JsonRoundTripIsExactAndKeepsTheOrderOfEveryList) {
  const RunSchema s = sample_schema();
  EXPECT_EQ(parse_schema_json(schema_json(s), "x"), s);
}

TEST(RunSchema, MalformedJsonIsRefusedNamingTheSource) {
  EXPECT_RIGID_ERROR((void)parse_schema_json("{", "out/summary.json"),
                     "out/summary.json: the run's schema is not JSON");
  EXPECT_RIGID_ERROR((void)parse_schema_json(R"({"kind": "coordinates"})", "s.json"),
                     "lacks a field");
  EXPECT_RIGID_ERROR(
      (void)parse_schema_json(
          R"({"kind": "coordinates", "columns": [{"name": "t", "quantity": "tme", "owner": "",
                             "component": "", "unit": "s"}], "parameters": {}, "diagnostics": {}, "metrics": {}})",
          "s.json"),
      "unknown quantity 'tme'");
  EXPECT_RIGID_ERROR((void)parse_schema_json(R"({"kind": 3, "columns": []})", "s.json"),
                     "wrong type");
}

// summary.json carries the schema of a run that has one, and refuses one that is not the
// trajectory's (a defect of whoever made the run).
TEST(RunSchema, SummaryJsonCarriesTheSchemaOfItsTrajectory) {
  RunResult r;
  r.trajectory = Table({"t", "energy"});
  r.trajectory.add_row(std::vector<double>{0.0, 1.0});
  EXPECT_FALSE(nlohmann::json::parse(summary_json(r)).contains("schema"));
  r.schema.columns = {{"t", Quantity::kTime, "", "", "s"},
                      {"energy", Quantity::kEnergy, "", "", "J"}};
  const auto j = nlohmann::json::parse(summary_json(r));
  EXPECT_EQ(parse_schema_json(j.at("schema").dump(), "summary.json"), r.schema);
  r.schema.columns.pop_back();
  EXPECT_RIGID_ERROR((void)summary_json(r),
                     "the run's schema names the columns t, its trajectory has t, energy");
}

TEST(Table, SelectCopiesColumnsInTheGivenOrder) {
  Table t({"a", "b", "c"});
  t.add_row(std::vector<double>{1, 2, 3});
  t.add_row(std::vector<double>{4, 5, 6});
  const std::vector<std::size_t> pick = {2, 0};
  const Table s = t.select(pick);
  EXPECT_EQ(s.columns(), (std::vector<std::string>{"c", "a"}));
  EXPECT_EQ(s.data(), (std::vector<double>{3, 1, 6, 4}));
  const std::vector<std::size_t> out_of_range = {3};
  EXPECT_RIGID_ERROR((void)t.select(out_of_range), "column index 3 is out of range");
  const std::vector<std::size_t> twice = {1, 1};
  EXPECT_THROW((void)t.select(twice), Error);
}

}  // namespace
}  // namespace rigid::io
