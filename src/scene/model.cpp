#include "rigid/scene/model.hpp"
#include "rigid/scene/density_field.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cstdint>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <string_view>

#include <fnmatch.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "rigid/body/free_body_batch.hpp"
#include "rigid/body/free_body_exact.hpp"
#include "rigid/body/free_body_integrators.hpp"
#include "rigid/body/heavy_top.hpp"
#include "rigid/body/rigid_body.hpp"
#include "rigid/common/escape.hpp"
#include "rigid/common/did_you_mean.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/wording.hpp"
#include "rigid/integrate/integrator.hpp"
#include "rigid/lagrange/expression_names.hpp"
#include "rigid/mass/primitive_table.hpp"
#include "rigid/mass/primitives.hpp"
#include "rigid/mesh/mass_from_file.hpp"
#include "rigid/mesh/read_mesh.hpp"
#include "detail/metrics.hpp"

namespace rigid::scene {
namespace {

using Clock = std::chrono::steady_clock;

// A scene expression for the Lagrangian engine: positions inside it map to the file.
lagrange::Expression to_lagrange(const Expression& e) { return {e.text, e.at(0)}; }

// Rethrows an error of a library call at a position of the scene file, unless the error
// already names a position in that file (expressions report their own column). The remedy is
// worded for a scene (its settings are the body's keys).
template <typename F>
auto at_location(const SourceLocation& where, const std::string& context, F&& f) {
  try {
    return f();
  } catch (const Cancelled&) {
    throw;
  } catch (const Error& e) {
    const std::string what = word_for(Surface::kScene, e.what());
    if (!where.file.empty() && what.starts_with(where.file + ":")) throw;
    detail::throw_error_at(where, fmt::format("{}: {}", context, what));
  }
}

// The results of a prototype model's expressions that are not plain numbers, by text.
using Results = std::map<std::string, double, std::less<>>;

// Whether every parameter `text` names (rigid::lagrange::names_in; function names are not
// parameters) has bit for bit the same value in `now` as in `then` (the last parameter of a
// name is the one an expression sees).
bool same_inputs(std::string_view text, const std::vector<lagrange::Parameter>& now,
                 const std::vector<lagrange::Parameter>& then) {
  auto value = [](const std::vector<lagrange::Parameter>& ps,
                  std::string_view name) -> std::optional<double> {
    for (auto it = ps.rbegin(); it != ps.rend(); ++it) {
      if (it->name == name) return it->value;
    }
    return std::nullopt;
  };
  for (const std::string& name : lagrange::names_in(text)) {
    const std::optional<double> a = value(now, name), b = value(then, name);
    if (a.has_value() != b.has_value()) return false;
    if (a && std::bit_cast<std::uint64_t>(*a) != std::bit_cast<std::uint64_t>(*b)) return false;
  }
  return true;
}

// The values of a model's expressions, from the parameters evaluated so far. A model built
// like another takes the other's result for the same text when every parameter the text names
// has the value it had there: the evaluation is deterministic, so that is the result a new one
// would give, and a sweep's run enters the symbolic core only for an expression of a swept
// value. A prototype (no `like`) records its results for the models built like it.
class Evaluator {
 public:
  Evaluator(const std::vector<lagrange::Parameter>& params,
            const std::vector<lagrange::Parameter>* like_params, const Results* like_results,
            Results* record)
      : params_(params), like_params_(like_params), like_results_(like_results), record_(record) {}

  [[nodiscard]] const std::vector<lagrange::Parameter>& params() const { return params_; }

  [[nodiscard]] double value(const Expression& e, const std::string& what) const {
    if (e.number) return *e.number;
    if (like_results_ != nullptr) {
      const auto it = like_results_->find(e.text);
      if (it != like_results_->end() && same_inputs(e.text, params_, *like_params_)) {
        return it->second;
      }
    }
    const double v = lagrange::evaluate_constant(to_lagrange(e), params_, what);
    if (record_ != nullptr) record_->emplace(e.text, v);
    return v;
  }

  [[nodiscard]] Eigen::Vector3d vector(const std::array<Expression, 3>& e,
                                       const std::string& what) const {
    return {value(e[0], what), value(e[1], what), value(e[2], what)};
  }

 private:
  const std::vector<lagrange::Parameter>& params_;
  const std::vector<lagrange::Parameter>* like_params_;
  const Results* like_results_;
  Results* record_;
};

lagrange::Vector3Expression expressions_of(const std::array<Expression, 3>& e) {
  return lagrange::Vector3Expression(std::array<lagrange::Expression, 3>{to_lagrange(e[0]), to_lagrange(e[1]),
                                                                         to_lagrange(e[2])});
}

// A body's mass properties twice: the numbers (checked by the libraries, for the simulation)
// and expressions of the parameters (for the equations), plus the constants a file or a
// vertex list contributes, which get names of their own.
struct BodyMass {
  MassProperties numeric;
  lagrange::BodyMass symbolic;
  std::vector<std::pair<std::string, double>> sizes{};  // a primitive's, canonical names
  std::optional<mass::DensityIntegration> density_field{};  // a density field's cubature
};

// Names for the constants of a body that the scene did not write (a mesh file's mass
// properties, a tetrahedron's): <body>_mass, <body>_com_x, …, <body>_ixx, …; zero entries
// stay 0. The names are added to `derived` with their values, and their SI units to `units`.
lagrange::BodyMass named_constants(const std::string& body, const MassProperties& mp,
                                   const std::vector<lagrange::Parameter>& taken,
                                   std::vector<lagrange::Parameter>& derived,
                                   std::vector<std::string>& units) {
  auto name = [&](const std::string& suffix, double value,
                  const char* unit) -> lagrange::Expression {
    if (value == 0.0) return lagrange::Expression("0");
    std::string n = body + "_" + suffix;
    auto used = [&](const std::string& x) {
      auto same = [&](const lagrange::Parameter& p) { return p.name == x; };
      return std::any_of(taken.begin(), taken.end(), same) || std::any_of(derived.begin(), derived.end(), same);
    };
    while (used(n)) n += "_";
    derived.push_back({n, value});
    units.emplace_back(unit);
    return lagrange::Expression(n);
  };
  lagrange::BodyMass b;
  b.mass = name("mass", mp.mass(), "kg");
  static constexpr const char* kCom[3] = {"com_x", "com_y", "com_z"};
  for (std::size_t k = 0; k < 3; ++k) {
    b.com[k] = name(kCom[k], mp.com()[static_cast<Eigen::Index>(k)], "m");
  }
  const Eigen::Matrix3d& I = mp.inertia_com();
  for (std::size_t k = 0; k < 6; ++k) {
    const auto& [element, row, col] = lagrange::BodyMass::kInertiaElements[k];
    b.inertia[k] = name(element, I(row, col), "kg·m²");
  }
  return b;
}

// Mass, COM (3) and inertia (6) as expression text (rigid::mass::primitive_expressions' layout).
lagrange::BodyMass body_mass_of(const std::array<std::string, 10>& text) {
  lagrange::BodyMass b;
  b.mass = text[0];
  for (std::size_t k = 0; k < 3; ++k) b.com[k] = text[1 + k];
  for (std::size_t k = 0; k < 6; ++k) b.inertia[k] = text[4 + k];
  return b;
}

// A mesh body's file as read and repaired; null for other bodies. A model built like another
// (a sweep's run) takes the other's when file, units and hole filling are the same, so a sweep
// reads each mesh file once and only measures it again for its run's mass or density.
using SharedMesh = std::shared_ptr<const mesh::PreparedMesh>;

BodyMass mass_of(const Body& b, const Evaluator& eval, std::vector<lagrange::Parameter>& derived,
                 std::vector<std::string>& derived_units, std::vector<std::string>& warnings,
                 SharedMesh& prepared) {
  const MassSpec& m = b.mass;
  const std::vector<lagrange::Parameter>& params = eval.params();
  const std::string ctx = fmt::format("body '{}'", b.name);
  switch (m.kind) {
    case MassSpec::Kind::kPrimitive: {
      const mass::PrimitiveEntry& entry = mass::find_primitive(m.primitive);
      mass::PrimitiveArguments args;
      for (const auto& [key, e] : m.dimensions) {
        args.sizes.emplace_back(key, eval.value(e, ctx + " " + key));
      }
      for (const auto& [key, e] : m.vertices) {
        args.points.emplace_back(key, eval.vector(e, ctx + " " + key));
      }
      if (m.density_field) {
        // ρ(x, y, z) with the run's parameters: integrated, named as constants (no closed form)
        const mass::DensityIntegration integration = at_location(m.where, ctx, [&] {
          const auto rho = compile_density_field(
              lagrange::Expression(m.density_field->text, m.density_field->where), params,
              ctx + " density_field");
          return integrate_density_field(m.primitive, args.sizes, rho, ctx + " density_field");
        });
        const MassProperties& numeric = integration.mass_properties;
        return {numeric, named_constants(b.name, numeric, params, derived, derived_units), {},
                integration};
      }
      const bool by_mass = m.mass.has_value();
      const Expression& amount = by_mass ? *m.mass : *m.density;
      const double value = eval.value(amount, ctx + (by_mass ? " mass" : " density"));
      const mass::Amount kind = by_mass ? mass::Amount::kMass : mass::Amount::kDensity;
      MassProperties numeric = at_location(m.where, ctx, [&] { return mass::make_primitive(m.primitive, kind, value, args); });
      std::vector<std::pair<std::string, double>> evaluated;  // canonical names, catalogue order
      for (const mass::PrimitiveSize& size : entry.sizes) {
        for (const auto& [key, v] : args.sizes) {
          if (entry.size_index(key) == entry.size_index(size.name)) evaluated.emplace_back(size.name, v);
        }
      }
      if (entry.formulas.mass.empty()) {
        return {numeric, named_constants(b.name, numeric, params, derived, derived_units),
                evaluated};
      }
      // the closed forms with the sizes as the file wrote them, in the entry's order
      std::vector<std::string> sizes(entry.sizes.size());
      for (const auto& [key, e] : m.dimensions) sizes[*entry.size_index(key)] = e.text;
      const std::array<std::string, 10> text = mass::primitive_expressions(entry, kind, amount.text, sizes);
      const lagrange::BodyMass symbolic = body_mass_of(text);
      return {numeric, symbolic, evaluated};
    }
    case MassSpec::Kind::kMesh: {
      if (m.density_field) {
        // ρ(x, y, z) over the closed mesh, read and checked as a solid of unit mass (its
        // refusals and warnings), then integrated; named as constants like a uniform mesh's
        const mass::DensityIntegration integration = at_location(m.where, ctx, [&] {
          if (!prepared) {
            prepared = std::make_shared<const mesh::PreparedMesh>(
                mesh::prepare_mesh_file(m.mesh_file.string(), mesh::unit_scale(m.units), {}, m.fill_holes));
          }
          (void)mesh::measure_prepared_mesh(*prepared, {1.0, std::nullopt, false, std::nullopt});
          const auto rho = compile_density_field(
              lagrange::Expression(m.density_field->text, m.density_field->where), params,
              ctx + " density_field");
          mass::DensityIntegration r = integrate_density_field_over_mesh(
              prepared->mesh.vertices, prepared->mesh.triangles, rho, ctx + " density_field");
          // the warnings of a solid of that mass: its size and its mean density against real materials
          const mesh::MeshFileMass solid = mesh::measure_prepared_mesh(
              *prepared, {r.mass_properties.mass(), std::nullopt, false, std::nullopt});
          for (const auto& w : solid.warnings()) warnings.push_back(fmt::format("{}: {}", ctx, word_for(Surface::kScene, w)));
          return r;
        });
        const MassProperties& numeric = integration.mass_properties;
        return {numeric, named_constants(b.name, numeric, params, derived, derived_units), {},
                integration};
      }
      mesh::MassSpec spec;
      if (m.mass) spec.mass = eval.value(*m.mass, ctx + " mass");
      if (m.density) spec.density = eval.value(*m.density, ctx + " density");
      spec.shell = m.shell;
      if (m.thickness) spec.thickness = eval.value(*m.thickness, ctx + " thickness");
      MassProperties numeric = at_location(m.where, ctx, [&] {
        if (!prepared) {
          prepared = std::make_shared<const mesh::PreparedMesh>(
              mesh::prepare_mesh_file(m.mesh_file.string(), mesh::unit_scale(m.units), {}, m.fill_holes));
        }
        const mesh::MeshFileMass r = mesh::measure_prepared_mesh(*prepared, spec);
        for (const auto& w : r.warnings()) warnings.push_back(fmt::format("{}: {}", ctx, word_for(Surface::kScene, w)));
        return r.mass.properties;
      });
      return {numeric, named_constants(b.name, numeric, params, derived, derived_units), {}};
    }
    case MassSpec::Kind::kExplicit: {
      const double mass = eval.value(*m.mass, ctx + " inertia mass");
      const Eigen::Vector3d com = eval.vector(m.com, ctx + " inertia com");
      Eigen::Matrix3d I;
      for (std::size_t i = 0; i < 6; ++i) {
        const auto& [element, row, col] = lagrange::BodyMass::kInertiaElements[i];
        I(row, col) = I(col, row) = eval.value(m.inertia[i], ctx + " " + element);
      }
      MassProperties numeric = at_location(m.where, ctx, [&] { return MassProperties(mass, com, I); });
      lagrange::BodyMass symbolic;
      symbolic.mass = to_lagrange(*m.mass);
      symbolic.com = expressions_of(m.com);
      for (std::size_t i = 0; i < 6; ++i) symbolic.inertia[i] = to_lagrange(m.inertia[i]);
      return {numeric, symbolic, {}};
    }
    case MassSpec::Kind::kPointMasses: {
      std::vector<double> masses;
      Eigen::Matrix3Xd points(3, static_cast<Eigen::Index>(m.points.size()));
      for (std::size_t i = 0; i < m.points.size(); ++i) {
        masses.push_back(eval.value(m.points[i].mass, ctx + " point mass"));
        points.col(static_cast<Eigen::Index>(i)) =
            eval.vector(m.points[i].position, ctx + " point position");
      }
      MassProperties numeric = at_location(m.where, ctx, [&] { return mass::point_masses(masses, points); });
      // the same sums as expressions of the parameters (rigid::mass::point_mass_expressions)
      std::vector<mass::PointMassText> texts;
      for (const PointMass& pm : m.points) {
        texts.push_back(
            {pm.mass.text, {pm.position[0].text, pm.position[1].text, pm.position[2].text}});
      }
      const std::array<std::string, 10> text = mass::point_mass_expressions(texts);
      const lagrange::BodyMass symbolic = body_mass_of(text);
      return {numeric, symbolic, {}};
    }
  }
  RIGID_THROW("unreachable mass kind");
}

// The integrator of a run, parsed once.
struct Method {
  std::string name;
  bool exact = false;                                       // free bodies: closed form
  integrate::Method coordinates = integrate::Method::kDopri5;
  body::FreeBodyMethod free = body::FreeBodyMethod::kSplitting4;
};

// A free body of the scene: a rigid body in uniform gravity, or a heavy top on its pivot. It
// is stepped in its principal frame P (about the COM, or about the pivot for a top), where its
// inertia is diagonal and the free-body kernels need no change of frame; the outputs are those
// of the scene's body frame B: R_WB = R_WP R_BPᵀ, ω_B = R_BP ω_P.
struct FreeBody {
  std::string name;
  std::optional<body::RigidBody> rigid;  // in P, origin at the COM
  std::optional<body::HeavyTop> top;     // in P, origin that of B
  SO3d R_BP = SO3d::identity();
  bool principal_is_body = true;  // R_BP = 1
  Eigen::Vector3d com_B = Eigen::Vector3d::Zero(), pivot_B = Eigen::Vector3d::Zero();
  lagrange::BodyMass symbolic;
  std::optional<std::array<Expression, 3>> pivot_expressions;
  Eigen::Vector3d pivot_W = Eigen::Vector3d::Zero();
  body::RigidBodyState initial;  // R_WP, ω_P and (free) p_WC, v_WC
};

// Appends p and R's quaternion (sign chosen to continue `previous`, so the columns are
// continuous).
void push_pose(std::vector<double>& row, const Eigen::Vector3d& p, const SO3d& R, Eigen::Vector4d& previous) {
  Eigen::Vector4d q = R.quaternion();
  if (q.dot(previous) < 0) q = -q;
  previous = q;
  row.insert(row.end(), {p.x(), p.y(), p.z(), q(0), q(1), q(2), q(3)});
}

// Largest |x_k − x_0| over the samples.
double max_change(const std::vector<double>& x) {
  double m = 0;
  for (double v : x) m = std::max(m, std::abs(v - x.front()));
  return m;
}

// A value that is not finite, in words: "not a number", "+infinity" or "-infinity".
std::string nonfinite_text(double v) {
  if (std::isnan(v)) return "not a number";
  return v > 0 ? "+infinity" : "-infinity";
}

std::string format_vec(const Eigen::Vector3d& v) {
  return fmt::format("({:.8g}, {:.8g}, {:.8g})", v.x(), v.y(), v.z());
}

}  // namespace

struct Model::Impl {
  Scene scene;
  SceneKind kind = SceneKind::kCoordinates;
  std::vector<lagrange::Parameter> params;   // the scene's, then the derived constants
  std::size_t scene_params = 0;              // how many of params the scene wrote
  std::vector<std::string> param_units;      // per parameter: "" for the scene's (it states none),
                                             // kg, m, kg·m² for the derived constants
  std::vector<ModelBody> bodies;
  std::vector<SharedMesh> meshes;  // per body: its mesh as read (null for other bodies)
  // the prototype's results of the expressions that are not numbers (shared by the models built
  // like it, which read them through Evaluator)
  std::shared_ptr<const Results> results;
  std::vector<std::string> warnings;
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();
  // simulation settings (validated)
  double t_end = 0, dt = 1e-3, tolerance = 1e-9, output_dt = 0;
  // coordinates: the derived equations (shared, read-only, by the models built from this one with
  // Model(scene, like)), and this model's initial state; runs pass this model's parameter values
  // and initial state, so the System's own defaults are never what a run uses
  std::shared_ptr<const lagrange::System> system;
  Eigen::VectorXd q0, q_dot0;
  // free bodies
  std::vector<FreeBody> free;
  // what a run produces: every column the model computes (full), and what run() returns after
  // [output] quantities selects columns (`kept`: their indices in full)
  io::RunSchema full_schema, schema;
  std::vector<std::size_t> kept;
  // metrics: the column each reads (index in full_schema), and how many leading columns are
  // functions of the state alone (what a step can evaluate)
  std::vector<std::size_t> metric_columns;
  std::size_t probe_size = 0;

  void read_simulation(const Evaluator& eval) {
    const Simulation& s = scene.simulation;
    auto positive = [&](const Expression& e, const char* what, const char* unit) {
      const double v = eval.value(e, std::string("[simulation] ") + what);
      if (!(v > 0)) {
        detail::throw_error_at(e.where, fmt::format("[simulation] {} must be positive, got {} {}", what, v, unit));
      }
      return v;
    };
    t_end = positive(s.t_end, "t_end", "s");
    if (s.dt) dt = positive(*s.dt, "dt", "s");
    if (s.tolerance) {
      tolerance = positive(*s.tolerance, "tolerance", "");
      if (tolerance < integrate::kMinRelativeTolerance) {
        detail::throw_error_at(s.tolerance->where,
                               fmt::format("[simulation] tolerance = {} is below what double precision "
                                           "can deliver; expected at least {:.3g} (10 ε)",
                                           tolerance, integrate::kMinRelativeTolerance));
      }
      if (tolerance > integrate::kMaxTolerance) {
        detail::throw_error_at(s.tolerance->where,
                               integrate::tolerance_above_bound("[simulation] tolerance", tolerance));
      }
    }
    if (s.output_dt) output_dt = positive(*s.output_dt, "output_dt", "s");
    if (output_dt > t_end) {
      detail::throw_error_at(s.output_dt->where, fmt::format("[simulation] output_dt = {} s is longer than "
                                                              "t_end = {} s; expected at most t_end",
                                                              output_dt, t_end));
    }
    // the output grid is made (and refused when too fine) before anything runs
    const double spacing = output_dt > 0 ? output_dt : dt;
    const SourceLocation& at = s.output_dt ? s.output_dt->where : s.dt ? s.dt->where : s.where;
    at_location(at, "[simulation]", [&] { return integrate::TimeGrid::uniform(0.0, t_end, spacing); });
  }

  // The schema of a run (before [output] quantities selects columns): the trajectory's columns,
  // the parameters, the diagnostics; check_metrics adds the metrics' units.
  [[nodiscard]] io::RunSchema make_schema() const {
    using Q = io::Quantity;
    io::RunSchema s;
    s.kind = kind;
    auto scalar = [&](Q q, std::string name, std::string owner) {
      s.columns.push_back({std::move(name), q, std::move(owner), "", std::string(io::unit_of(q))});
    };
    auto vector = [&](Q q, const std::string& body) {
      for (const char* c : {"x", "y", "z"}) s.columns.push_back(io::body_column(q, body, c));
    };
    auto pose = [&](const std::string& body) {
      vector(Q::kPosition, body);
      for (const char* c : {"w", "x", "y", "z"}) {
        s.columns.push_back(io::body_column(Q::kOrientation, body, c));
      }
    };
    auto diagnostic = [&](std::string name, Q q) {
      s.diagnostics.push_back({std::move(name), std::string(io::unit_of(q))});
    };
    scalar(Q::kTime, "t", "");
    if (kind == SceneKind::kCoordinates) {
      const lagrange::System& sys = *system;
      for (const auto& c : sys.coordinate_names()) scalar(Q::kCoordinate, c, c);
      // a coordinate's rate c_dot is owned by c; a ball's ω (b_wx …) by itself
      for (const auto& v : sys.velocity_names()) {
        scalar(Q::kCoordinateRate, v, v.ends_with("_dot") ? v.substr(0, v.size() - 4) : v);
      }
      for (const auto& b : sys.body_names()) pose(b);
      scalar(Q::kEnergy, "energy", "");
      scalar(Q::kJacobi, "jacobi", "");
      for (const auto& c : sys.constraint_names()) scalar(Q::kMultiplier, "lambda_" + c, c);
      if (!sys.constraint_names().empty()) {
        scalar(Q::kConstraintResidual, "constraint_residual", "");
      }
      for (const auto& c : sys.velocity_constraint_names()) {
        scalar(Q::kVelocityMultiplier, "mu_" + c, c);
      }
      if (sys.num_velocity_constraints() > 0) {
        scalar(Q::kVelocityConstraintResidual, "velocity_constraint_residual", "");
      }
      for (const auto& c : sys.cyclic_coordinates()) scalar(Q::kConjugateMomentum, "p_" + c, c);
      for (const char* d : {"energy_initial", "energy_final", "energy_max_change"}) {
        diagnostic(d, Q::kEnergy);
      }
      diagnostic("jacobi_max_change", Q::kJacobi);
      if (!sys.constraint_names().empty()) {
        diagnostic("constraint_residual_max", Q::kConstraintResidual);
        diagnostic("constraint_velocity_residual_max", Q::kConstraintResidual);
      }
      if (sys.num_velocity_constraints() > 0) {
        diagnostic("velocity_constraint_residual_max", Q::kVelocityConstraintResidual);
      }
      for (const auto& c : sys.cyclic_coordinates()) {
        diagnostic("p_" + c + "_max_change", Q::kConjugateMomentum);
      }
    } else {
      for (const FreeBody& f : free) {
        pose(f.name);
        vector(Q::kVelocity, f.name);
        vector(Q::kAngularVelocity, f.name);
        vector(Q::kAngularMomentum, f.name);
      }
      scalar(Q::kEnergy, "energy", "");
      for (const char* d : {"energy_initial", "energy_final", "energy_max_change"}) {
        diagnostic(d, Q::kEnergy);
      }
      for (const FreeBody& f : free) {
        diagnostic(f.name + (f.top ? ".L_vertical_max_change" : ".L_norm_max_change"),
                   Q::kAngularMomentum);
        s.diagnostics.push_back({f.name + ".orthonormality_max", ""});
      }
    }
    for (std::size_t k = 0; k < params.size(); ++k) {
      s.parameters.push_back({params[k].name, param_units[k]});
    }
    return s;
  }

  // The schema of what run() returns: [output] quantities (shell patterns, fnmatch) select
  // columns, `t` first. A pattern that matches nothing is an error that lists the columns.
  void select_columns() {
    const Output& out = scene.output;
    const std::vector<std::string> cols = full_schema.column_names();
    kept.clear();
    if (out.quantities.empty()) {
      for (std::size_t c = 0; c < cols.size(); ++c) kept.push_back(c);
      schema = full_schema;
      return;
    }
    std::vector<bool> keep(cols.size(), false);
    keep[0] = true;  // t
    for (const std::string& p : out.quantities) {
      bool any = false;
      for (std::size_t c = 0; c < cols.size(); ++c) {
        if (fnmatch(p.c_str(), cols[c].c_str(), 0) == 0) keep[c] = any = true;
      }
      if (!any) {
        std::string msg = fmt::format("[output] quantities: '{}' matches no column", p);
        if (auto g = did_you_mean(p, cols)) msg += fmt::format("; did you mean '{}'?", *g);
        detail::throw_error_at(out.quantities_where,
                               msg + fmt::format(" (columns: {})", fmt::join(cols, ", ")));
      }
    }
    std::vector<std::string> names;
    for (std::size_t c = 0; c < cols.size(); ++c) {
      if (!keep[c]) continue;
      kept.push_back(c);
      names.push_back(cols[c]);
    }
    schema = full_schema.select(names);
  }

  [[nodiscard]] std::vector<std::string> columns() const { return full_schema.column_names(); }

  [[nodiscard]] std::uint64_t max_memory(const RunOptions& o) const {
    if (o.max_memory) return *o.max_memory;
    if (scene.output.max_memory) return *scene.output.max_memory;
    return io::kDefaultMaxMemory;
  }

  // What a run would refuse, found before it runs: more rows than the memory limit allows
  // (rows × columns × 8 bytes), more steps than a run may take. Returns the most rows dopri5
  // may record when it samples every step (their number is known only while it runs).
  std::size_t check_budget(const Method& method, const RunOptions& o) const {
    const Simulation& s = scene.simulation;
    const std::size_t cols = columns().size();
    const std::uint64_t limit = max_memory(o);
    const bool every_step = kind == SceneKind::kCoordinates && method.coordinates == integrate::Method::kDopri5 &&
                            !(output_dt > 0);
    const integrate::TimeGrid grid = integrate::TimeGrid::uniform(0.0, t_end, output_dt > 0 ? output_dt : dt);
    if (!every_step) io::check_trajectory_memory(grid.size(), cols, limit);
    const bool fixed_steps = kind == SceneKind::kFreeBodies ? !method.exact
                                                            : method.coordinates != integrate::Method::kDopri5;
    if (fixed_steps) {
      // the step counts of the march (TimeGrid::steps_in), without stepping
      const std::size_t max_steps = kind == SceneKind::kFreeBodies ? o.control.max_steps
                                                                   : std::min(o.control.max_steps, integrate::Options{}.max_steps);
      const SourceLocation& at = s.dt ? s.dt->where : s.where;
      at_location(at, "[simulation] dt", [&] {
        std::size_t total = 0;
        for (std::size_t k = 0; k < grid.size(); ++k) total += grid.steps_in(k, dt, max_steps, total);
        return total;
      });
    }
    return static_cast<std::size_t>(std::min<double>(static_cast<double>(limit) / (8.0 * static_cast<double>(cols)),
                                                     static_cast<double>(integrate::TimeGrid::kMaxOutputs)));
  }

  // q(0) and q̇(0): a ball's quaternion (4 entries of q) and ω (3 of q̇)
  void read_initial_state(const Evaluator& eval) {
    std::vector<double> q, v;
    constexpr std::array<const char*, 4> kPart{"w", "x", "y", "z"};
    for (const Coordinate& c : scene.coordinates) {
      if (c.kind == Coordinate::Kind::kBall) {
        for (std::size_t k = 0; k < 4; ++k) {
          q.push_back(eval.value(c.orientation[k], fmt::format("{} orientation {}", c.name, kPart[k])));
        }
        for (std::size_t k = 0; k < 3; ++k) {
          v.push_back(eval.value(c.angular_velocity[k],
                                 fmt::format("{} angular velocity {}", c.name, kPart[k + 1])));
        }
        continue;
      }
      q.push_back(eval.value(c.initial, c.name + " initial"));
      v.push_back(eval.value(c.velocity, c.name + " velocity"));
    }
    q0 = Eigen::Map<const Eigen::VectorXd>(q.data(), static_cast<Eigen::Index>(q.size()));
    q_dot0 = Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
  }

  // A workspace of the System with this model's parameter values.
  [[nodiscard]] lagrange::Workspace make_workspace() const {
    lagrange::Workspace w = system->make_workspace();
    w.set_parameters(params);
    return w;
  }

  void build_coordinates(const std::vector<lagrange::BodyMass>& masses, const Evaluator& eval) {
    read_initial_state(eval);
    lagrange::SystemSpec spec;
    spec.parameters = params;
    Eigen::Index iq = 0, iv = 0;
    for (const Coordinate& c : scene.coordinates) {
      lagrange::Coordinate lc{c.name, 0.0, 0.0};
      if (c.kind == Coordinate::Kind::kBall) {
        lc.kind = lagrange::Coordinate::Kind::kBall;
        for (std::size_t k = 0; k < 4; ++k) lc.orientation[k] = q0(iq++);
        for (Eigen::Index k = 0; k < 3; ++k) lc.angular_velocity[k] = q_dot0(iv++);
      } else {
        lc.initial = q0(iq++);
        lc.velocity = q_dot0(iv++);
      }
      spec.coordinates.push_back(std::move(lc));
    }
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const Body& b = scene.bodies[i];
      lagrange::Body lb{b.name, masses[i], {}, {}};
      for (std::size_t k = 0; k < 3; ++k) lb.position[k] = to_lagrange(b.position[k]);
      for (const AxisRotation& r : b.rotations) {
        lb.rotations.push_back({Eigen::Vector3d(r.axis[0], r.axis[1], r.axis[2]), to_lagrange(r.angle)});
      }
      if (b.orientation) lb.orientation = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>(b.orientation->data());
      lb.parent = b.parent;
      for (const Joint& j : b.joints) {
        lb.joints.push_back({j.kind == Joint::Kind::kTurn    ? lagrange::JointMotion::Kind::kTurn
                             : j.kind == Joint::Kind::kBall ? lagrange::JointMotion::Kind::kBall
                                                            : lagrange::JointMotion::Kind::kSlide,
                             Eigen::Vector3d(j.axis[0], j.axis[1], j.axis[2]),
                             Eigen::Vector3d(j.anchor[0], j.anchor[1], j.anchor[2]),
                             to_lagrange(j.amount)});
      }
      spec.bodies.push_back(std::move(lb));
    }
    spec.gravity_W = expressions_of(scene.gravity);
    if (scene.lagrangian) spec.lagrangian = to_lagrange(*scene.lagrangian);
    for (const auto& p : scene.potentials) spec.potentials.push_back({p.name, to_lagrange(p.expression)});
    for (const auto& f : scene.forces) spec.forces.push_back({f.name, to_lagrange(f.expression)});
    for (const auto& c : scene.constraints) spec.constraints.push_back({c.name, to_lagrange(c.expression)});
    for (const VelocityConstraint& vc : scene.velocity_constraints) {
      lagrange::VelocityConstraint lv{vc.name, {}, vc.term ? to_lagrange(*vc.term) : lagrange::Expression(), vc.where};
      for (const auto& c : vc.coefficients) lv.coefficients.push_back({c.name, to_lagrange(c.expression)});
      spec.velocity_constraints.push_back(std::move(lv));
    }
    for (const Spring& sp : scene.springs) {
      lagrange::Spring ls;
      ls.body_a = sp.body_a;
      ls.point_a_B = Eigen::Vector3d(sp.point_a[0], sp.point_a[1], sp.point_a[2]);
      ls.body_b = sp.body_b;
      ls.point_b_B = Eigen::Vector3d(sp.point_b[0], sp.point_b[1], sp.point_b[2]);
      ls.stiffness = to_lagrange(sp.stiffness);
      ls.rest_length = to_lagrange(sp.rest_length);
      spec.springs.push_back(std::move(ls));
    }
    const SourceLocation whole{scene.file.string(), 0, 0};
    system = std::make_shared<const lagrange::System>(at_location(whole, "the equations of motion", [&] {
      return lagrange::System(spec);
    }));
  }

  void build_free_bodies(const std::vector<lagrange::BodyMass>& masses) {
    if (!scene.springs.empty()) {
      detail::throw_error_at(scene.springs.front().where,
                             "springs between free bodies are not simulated; pose the bodies by "
                             "[[coordinates]] to connect them with springs");
    }
    if (!scene.velocity_constraints.empty()) {
      detail::throw_error_at(scene.velocity_constraints.front().where,
                             "[[velocity_constraints]] act on coordinates; a scene of free bodies "
                             "has none (pose the bodies by [[coordinates]] to constrain their "
                             "velocities)");
    }
    if (!scene.constraints.empty() || !scene.potentials.empty() || !scene.forces.empty()) {
      detail::throw_error_at({scene.file.string(), 0, 0},
                             "[[constraints]], [[potentials]] and [[forces]] act on coordinates; a "
                             "scene of free bodies has none");
    }
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const Body& b = scene.bodies[i];
      const MassProperties& mp = bodies[i].mass;
      FreeBody f;
      f.name = b.name;
      f.symbolic = masses[i];
      const SO3d R_WB0 = SO3d::from_quaternion(b.initial_orientation[0], b.initial_orientation[1],
                                               b.initial_orientation[2], b.initial_orientation[3]);
      const Eigen::Vector3d p_WB0(b.initial_position[0], b.initial_position[1], b.initial_position[2]);
      const Eigen::Vector3d w_B0(b.angular_velocity[0], b.angular_velocity[1], b.angular_velocity[2]);
      const Eigen::Vector3d v0(b.initial_velocity[0], b.initial_velocity[1], b.initial_velocity[2]);
      const std::string ctx = fmt::format("free body '{}'", b.name);
      f.com_B = mp.com();
      if (b.pivot) {
        f.pivot_B = Eigen::Vector3d((*b.pivot)[0], (*b.pivot)[1], (*b.pivot)[2]);
        if (v0.norm() != 0) {
          detail::throw_error_at(b.where, fmt::format("body '{}' turns about its pivot, so its COM "
                                                      "velocity follows from angular_velocity; "
                                                      "remove initial_velocity",
                                                      b.name));
        }
        // P: the principal axes of the inertia about the pivot (rigid::MassProperties)
        const PrincipalAxes pa = at_location(b.where, ctx, [&] {
          return MassProperties(mp.mass(), Eigen::Vector3d::Zero(), mp.inertia_about(f.pivot_B)).principal_axes();
        });
        f.R_BP = SO3d::from_matrix(pa.R_BP);
        const SO3d R_PB = f.R_BP.inverse();
        const MassProperties mass_P(mp.mass(), R_PB * mp.com(),
                                    R_PB.matrix() * mp.inertia_com() * R_PB.matrix().transpose());
        f.top.emplace(at_location(b.where, ctx, [&] { return body::HeavyTop(mass_P, R_PB * f.pivot_B, gravity); }));
        f.pivot_W = p_WB0 + R_WB0 * f.pivot_B;
        std::array<Expression, 3> pv;
        for (std::size_t k = 0; k < 3; ++k) {
          const double v = (*b.pivot)[k];
          pv[k] = Expression::of(v, b.where);
        }
        f.pivot_expressions = pv;
      } else {
        // P: the principal axes of the inertia about the COM; the body there is diagonal
        const PrincipalAxes pa = mp.principal_axes();
        f.R_BP = SO3d::from_matrix(pa.R_BP);
        const MassProperties mass_P(mp.mass(), Eigen::Vector3d::Zero(), pa.moments.asDiagonal().toDenseMatrix());
        f.rigid.emplace(at_location(b.where, ctx, [&] { return body::RigidBody(mass_P, gravity); }));
        f.initial.p_WC = p_WB0 + R_WB0 * mp.com();
        f.initial.v_WC = v0;
      }
      f.principal_is_body = f.R_BP.w() == 1.0;
      f.initial.R_WB = R_WB0 * f.R_BP;
      f.initial.w_B = f.R_BP.inverse() * w_B0;
      free.push_back(std::move(f));
    }
  }

  // Every metric's column is checked against the run's columns, at the metric's line.
  // Their units go into the schema.
  void check_metrics() {
    const std::vector<std::string> cols = columns();
    probe_size = cols.size();
    if (kind == SceneKind::kCoordinates) {
      const io::Column* jacobi = full_schema.find(io::Quantity::kJacobi, "", "");
      probe_size = static_cast<std::size_t>(jacobi - full_schema.columns.data()) + 1;
    }
    for (const MetricSpec& m : scene.output.metrics) {
      const std::string what = fmt::format("[[output.metrics]] '{}'", m.name);
      if (m.kind == MetricSpec::Kind::kDrift) {
        std::vector<std::string> takes = {"energy"};
        if (kind == SceneKind::kCoordinates) takes.push_back("jacobi");
        for (const FreeBody& f : free) takes.push_back(f.name + ".L");
        if (std::find(takes.begin(), takes.end(), m.column) == takes.end()) {
          detail::throw_error_at(m.column_where,
                                 fmt::format("{}: drift of '{}' is not known{}; expected one of: {} (<body>.L: the "
                                             "norm of a free body's angular momentum, its vertical component "
                                             "on a pivot)",
                                             what, m.column, did_you_mean_hint(m.column, takes), fmt::join(takes, ", ")));
        }
        metric_columns.push_back(0);
        full_schema.metrics.push_back({m.name, m.unit_given ? m.unit : ""});
        continue;
      }
      const auto it = std::find(cols.begin(), cols.end(), m.column);
      if (it == cols.end()) {
        detail::throw_error_at(m.column_where, fmt::format("{}: the run has no column '{}'{} (columns: {})", what, m.column,
                                                           did_you_mean_hint(m.column, cols), fmt::join(cols, ", ")));
      }
      const auto index = static_cast<std::size_t>(it - cols.begin());
      if (index >= probe_size) {
        detail::throw_error_at(
            m.column_where,
            fmt::format("{}: column '{}' is computed at the output times only (multipliers, residuals and "
                        "momenta are not part of the state the steps see); metrics read: {}",
                        what, m.column, fmt::join(cols.begin(), cols.begin() + static_cast<std::ptrdiff_t>(probe_size), ", ")));
      }
      metric_columns.push_back(index);
      using K = MetricSpec::Kind;
      const bool time = m.kind == K::kCrossing || m.kind == K::kPeriod ||
                        (m.kind == K::kExtremum && !m.report_value);
      full_schema.metrics.push_back({m.name, m.unit_given ? m.unit
                                             : time ? std::string(io::unit_of(io::Quantity::kTime))
                                                    : full_schema.columns[index].unit});
    }
  }

  // The unit of a drift's absolute change: the energy's or the Jacobi integral's, or a body's
  // angular momentum's.
  [[nodiscard]] std::string drift_unit(const std::string& drift) const {
    for (const io::Column& c : full_schema.columns) {
      if (c.name == drift ||
          (c.quantity == io::Quantity::kAngularMomentum && c.owner + ".L" == drift)) {
        return c.unit;
      }
    }
    return "";
  }

  // The metrics of a run from the recorder, with their units, and the drifts from the samples:
  // max |x_k − x_0| / |x_0|, or the absolute change with a note when |x_0| is not larger than
  // that change (a relative drift of 1 or more says nothing, and such an x_0 is the round-off of
  // a zero; the report page's error plots use the same rule).
  [[nodiscard]] std::vector<io::Metric> metrics_of(MetricRecorder& recorder,
                                                   const std::vector<std::pair<std::string, std::vector<double>>>& drift) const {
    std::vector<io::Metric> out = recorder.finish();
    for (std::size_t i = 0; i < out.size(); ++i) {
      const MetricSpec& m = scene.output.metrics[i];
      out[i].unit = full_schema.metrics[i].unit;
      if (m.kind != MetricSpec::Kind::kDrift) continue;
      for (const auto& [name, x] : drift) {
        if (name != m.column || x.empty()) continue;
        const double change = max_change(x);
        if (std::abs(x.front()) > change) {
          out[i].value = change / std::abs(x.front());
        } else {
          out[i].value = change;
          out[i].unit = drift_unit(m.column);
          out[i].note = fmt::format("{} at t = 0 ({:.3g}) is not larger than its change: the absolute change",
                                    m.column, x.front());
        }
      }
    }
    return out;
  }

  [[nodiscard]] Method parse_method(const std::string& requested) const;
  RunResult run_coordinates(const Method& method, const RunOptions& o) const;
  RunResult run_free(const Method& method, const RunOptions& o) const;
  // What run() adds to every run's result after it has run (its scene, integrator, times,
  // parameters, warnings, the columns [output] keeps), checked against the schema.
  void finish_run(RunResult& r, const Method& method, double wall_seconds) const;
  // Whether run_batch steps this model with `method` and `o` together with `first` (itself or
  // the batch's first model): see Model::batches.
  [[nodiscard]] bool batches_with(const Impl& first, const Method& method, const RunOptions& o) const;
  struct FreeRun;
};

Model::Model(const Scene& scene) : Model(scene, nullptr) {}

Model::Model(const Scene& scene, const Model& like) : Model(scene, &like) {}

Model::Model(const Scene& scene, const Model* like) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.scene = scene;
  m.kind = scene.is_free_body_scene() ? SceneKind::kFreeBodies : SceneKind::kCoordinates;
  // a prototype records its expressions' results, a model built like it reads them
  auto record = like == nullptr ? std::make_shared<Results>() : nullptr;
  const Impl* prototype = like != nullptr ? like->impl_.get() : nullptr;
  const Evaluator eval(m.params, prototype != nullptr ? &prototype->params : nullptr,
                       prototype != nullptr ? prototype->results.get() : nullptr, record.get());
  for (const Parameter& p : scene.parameters) {
    m.params.push_back({p.name, eval.value(p.value, "parameter " + p.name)});
  }
  m.scene_params = m.params.size();
  m.gravity = eval.vector(scene.gravity, "gravity");
  std::vector<lagrange::Parameter> derived;
  std::vector<std::string> derived_units;
  std::vector<lagrange::BodyMass> masses;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const Body& b = scene.bodies[i];
    SharedMesh prepared;
    if (like != nullptr && b.mass.kind == MassSpec::Kind::kMesh && i < like->impl_->meshes.size() &&
        like->impl_->meshes[i]) {
      const MassSpec& other = like->impl_->scene.bodies[i].mass;
      if (other.kind == MassSpec::Kind::kMesh && other.mesh_file == b.mass.mesh_file &&
          other.units == b.mass.units && other.fill_holes == b.mass.fill_holes) {
        prepared = like->impl_->meshes[i];
      }
    }
    BodyMass bm = mass_of(b, eval, derived, derived_units, m.warnings, prepared);
    m.meshes.push_back(std::move(prepared));
    m.bodies.push_back({b.name, bm.numeric, b.free, bm.sizes, bm.density_field});
    masses.push_back(std::move(bm.symbolic));
  }
  m.params.insert(m.params.end(), derived.begin(), derived.end());
  m.param_units.assign(m.scene_params, "");
  m.param_units.insert(m.param_units.end(), derived_units.begin(), derived_units.end());
  m.read_simulation(eval);
  if (m.kind == SceneKind::kCoordinates && like != nullptr) {
    // the equations of `like`, whose scene differs from this one only in values: checked as far
    // as names go (a scene changed by apply_overrides keeps every name and expression)
    const Impl& l = *like->impl_;
    auto names = [](const std::vector<lagrange::Parameter>& ps) {
      std::vector<std::string> out;
      for (const auto& p : ps) out.push_back(p.name);
      return out;
    };
    auto coordinate_names = [](const Scene& sc) {
      std::vector<std::string> out;
      for (const auto& c : sc.coordinates) out.push_back(c.name);
      return out;
    };
    RIGID_REQUIRE(l.kind == SceneKind::kCoordinates && names(l.params) == names(m.params) &&
                      coordinate_names(l.scene) == coordinate_names(scene) &&
                      l.scene.bodies.size() == scene.bodies.size(),
                  "the scene '{}' differs from the model's it should share equations with in more than values",
                  scene.file.string());
    m.system = l.system;
    m.read_initial_state(eval);
  } else if (m.kind == SceneKind::kCoordinates) {
    m.build_coordinates(masses, eval);
  } else {
    m.build_free_bodies(masses);
  }
  m.results =
      prototype != nullptr ? prototype->results : std::shared_ptr<const Results>(std::move(record));
  m.full_schema = m.make_schema();
  m.check_metrics();
  m.select_columns();
  (void)integrator();  // an unknown [simulation] integrator is an error of the scene
}

Model::~Model() = default;
Model::Model(Model&&) noexcept = default;
Model& Model::operator=(Model&&) noexcept = default;

SceneKind Model::kind() const { return impl_->kind; }
double Model::t_end() const { return impl_->t_end; }
const Scene& Model::scene() const { return impl_->scene; }
const std::vector<lagrange::Parameter>& Model::parameters() const { return impl_->params; }
const std::vector<ModelBody>& Model::bodies() const { return impl_->bodies; }
const std::vector<std::string>& Model::warnings() const { return impl_->warnings; }
const io::RunSchema& Model::schema() const { return impl_->schema; }

const lagrange::System& Model::system() const {
  RIGID_REQUIRE(impl_->system, "a scene of free bodies has no coordinate system");
  return *impl_->system;
}

Method Model::Impl::parse_method(const std::string& requested) const {
  const bool from_scene = requested.empty() && !scene.simulation.integrator.empty();
  Method method;
  method.name = !requested.empty() ? requested
                : from_scene       ? scene.simulation.integrator
                : kind == SceneKind::kCoordinates ? "dopri5"
                                                  : "splitting4";
  try {
    if (kind == SceneKind::kCoordinates) {
      method.coordinates = integrate::parse_method(method.name);
      return method;
    }
    const bool any_top = std::any_of(free.begin(), free.end(), [](const FreeBody& f) { return f.top.has_value(); });
    if (method.name == "exact") {
      if (any_top) {
        throw Error("integrator 'exact' is the closed-form motion of the torque-free body; a body "
                    "on a pivot feels the gravity torque: use splitting2, splitting4 or splitting6");
      }
      method.exact = true;
      return method;
    }
    try {
      method.free = body::free_body_method_from_name(method.name);
    } catch (const Error&) {
      // the scene's list: the closed form "exact" too (not a stepping method of the body module)
      const std::vector<std::string> names = {"exact",      "rk4",      "splitting2", "splitting4",
                                              "splitting6", "midpoint", "rkmk4",      "moser_veselov"};
      throw Error(fmt::format("unknown integrator '{}' for free bodies{}; expected one of exact "
                              "(closed form, no pivot), rk4, splitting2, splitting4, splitting6, "
                              "midpoint, rkmk4, moser_veselov",
                              method.name, did_you_mean_hint(method.name, names)));
    }
    if (any_top) {
      const body::FreeBodyMethod m = method.free;
      if (m != body::FreeBodyMethod::kSplitting2 && m != body::FreeBodyMethod::kSplitting4 &&
          m != body::FreeBodyMethod::kSplitting6) {
        throw Error(fmt::format("integrator '{}' cannot take the gravity torque of a body on a pivot; "
                                "a heavy top is integrated by the gravity-kick splitting around the "
                                "free flow: use splitting2, splitting4 or splitting6",
                                method.name));
      }
    }
  } catch (const Error& e) {
    if (from_scene) {
      detail::throw_error_at(scene.simulation.where,
                             fmt::format("[simulation] integrator: {}", word_for(Surface::kScene, e.what())));
    }
    throw;
  }
  return method;
}

std::string Model::integrator(const std::string& requested) const { return impl_->parse_method(requested).name; }

std::string Model::equations(bool latex) const {
  return equations(latex ? lagrange::EquationFormat::kLatex : lagrange::EquationFormat::kText);
}

std::string Model::equations(lagrange::EquationFormat format) const {
  const Impl& m = *impl_;
  const bool latex = format == lagrange::EquationFormat::kLatex;
  // constants the scene did not write (from mesh files, vertices), named in the equations
  std::string note;
  if (m.params.size() > m.scene_params) {
    note = "where ";
    for (std::size_t k = m.scene_params; k < m.params.size(); ++k) {
      note += fmt::format("{}{} = {:.8g}", k > m.scene_params ? ", " : "", m.params[k].name, m.params[k].value);
    }
    note += " (SI units; computed from the bodies' files, vertices and density fields)";
  }
  if (m.kind == SceneKind::kCoordinates) {
    lagrange::Equations eq = m.system->equations();
    eq.note = note;
    return lagrange::format_equations(eq, format);
  }
  std::string out;
  nlohmann::ordered_json bodies = nlohmann::ordered_json::array();
  for (const FreeBody& f : m.free) {
    lagrange::FreeBodyEquationsSpec spec;
    spec.name = f.name;
    spec.mass = f.symbolic;
    spec.gravity_W = expressions_of(m.scene.gravity);
    if (f.pivot_expressions) {
      spec.has_pivot = true;
      spec.pivot_B = expressions_of(*f.pivot_expressions);
    }
    const Eigen::Vector3d I = f.top ? f.top->principal_moments() : f.rigid->principal_moments();
    const Eigen::Matrix3d R = f.R_BP.matrix();
    const std::string moments = fmt::format("  principal moments about the {} (ascending) I = {} kg·m², axes in B (columns "
                                            "of R_BP): {}, {}, {}",
                                            f.top ? "pivot" : "COM", format_vec(I), format_vec(R.col(0)),
                                            format_vec(R.col(1)), format_vec(R.col(2)));
    if (format == lagrange::EquationFormat::kJson) {
      bodies.push_back({{"name", f.name},
                        {"pivot", f.top.has_value()},
                        {"text", lagrange::free_body_equations(m.params, spec, false)},
                        {"latex", lagrange::free_body_equations(m.params, spec, true)},
                        {"principal_moments", {I.x(), I.y(), I.z()}}});
      continue;
    }
    for (const auto& line : lagrange::free_body_equations(m.params, spec, latex)) out += line + "\n";
    if (!latex) out += moments + "\n";
  }
  if (format == lagrange::EquationFormat::kJson) {
    nlohmann::ordered_json j;
    j["kind"] = io::to_string(SceneKind::kFreeBodies);
    j["bodies"] = bodies;
    if (!note.empty()) j["note"] = note;
    return j.dump(2) + "\n";
  }
  if (!note.empty()) out += (latex ? "% " : "") + note + "\n";
  return out;
}

void Model::check(const RunOptions& options) const {
  const Impl& m = *impl_;
  const Method method = m.parse_method(options.integrator);
  (void)m.check_budget(method, options);
  if (m.kind == SceneKind::kCoordinates) {
    // The run's own start, stopped before it steps: simulate() checks the initial conditions
    // against the constraints, factors the mass matrix and evaluates the right-hand side at
    // t = 0 (a q̈ that is not finite is refused there), the integrator checks its settings and
    // the initial state; the cancel flag, set already, stops the march at its first poll
    // (fixed-step methods: at t = 0, before any step; dopri5: after its first step, the first
    // poll it has). Nothing is integrated further, whatever the output interval or the
    // tolerance.
    lagrange::SimulationOptions so;
    so.method = method.coordinates;
    so.dt = m.dt;
    so.tolerance = m.tolerance;
    so.output_dt = m.output_dt;
    so.t_end = m.t_end;
    so.parameters = m.params;
    const std::atomic<bool> stop{true};
    so.control.cancel = &stop;
    // a failure here is the model's at its start, with the run's settings
    at_location(m.scene.simulation.where, "[simulation] at t = 0", [&] {
      try {
        (void)m.system->simulate(so, m.q0, m.q_dot0);
      } catch (const Cancelled&) {
        // the expected end: the start passed every check, a finite q̈(0) among them
      }
    });
  }
}

RunResult Model::run(const RunOptions& options) const {
  const Method method = impl_->parse_method(options.integrator);
  RunOptions o = options;
  o.control.max_outputs = std::min(o.control.max_outputs, impl_->check_budget(method, options));
  const auto start = Clock::now();
  RunResult r = impl_->kind == SceneKind::kCoordinates ? impl_->run_coordinates(method, o)
                                                       : impl_->run_free(method, o);
  impl_->finish_run(r, method, std::chrono::duration<double>(Clock::now() - start).count());
  return r;
}

void Model::Impl::finish_run(RunResult& r, const Method& method, double wall_seconds) const {
  // The march checks the state after every step; a quantity computed from a finite state can
  // still overflow (the energy ½ m |v|² − m g·p of a body at 1e154 m/s, its change between
  // two samples): refused, never written as a number.
  const auto& data = r.trajectory.data();
  if (const auto i = integrate::first_nonfinite(data)) [[unlikely]] {
    const std::size_t cols = r.trajectory.columns().size(), row = *i / cols;
    throw Error(fmt::format("the output {} at t = {} s is {}, computed from a finite state: it overflowed the "
                            "double range (±1.8e308); check the scene's scales (masses, sizes, gravity, "
                            "velocities)",
                            r.trajectory.columns()[*i % cols], data[row * cols], nonfinite_text(data[*i])));
  }
  for (const auto& [name, value] : r.summary.diagnostics) {
    if (!std::isfinite(value)) [[unlikely]] {
      throw Error(fmt::format("the diagnostic {} is {}, computed from finite outputs: it overflowed the double "
                              "range (±1.8e308); check the scene's scales (masses, sizes, gravity, velocities)",
                              name, nonfinite_text(value)));
    }
  }
  r.summary.wall_seconds = wall_seconds;
  // shown, never opened: a file name of any bytes (0xff) escaped, so that the JSON writer
  // gets UTF-8 (it threw after the whole run, and nothing was written)
  r.summary.scene = escaped(scene.file.string());
  r.summary.integrator = method.name;
  r.summary.t_end = t_end;
  r.summary.samples = r.trajectory.rows();
  for (const auto& p : params) r.summary.parameters.emplace_back(p.name, p.value);
  r.summary.warnings = warnings;
  // the schema is the model's, published before the run: a run that disagreed with it is a defect
  const io::RunSchema& full = full_schema;
  RIGID_REQUIRE(r.trajectory.columns().size() == full.columns.size() &&
                    r.summary.diagnostics.size() == full.diagnostics.size() &&
                    r.summary.metrics.size() == full.metrics.size(),
                "the run's outputs ({} columns, {} diagnostics, {} metrics) differ from its "
                "schema's ({}, {}, {})",
                r.trajectory.columns().size(), r.summary.diagnostics.size(),
                r.summary.metrics.size(), full.columns.size(), full.diagnostics.size(),
                full.metrics.size());
  if (kept.size() != full.columns.size()) r.trajectory = r.trajectory.select(kept);
  r.schema = schema;
}

std::filesystem::path Model::output_directory(const std::string& requested) const {
  if (!requested.empty()) return requested;
  if (!impl_->scene.output.directory.empty()) return impl_->scene.output.directory;
  // one directory per scene: runs of different scenes never mix their files
  const std::string stem = impl_->scene.file.stem().string();
  return std::filesystem::path("out") / (stem.empty() ? std::string("scene") : stem);
}

std::vector<io::OutputFormat> Model::output_formats(const std::vector<std::string>& requested) const {
  const std::vector<std::string>& names = requested.empty() ? impl_->scene.output.formats : requested;
  std::vector<io::OutputFormat> formats;
  for (const std::string& n : names) formats.push_back(io::parse_output_format(n));
  RIGID_REQUIRE(!formats.empty(), "no output format selected; expected csv, npy or json");
  return formats;
}

RunResult Model::Impl::run_coordinates(const Method& method, const RunOptions& o) const {
  lagrange::SimulationOptions so;
  so.method = method.coordinates;
  so.t_end = t_end;
  so.dt = dt;
  so.tolerance = tolerance;
  so.output_dt = output_dt;
  so.control = o.control;
  // metrics: every step's state (and dopri5's dense output inside it) through the probe
  const bool with_metrics = !scene.output.metrics.empty();
  MetricRecorder recorder(scene.output.metrics, metric_columns);
  so.parameters = params;
  lagrange::Workspace probe_workspace = make_workspace();
  const auto nq = static_cast<Eigen::Index>(system->num_coordinates());
  const auto n = static_cast<Eigen::Index>(system->num_velocities());
  std::vector<Eigen::Vector4d> probe_previous(system->body_names().size(), Eigen::Vector4d(1, 0, 0, 0));
  Eigen::VectorXd pq(nq), pqd(n);
  // the leading columns of a row (t, q, q̇, poses, energy, jacobi) at (t, q, q̇)
  auto probe = [&](double t, std::vector<double>& out) {
    out.clear();
    out.push_back(t);
    for (Eigen::Index i = 0; i < nq; ++i) out.push_back(pq[i]);
    for (Eigen::Index i = 0; i < n; ++i) out.push_back(pqd[i]);
    const std::vector<lagrange::BodyPose> poses = system->body_poses(probe_workspace, t, pq);
    for (std::size_t b = 0; b < poses.size(); ++b) push_pose(out, poses[b].p_WB, poses[b].R_WB, probe_previous[b]);
    out.push_back(system->energy(probe_workspace, t, pq, pqd));
    out.push_back(system->jacobi_integral(probe_workspace, t, pq, pqd));
  };
  std::vector<double> values;
  std::vector<double> ybuf(static_cast<std::size_t>(nq + n));
  if (with_metrics) {
    pq = q0;
    pqd = q_dot0;
    probe(0.0, values);
    recorder.start(0.0, values);
    so.control.on_step = [&, outer = o.control.on_step](const integrate::StepView& v) {
      pq = Eigen::Map<const Eigen::VectorXd>(v.y.data(), nq);
      pqd = Eigen::Map<const Eigen::VectorXd>(v.y.data() + nq, n);
      probe(v.t1, values);
      if (v.dense) {
        const MetricProbe dense = [&](double t, std::vector<double>& out) {
          v.dense(t, ybuf);
          pq = Eigen::Map<const Eigen::VectorXd>(ybuf.data(), nq);
          pqd = Eigen::Map<const Eigen::VectorXd>(ybuf.data() + nq, n);
          probe(t, out);
        };
        // dopri5's last step may pass t_end: the run (and its metrics) end at t_end
        if (v.t1 > t_end) dense(t_end, values);
        recorder.step(std::min(v.t1, t_end), values, &dense);
      } else {
        recorder.step(v.t1, values, nullptr);
      }
      if (outer) outer(v);
    };
  }
  const lagrange::Trajectory tr = system->simulate(so, q0, q_dot0);

  RunResult r;
  r.trajectory = io::Table(columns());
  lagrange::Workspace workspace = make_workspace();
  std::vector<Eigen::Vector4d> previous(system->body_names().size(), Eigen::Vector4d(1, 0, 0, 0));
  std::vector<double> row;
  for (Eigen::Index k = 0; k < tr.t.size(); ++k) {
    row.clear();
    row.push_back(tr.t[k]);
    for (Eigen::Index i = 0; i < tr.q.cols(); ++i) row.push_back(tr.q(k, i));
    for (Eigen::Index i = 0; i < tr.q_dot.cols(); ++i) row.push_back(tr.q_dot(k, i));
    const std::vector<lagrange::BodyPose> poses = system->body_poses(workspace, tr.t[k], tr.q.row(k).transpose());
    for (std::size_t b = 0; b < poses.size(); ++b) push_pose(row, poses[b].p_WB, poses[b].R_WB, previous[b]);
    row.push_back(tr.energy[k]);
    row.push_back(tr.jacobi[k]);
    for (Eigen::Index c = 0; c < tr.lambda.cols(); ++c) row.push_back(tr.lambda(k, c));
    if (!tr.constraint_names.empty()) row.push_back(tr.residual[k]);
    for (Eigen::Index c = 0; c < tr.mu.cols(); ++c) row.push_back(tr.mu(k, c));
    if (!tr.velocity_constraint_names.empty()) row.push_back(tr.velocity_constraint_residual[k]);
    for (Eigen::Index c = 0; c < tr.cyclic_momenta.cols(); ++c) row.push_back(tr.cyclic_momenta(k, c));
    r.trajectory.add_row(row);
  }

  RunSummary& s = r.summary;
  s.kind = SceneKind::kCoordinates;
  s.dt = dt;
  s.tolerance = so.method == integrate::Method::kDopri5 ? tolerance : 0.0;
  s.steps = tr.steps;
  s.rhs_evaluations = tr.rhs_evaluations;
  const std::vector<double> energy(tr.energy.data(), tr.energy.data() + tr.energy.size());
  const std::vector<double> jacobi(tr.jacobi.data(), tr.jacobi.data() + tr.jacobi.size());
  s.diagnostics.emplace_back("energy_initial", energy.front());
  s.diagnostics.emplace_back("energy_final", energy.back());
  s.diagnostics.emplace_back("energy_max_change", max_change(energy));
  s.diagnostics.emplace_back("jacobi_max_change", max_change(jacobi));
  if (!tr.constraint_names.empty()) {
    s.diagnostics.emplace_back("constraint_residual_max", tr.residual.maxCoeff());
    s.diagnostics.emplace_back("constraint_velocity_residual_max", tr.velocity_residual.maxCoeff());
  }
  if (!tr.velocity_constraint_names.empty()) {
    s.diagnostics.emplace_back("velocity_constraint_residual_max",
                               tr.velocity_constraint_residual.maxCoeff());
  }
  for (Eigen::Index c = 0; c < tr.cyclic_momenta.cols(); ++c) {
    const Eigen::VectorXd col = tr.cyclic_momenta.col(c);
    s.diagnostics.emplace_back("p_" + tr.cyclic_names[static_cast<std::size_t>(c)] + "_max_change",
                               max_change(std::vector<double>(col.data(), col.data() + col.size())));
  }
  if (with_metrics) s.metrics = metrics_of(recorder, {{"energy", energy}, {"jacobi", jacobi}});
  return r;
}

// One run of a free-body model as it marches: the bodies' state (in P) and what the run
// records from it (the rows, each body's conserved quantity and orthonormality, the energy,
// the metrics). run_free marches one; Model::run_batch marches several through one step.
struct Model::Impl::FreeRun {
  const Impl& m;
  RunResult r;
  std::vector<body::RigidBodyState> state;
  std::vector<std::string> owners;
  // the quaternion sign of the last row (continuity) and of the last metric probe
  std::vector<Eigen::Vector4d> previous, probe_previous;
  // per body: |L| about the COM (free) or g·L about the pivot (top) at each output, and
  // max |RᵀR − 1|; the total energy at each output
  std::vector<std::vector<double>> L;
  std::vector<double> ortho, energy;
  std::vector<double> row, values, conserved;
  Eigen::Vector3d g_dir;
  bool with_metrics;
  MetricRecorder recorder;
  std::string error;  // a batched run that failed: the message its run() would throw

  explicit FreeRun(const Impl& model)
      : m(model),
        previous(model.free.size(), Eigen::Vector4d(1, 0, 0, 0)),
        probe_previous(model.free.size(), Eigen::Vector4d(1, 0, 0, 0)),
        L(model.free.size()),
        ortho(model.free.size(), 0.0),
        conserved(model.free.size()),
        g_dir(model.gravity.norm() > 0 ? Eigen::Vector3d(model.gravity.normalized()) : Eigen::Vector3d::UnitZ()),
        with_metrics(!model.scene.output.metrics.empty()),
        recorder(model.scene.output.metrics, model.metric_columns) {
    r.trajectory = io::Table(m.columns());
    for (const FreeBody& f : m.free) {
      state.push_back(f.initial);
      owners.push_back(fmt::format("body '{}'", f.name));
    }
  }

  // A row of the trajectory from the bodies' state at t; `conserved` gets each body's |L|
  // (free) or g·L (top), the return value is the total energy.
  double fill_row(double t, std::vector<double>& out, std::vector<Eigen::Vector4d>& continuity) {
    out.clear();
    out.push_back(t);
    double e_total = 0;
    for (std::size_t i = 0; i < m.free.size(); ++i) {
      const FreeBody& f = m.free[i];
      const body::RigidBodyState& s = state[i];  // in P
      const SO3d R_WB = f.principal_is_body ? s.R_WB : s.R_WB * f.R_BP.inverse();
      const Eigen::Vector3d w_B = f.principal_is_body ? s.w_B : Eigen::Vector3d(f.R_BP * s.w_B);
      const Eigen::Matrix3d R_WP = s.R_WB.matrix();
      Eigen::Vector3d p_WB, v_WC, L_W;
      if (f.top) {
        const body::FreeBodyState rot{s.R_WB, s.w_B};
        p_WB = f.pivot_W - R_WB * f.pivot_B;
        v_WC = R_WP * s.w_B.cross(f.top->com_from_pivot());
        L_W = R_WP * (f.top->inertia_about_pivot() * s.w_B);  // about the pivot
        e_total += f.top->energy(rot);
        conserved[i] = g_dir.dot(L_W);
      } else {
        // P is principal: I ω is a componentwise product; the energy ½ m |v|² + ½ ωᵀ I ω − m g·p
        // is the library's (RigidBody::energy)
        const Eigen::Vector3d L_P = f.rigid->principal_moments().cwiseProduct(s.w_B);
        p_WB = s.p_WC - R_WB * f.com_B;
        v_WC = s.v_WC;
        L_W = R_WP * L_P;  // about the COM
        e_total += f.rigid->energy(s);
        conserved[i] = L_W.norm();
      }
      push_pose(out, p_WB, R_WB, continuity[i]);
      out.insert(out.end(), {v_WC.x(), v_WC.y(), v_WC.z(), w_B.x(), w_B.y(), w_B.z(), L_W.x(), L_W.y(), L_W.z()});
    }
    out.push_back(e_total);
    return e_total;
  }

  // Output k at its time t.
  void observe(double t) {
    energy.push_back(fill_row(t, row, previous));
    for (std::size_t i = 0; i < m.free.size(); ++i) {
      L[i].push_back(conserved[i]);
      const Eigen::Matrix3d R_WP = state[i].R_WB.matrix();
      ortho[i] = std::max(ortho[i], (R_WP.transpose() * R_WP - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff());
    }
    r.trajectory.add_row(row);
  }

  // Metrics: the state at t = 0, then every step's (fixed steps: interpolated by cubics).
  void start_metrics() {
    (void)fill_row(0.0, values, probe_previous);
    recorder.start(0.0, values);
  }
  void record_step(double t1) {
    (void)fill_row(t1, values, probe_previous);
    recorder.step(t1, values, nullptr);
  }

  [[nodiscard]] std::optional<integrate::NonFinite> find_nonfinite() const {
    for (std::size_t i = 0; i < state.size(); ++i) {
      if (auto bad = body::find_nonfinite(state[i], owners[i])) return bad;
    }
    return std::nullopt;
  }

  // The summary after the last output: `steps` steps taken.
  void summarize(std::size_t steps) {
    RunSummary& s = r.summary;
    s.kind = SceneKind::kFreeBodies;
    s.dt = m.dt;
    s.steps = steps;
    s.diagnostics.emplace_back("energy_initial", energy.front());
    s.diagnostics.emplace_back("energy_final", energy.back());
    s.diagnostics.emplace_back("energy_max_change", max_change(energy));
    for (std::size_t i = 0; i < m.free.size(); ++i) {
      const std::string& n = m.free[i].name;
      s.diagnostics.emplace_back(n + (m.free[i].top ? ".L_vertical_max_change" : ".L_norm_max_change"),
                                 max_change(L[i]));
      s.diagnostics.emplace_back(n + ".orthonormality_max", ortho[i]);
    }
    if (with_metrics) {
      std::vector<std::pair<std::string, std::vector<double>>> drift = {{"energy", energy}};
      for (std::size_t i = 0; i < m.free.size(); ++i) drift.emplace_back(m.free[i].name + ".L", L[i]);
      s.metrics = m.metrics_of(recorder, drift);
    }
  }
};

RunResult Model::Impl::run_free(const Method& method, const RunOptions& o) const {
  FreeRun run(*this);
  const integrate::TimeGrid grid = integrate::TimeGrid::uniform(0.0, t_end, output_dt > 0 ? output_dt : dt);
  auto observe = [&](std::size_t, double t) { run.observe(t); };
  integrate::MarchControl control = o.control;
  if (run.with_metrics) {
    run.start_metrics();
    control.on_step = [&, outer = o.control.on_step](const integrate::StepView& v) {
      run.record_step(v.t1);
      if (outer) outer(v);
    };
  }

  std::size_t steps = 0;
  if (method.exact) {
    // the closed-form rotation (Jacobi elliptic functions) and the COM's parabola, evaluated
    // at each output time
    std::vector<body::FreeBodyMotion> motions;
    for (const FreeBody& f : free) motions.emplace_back(f.rigid->principal_moments(), f.initial.R_WB, f.initial.w_B);
    auto set_state = [&](double t) {
      for (std::size_t i = 0; i < free.size(); ++i) {
        const body::RigidBodyState& s0 = free[i].initial;
        body::RigidBodyState& s = run.state[i];
        s.R_WB = motions[i].orientation(t);
        s.w_B = motions[i].omega_body(t);
        s.p_WC = s0.p_WC + s0.v_WC * t + 0.5 * gravity * t * t;
        s.v_WC = s0.v_WC + gravity * t;
      }
    };
    // the closed form is its own dense output: events between output times are found on it
    const MetricProbe exact = [&](double t, std::vector<double>& out) {
      set_state(t);
      (void)run.fill_row(t, out, run.probe_previous);
    };
    for (std::size_t k = 0; k < grid.size(); ++k) {
      const double t = grid[k];
      if (run.with_metrics) {
        exact(t, run.values);
        run.recorder.step(t, run.values, &exact);
      }
      set_state(t);
      observe(k, t);
      integrate::poll(o.control, t);
    }
  } else {
    // every body by its library model: a rigid body's kick–drift–kick (the kick is exact for
    // gravity alone, the drift's rotation is the free-body method), a top's gravity splitting
    auto step = [&](double t, double h) {
      for (std::size_t i = 0; i < free.size(); ++i) {
        const FreeBody& f = free[i];
        body::RigidBodyState& s = run.state[i];
        if (f.top) {
          const body::FreeBodyState next = f.top->step({s.R_WB, s.w_B}, h, method.free);
          s.R_WB = next.R_WB;
          s.w_B = next.w_B;
        } else {
          s = body::step_rigid_body(*f.rigid, body::RigidBodyMethod::kSplitting2, t, s, h, method.free);
        }
      }
    };
    steps = integrate::march(grid, dt, step, [&] { return run.find_nonfinite(); }, observe, control).steps;
  }
  run.summarize(steps);
  return std::move(run.r);
}

bool Model::Impl::batches_with(const Impl& first, const Method& method, const RunOptions& o) const {
  const bool splitting = method.free == body::FreeBodyMethod::kSplitting2 ||
                         method.free == body::FreeBodyMethod::kSplitting4 ||
                         method.free == body::FreeBodyMethod::kSplitting6;
  if (kind != SceneKind::kFreeBodies || method.exact || !splitting || o.control.on_step || o.control.progress) {
    return false;
  }
  // one grid and one step for the whole batch
  if (t_end != first.t_end || dt != first.dt || output_dt != first.output_dt) return false;
  // bodies in uniform gravity alone (a kick is v += ½h g), stepped in their principal frame
  // as they are, from a finite state (the step's input checks pass: a run with a non-finite
  // start is run alone, where its error is raised)
  return std::all_of(free.begin(), free.end(), [](const FreeBody& f) {
    const body::RigidBodyState& s = f.initial;
    return !f.top && f.rigid && f.rigid->load_count() == 0 &&
           f.rigid->principal_axes().quaternion() == Eigen::Vector4d(1, 0, 0, 0) &&
           std::isfinite(s.R_WB.quaternion().sum() + s.w_B.sum() + s.p_WC.sum() + s.v_WC.sum());
  });
}

bool Model::batches(const RunOptions& options) const {
  try {
    return impl_->batches_with(*impl_, impl_->parse_method(options.integrator), options);
  } catch (const Error&) {
    return false;  // an unknown integrator: its run refuses it
  }
}

namespace {

// Thrown inside a batch's march when every run of it has failed: nothing is left to step.
struct BatchEmpty {};

}  // namespace

std::vector<Model::BatchedRun> Model::run_batch(std::span<const Model* const> models, const RunOptions& options) {
  std::vector<BatchedRun> out(models.size());
  // together when every model's method is the first's and batches with it (an unknown
  // integrator: one by one, where each run refuses it)
  const auto method_of = [&](const Model* m) -> std::optional<Method> {
    try {
      return m->impl_->parse_method(options.integrator);
    } catch (const Error&) {
      return std::nullopt;
    }
  };
  const std::optional<Method> common = models.empty() ? std::nullopt : method_of(models[0]);
  const bool together = models.size() > 1 && common && std::all_of(models.begin(), models.end(), [&](const Model* m) {
    const std::optional<Method> a = method_of(m);
    return a && a->name == common->name && a->free == common->free &&
           m->impl_->batches_with(*models[0]->impl_, *a, options);
  });
  if (!together) {
    for (std::size_t i = 0; i < models.size(); ++i) {
      try {
        out[i].result = models[i]->run(options);
      } catch (const Cancelled&) {
        throw;
      } catch (const Error& e) {
        out[i].error = e.what();
      }
    }
    return out;
  }

  const Impl& first = *models[0]->impl_;
  const Method& method = *common;
  // each run's own start, as run() makes it: the memory and step budget
  std::vector<std::unique_ptr<Impl::FreeRun>> runs(models.size());
  std::vector<Impl::FreeRun*> active;
  for (std::size_t i = 0; i < models.size(); ++i) {
    try {
      (void)models[i]->impl_->check_budget(method, options);
      runs[i] = std::make_unique<Impl::FreeRun>(*models[i]->impl_);
      if (runs[i]->with_metrics) runs[i]->start_metrics();
      active.push_back(runs[i].get());
    } catch (const Cancelled&) {
      throw;
    } catch (const Error& e) {
      out[i].error = e.what();
      runs[i].reset();
    }
  }
  const auto start = Clock::now();

  // The step of step_rigid_body (kSplitting2: kick ½h, drift h, kick ½h; gravity alone, so a
  // kick is v += ½h g) for every body of every active run, with the drift's rotations in one
  // call of the batch kernel (blocks of four bodies in vector registers), whose results are
  // the bits of step_free_body: each run's rows are those of its run() alone.
  std::vector<Eigen::Vector3d> moments;
  std::vector<body::FreeBodyState> rotations;
  auto gather_moments = [&] {
    moments.clear();
    for (const Impl::FreeRun* run : active) {
      for (const FreeBody& f : run->m.free) moments.push_back(f.rigid->principal_moments());
    }
    rotations.resize(moments.size());
  };
  gather_moments();
  double last_h = 0;
  auto step = [&](double, double h) {
    last_h = h;
    const double tau = 0.5 * h;
    std::size_t k = 0;
    for (Impl::FreeRun* run : active) {
      for (std::size_t i = 0; i < run->state.size(); ++i) {
        body::RigidBodyState& s = run->state[i];
        s.v_WC += tau * run->m.free[i].rigid->gravity();
        s.p_WC += h * s.v_WC;
        rotations[k++] = {s.R_WB, s.w_B};
      }
    }
    try {
      body::step_free_bodies(method.free, moments, rotations, h);
    } catch (const Error&) {
      // a body's rotation diverged (every body has been stepped): its run finds the
      // component below and fails, as its run() would
    }
    k = 0;
    for (Impl::FreeRun* run : active) {
      for (std::size_t i = 0; i < run->state.size(); ++i) {
        body::RigidBodyState& s = run->state[i];
        s.R_WB = rotations[k].R_WB;
        s.w_B = rotations[k].w_B;
        ++k;
        s.v_WC += tau * run->m.free[i].rigid->gravity();
      }
    }
  };
  // a run that fails leaves the batch; the others go on
  auto leave = [&](std::vector<Impl::FreeRun*>& left) {
    if (left.empty()) return;
    std::erase_if(active, [&](const Impl::FreeRun* r) { return std::find(left.begin(), left.end(), r) != left.end(); });
    left.clear();
    if (active.empty()) throw BatchEmpty{};
    gather_moments();
  };
  std::vector<Impl::FreeRun*> left;
  std::size_t steps = 0;
  integrate::MarchControl control = options.control;
  // after every step: each run's finiteness check (march's, with its message) and its metrics
  control.on_step = [&](const integrate::StepView& v) {
    ++steps;
    for (Impl::FreeRun* run : active) {
      if (auto bad = run->find_nonfinite()) [[unlikely]] {
        run->error = integrate::nonfinite_message(*bad, steps, v.t1, last_h);
        left.push_back(run);
      } else if (run->with_metrics) {
        try {
          run->record_step(v.t1);
        } catch (const Error& e) {
          run->error = e.what();
          left.push_back(run);
        }
      }
    }
    leave(left);
  };
  auto observe = [&](std::size_t, double t) {
    for (Impl::FreeRun* run : active) {
      try {
        run->observe(t);
      } catch (const Error& e) {
        run->error = e.what();
        left.push_back(run);
      }
    }
    leave(left);
  };
  const integrate::TimeGrid grid =
      integrate::TimeGrid::uniform(0.0, first.t_end, first.output_dt > 0 ? first.output_dt : first.dt);
  try {
    if (active.empty()) throw BatchEmpty{};
    steps = integrate::march(grid, first.dt, step, [] { return std::optional<integrate::NonFinite>{}; }, observe,
                             control)
                .steps;
  } catch (const BatchEmpty&) {
    // every run failed
  } catch (const Cancelled&) {
    throw;
  } catch (const Error& e) {
    for (Impl::FreeRun* run : active) run->error = e.what();  // the march's own refusal: every run's
    active.clear();
  }
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  for (std::size_t i = 0; i < models.size(); ++i) {
    if (!runs[i]) continue;
    Impl::FreeRun& run = *runs[i];
    if (std::find(active.begin(), active.end(), &run) == active.end()) {
      out[i].error = run.error;
      continue;
    }
    try {
      run.summarize(steps);
      models[i]->impl_->finish_run(run.r, method, wall);
      out[i].result = std::move(run.r);
    } catch (const Error& e) {
      out[i].error = e.what();
    }
  }
  return out;
}

Model load_model(const std::filesystem::path& file, const std::vector<std::string>& overrides,
                 const ModelOptions& model) {
  Scene s = load_scene(file, model);
  apply_overrides(s, overrides);
  return Model(s);
}

}  // namespace rigid::scene
