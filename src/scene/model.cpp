#include "rigid/scene/model.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fnmatch.h>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "rigid/body/free_body_exact.hpp"
#include "rigid/body/free_body_integrators.hpp"
#include "rigid/body/heavy_top.hpp"
#include "rigid/common/error.hpp"
#include "rigid/mass/primitive_table.hpp"
#include "rigid/mass/primitives.hpp"
#include "rigid/mesh/mass_from_file.hpp"
#include "rigid/mesh/read_mesh.hpp"

namespace rigid::scene {
namespace {

using Clock = std::chrono::steady_clock;

// A scene expression for the Lagrangian engine: positions inside it map to the file.
lagrange::Expression to_lagrange(const Expression& e) { return {e.text, e.at(0)}; }

// Rethrows an error of a library call at a position of the scene file, unless the error
// already names a position in that file (expressions report their own column).
template <typename F>
auto at_location(const SourceLocation& where, const std::string& context, F&& f) {
  try {
    return f();
  } catch (const Error& e) {
    const std::string_view what = e.what();
    if (!where.file.empty() && what.starts_with(where.file + ":")) throw;
    detail::throw_error_at(where, fmt::format("{}: {}", context, what));
  }
}

double value_of(const Expression& e, const std::vector<lagrange::Parameter>& params,
                const std::string& what) {
  if (e.number) return *e.number;
  return lagrange::evaluate_constant(to_lagrange(e), params, what);
}

Eigen::Vector3d vector_of(const std::array<Expression, 3>& e,
                          const std::vector<lagrange::Parameter>& params, const std::string& what) {
  return {value_of(e[0], params, what), value_of(e[1], params, what), value_of(e[2], params, what)};
}

MassProperties mass_of(const Body& b, const std::vector<lagrange::Parameter>& params,
                       std::vector<std::string>& warnings) {
  const MassSpec& m = b.mass;
  const std::string ctx = fmt::format("body '{}'", b.name);
  switch (m.kind) {
    case MassSpec::Kind::kPrimitive: {
      std::vector<std::pair<std::string, double>> sizes;
      for (const auto& [key, e] : m.dimensions) sizes.emplace_back(key, value_of(e, params, ctx + " " + key));
      const bool by_mass = m.mass.has_value();
      const double amount = value_of(by_mass ? *m.mass : *m.density, params,
                                     ctx + (by_mass ? " mass" : " density"));
      return at_location(m.where, ctx, [&] {
        return mass::make_primitive(m.primitive, by_mass ? mass::Amount::kMass : mass::Amount::kDensity,
                                    amount, sizes);
      });
    }
    case MassSpec::Kind::kMesh: {
      mesh::MassSpec spec;
      if (m.mass) spec.mass = value_of(*m.mass, params, ctx + " mass");
      if (m.density) spec.density = value_of(*m.density, params, ctx + " density");
      return at_location(m.where, ctx, [&] {
        const mesh::MeshFileMass r = mesh::mesh_mass_from_file(m.mesh_file.string(), mesh::unit_scale(m.units), spec);
        for (const auto& w : r.repair.warnings) warnings.push_back(fmt::format("{}: {}", ctx, w));
        for (const auto& w : r.mass.warnings) warnings.push_back(fmt::format("{}: {}", ctx, w));
        return r.mass.properties;
      });
    }
    case MassSpec::Kind::kExplicit: {
      const double mass = value_of(*m.mass, params, ctx + " inertia mass");
      const Eigen::Vector3d com = vector_of(m.com, params, ctx + " inertia com");
      std::array<double, 6> v{};
      const char* names[6] = {"ixx", "iyy", "izz", "ixy", "ixz", "iyz"};
      for (std::size_t i = 0; i < 6; ++i) v[i] = value_of(m.inertia[i], params, ctx + " " + names[i]);
      Eigen::Matrix3d I;
      I << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
      return at_location(m.where, ctx, [&] { return MassProperties(mass, com, I); });
    }
    case MassSpec::Kind::kPointMasses: {
      std::vector<double> masses;
      Eigen::Matrix3Xd points(3, static_cast<Eigen::Index>(m.points.size()));
      for (std::size_t i = 0; i < m.points.size(); ++i) {
        masses.push_back(value_of(m.points[i].mass, params, ctx + " point mass"));
        points.col(static_cast<Eigen::Index>(i)) = vector_of(m.points[i].position, params, ctx + " point position");
      }
      return at_location(m.where, ctx, [&] { return mass::point_masses(masses, points); });
    }
  }
  RIGID_THROW("unreachable mass kind");
}

// A free body integrated in its principal frame P (B → P by R_BP).
struct FreeModel {
  std::string name;
  double mass = 0;
  Eigen::Vector3d I_P = Eigen::Vector3d::Ones();  // principal moments (about COM or pivot)
  Eigen::Quaterniond q_BP = Eigen::Quaterniond::Identity();
  Eigen::Vector3d p_BC = Eigen::Vector3d::Zero();  // COM in B
  bool top = false;                                // pivot: heavy top
  Eigen::Vector3d pivot_B = Eigen::Vector3d::Zero();
  Eigen::Vector3d pivot_W = Eigen::Vector3d::Zero();
  body::HeavyTop heavy;
  // initial state
  body::FreeBodyState rot0;  // q_WP, w_P
  Eigen::Vector3d p_WC0 = Eigen::Vector3d::Zero(), v_WC0 = Eigen::Vector3d::Zero();
};

std::string format_vec(const Eigen::Vector3d& v) { return fmt::format("({:.10g}, {:.10g}, {:.10g})", v.x(), v.y(), v.z()); }

}  // namespace

struct Model::Impl {
  Scene scene;
  SceneKind kind = SceneKind::kCoordinates;
  std::vector<lagrange::Parameter> params;
  std::vector<ModelBody> bodies;
  std::vector<std::string> warnings;
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();
  // simulation settings (validated)
  double t_end = 0, dt = 1e-3, tolerance = 1e-9, output_dt = 0;
  // coordinates
  std::unique_ptr<lagrange::System> system;
  // free bodies
  std::vector<FreeModel> free;

  void read_simulation() {
    const Simulation& s = scene.simulation;
    auto positive = [&](const Expression& e, const char* what, const char* unit) {
      const double v = value_of(e, params, std::string("[simulation] ") + what);
      if (!(v > 0)) {
        detail::throw_error_at(e.where, fmt::format("[simulation] {} must be positive, got {} {}", what, v, unit));
      }
      return v;
    };
    t_end = positive(s.t_end, "t_end", "s");
    if (s.dt) dt = positive(*s.dt, "dt", "s");
    if (s.tolerance) tolerance = positive(*s.tolerance, "tolerance", "");
    if (s.output_dt) output_dt = positive(*s.output_dt, "output_dt", "s");
    if (output_dt > t_end) {
      detail::throw_error_at(s.output_dt->where, fmt::format("[simulation] output_dt = {} s is longer than "
                                                              "t_end = {} s; expected at most t_end",
                                                              output_dt, t_end));
    }
  }

  void build_coordinates() {
    lagrange::SystemSpec spec;
    spec.parameters = params;
    for (const Coordinate& c : scene.coordinates) {
      spec.coordinates.push_back({c.name, value_of(c.initial, params, c.name + " initial"),
                                  value_of(c.velocity, params, c.name + " velocity")});
    }
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const Body& b = scene.bodies[i];
      lagrange::Body lb{b.name, bodies[i].mass, {}, {}};
      for (int k = 0; k < 3; ++k) lb.position[static_cast<std::size_t>(k)] = to_lagrange(b.position[static_cast<std::size_t>(k)]);
      for (const AxisRotation& r : b.rotations) {
        lb.rotations.push_back({Eigen::Vector3d(r.axis[0], r.axis[1], r.axis[2]), to_lagrange(r.angle)});
      }
      spec.bodies.push_back(std::move(lb));
    }
    spec.gravity_W = gravity;
    for (const auto& p : scene.potentials) spec.potentials.push_back({p.name, to_lagrange(p.expression)});
    for (const auto& f : scene.forces) spec.forces.push_back({f.name, to_lagrange(f.expression)});
    for (const auto& c : scene.constraints) spec.constraints.push_back({c.name, to_lagrange(c.expression)});
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
    system = std::make_unique<lagrange::System>(at_location(whole, "the equations of motion", [&] {
      return lagrange::System(spec);
    }));
  }

  void build_free_bodies() {
    if (!scene.springs.empty()) {
      detail::throw_error_at(scene.springs.front().where,
                             "springs between free bodies are not simulated; pose the bodies by "
                             "[[coordinates]] to connect them with springs");
    }
    if (!scene.constraints.empty() || !scene.potentials.empty() || !scene.forces.empty()) {
      detail::throw_error_at({scene.file.string(), 0, 0},
                             "[[constraints]], [[potentials]] and [[forces]] act on coordinates; a "
                             "scene of free bodies has none");
    }
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const Body& b = scene.bodies[i];
      const MassProperties& mp = bodies[i].mass;
      FreeModel f;
      f.name = b.name;
      f.mass = mp.mass();
      f.p_BC = mp.com();
      const Eigen::Quaterniond q_WB0(b.initial_orientation[0], b.initial_orientation[1],
                                     b.initial_orientation[2], b.initial_orientation[3]);
      const Eigen::Vector3d p_WB0(b.initial_position[0], b.initial_position[1], b.initial_position[2]);
      const Eigen::Vector3d w_B0(b.angular_velocity[0], b.angular_velocity[1], b.angular_velocity[2]);
      const Eigen::Vector3d v0(b.initial_velocity[0], b.initial_velocity[1], b.initial_velocity[2]);
      Eigen::Matrix3d I_about = mp.inertia_com();
      if (b.pivot) {
        f.top = true;
        f.pivot_B = Eigen::Vector3d((*b.pivot)[0], (*b.pivot)[1], (*b.pivot)[2]);
        I_about = mp.inertia_about(f.pivot_B);
        f.pivot_W = p_WB0 + q_WB0 * f.pivot_B;
        if (v0.norm() != 0) {
          detail::throw_error_at(b.where, fmt::format("body '{}' turns about its pivot, so its COM "
                                                      "velocity follows from angular_velocity; "
                                                      "remove initial_velocity",
                                                      b.name));
        }
      }
      const PrincipalAxes pa = MassProperties(mp.mass(), Eigen::Vector3d::Zero(), I_about).principal_axes();
      if (!(pa.moments.minCoeff() > 1e-12 * pa.moments.sum())) {
        detail::throw_error_at(
            b.where, fmt::format("free body '{}' has principal moments {} kg·m² about its {}: a "
                                 "zero moment (a point mass or a thin rod) leaves its rotation "
                                 "undefined; give it a finite size",
                                 b.name, format_vec(pa.moments), f.top ? "pivot" : "COM"));
      }
      f.I_P = pa.moments;
      f.q_BP = Eigen::Quaterniond(pa.R_BP);
      f.rot0.q_WB = (q_WB0 * f.q_BP).normalized();
      f.rot0.w_B = f.q_BP.conjugate() * w_B0;
      f.p_WC0 = p_WB0 + q_WB0 * f.p_BC;
      f.v_WC0 = v0;
      if (f.top) {
        f.heavy.mass = f.mass;
        f.heavy.I_B = f.I_P;
        f.heavy.p_PC_B = f.q_BP.conjugate() * (f.p_BC - f.pivot_B);
        f.heavy.g_W = gravity;
        f.v_WC0 = q_WB0 * w_B0.cross(f.p_BC - f.pivot_B);
      }
      free.push_back(f);
    }
  }

  std::vector<double> output_times() const {
    const double spacing = output_dt > 0 ? output_dt : dt;
    std::vector<double> times;
    const auto n = static_cast<std::size_t>(std::floor(t_end / spacing * (1 + 1e-12)));
    for (std::size_t k = 0; k <= n; ++k) times.push_back(std::min(t_end, static_cast<double>(k) * spacing));
    if (t_end - times.back() > 1e-12 * t_end) times.push_back(t_end);
    return times;
  }

  RunResult run_coordinates(const std::string& method, const RunOptions& o) const;
  RunResult run_free(const std::string& method, const RunOptions& o) const;
};

Model::Model(const Scene& scene) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.scene = scene;
  m.kind = scene.is_free_body_scene() ? SceneKind::kFreeBodies : SceneKind::kCoordinates;
  for (const Parameter& p : scene.parameters) {
    m.params.push_back({p.name, value_of(p.value, m.params, "parameter " + p.name)});
  }
  m.gravity = vector_of(scene.gravity, m.params, "gravity");
  for (const Body& b : scene.bodies) m.bodies.push_back({b.name, mass_of(b, m.params, m.warnings), b.free});
  m.read_simulation();
  if (m.kind == SceneKind::kCoordinates) {
    m.build_coordinates();
  } else {
    m.build_free_bodies();
  }
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

const lagrange::System& Model::system() const {
  RIGID_REQUIRE(impl_->system, "a scene of free bodies has no coordinate system");
  return *impl_->system;
}

std::string Model::integrator(const std::string& requested) const {
  const Impl& m = *impl_;
  const bool from_scene = requested.empty() && !m.scene.simulation.integrator.empty();
  const std::string name = !requested.empty() ? requested
                           : from_scene       ? m.scene.simulation.integrator
                           : m.kind == SceneKind::kCoordinates ? "dopri5"
                                                               : "splitting4";
  try {
    if (m.kind == SceneKind::kCoordinates) {
      (void)integrate::parse_method(name);
    } else {
      const bool any_top = std::any_of(m.free.begin(), m.free.end(), [](const FreeModel& f) { return f.top; });
      if (name == "exact") {
        RIGID_REQUIRE(!any_top, "integrator 'exact' is the closed-form motion of the torque-free "
                      "body; a body on a pivot feels the gravity torque: use splitting2, "
                      "splitting4 or splitting6");
        return name;
      }
      const body::FreeBodyMethod method = body::free_body_method_from_name(name);
      if (any_top && method != body::FreeBodyMethod::kSplitting2 &&
          method != body::FreeBodyMethod::kSplitting4 && method != body::FreeBodyMethod::kSplitting6) {
        RIGID_THROW("integrator '{}' cannot take the gravity torque of a body on a pivot; a heavy "
                    "top is integrated by the gravity-kick splitting around the free flow: use "
                    "splitting2, splitting4 or splitting6",
                    name);
      }
    }
  } catch (const Error& e) {
    if (from_scene) detail::throw_error_at(m.scene.simulation.where, fmt::format("[simulation] integrator: {}", e.what()));
    throw;
  }
  return name;
}

std::string Model::equations(bool latex) const {
  const Impl& m = *impl_;
  std::string out;
  if (m.kind == SceneKind::kCoordinates) {
    const lagrange::Equations eq = m.system->equations();
    out += latex ? fmt::format("L = {}\n", eq.lagrangian_latex) : fmt::format("L = {}\n", eq.lagrangian_text);
    for (const auto& line : latex ? eq.latex : eq.text) out += line + "\n";
    for (const auto& line : latex ? eq.constraints_latex : eq.constraints_text) out += line + "\n";
    if (!latex) {
      out += fmt::format("energy (Jacobi integral) h = {}\n", eq.energy_text);
      if (!eq.cyclic.empty()) out += fmt::format("cyclic coordinates: {}\n", fmt::join(eq.cyclic, ", "));
    }
    return out;
  }
  for (const FreeModel& f : m.free) {
    const Eigen::Vector3d& I = f.I_P;
    const Eigen::Matrix3d R_BP = f.q_BP.toRotationMatrix();
    if (latex) {
      out += fmt::format("% body {}: principal frame P, I = \\mathrm{{diag}}({:.10g}, {:.10g}, {:.10g})\n", f.name, I[0], I[1], I[2]);
      const char* tau = f.top ? " + \\tau_{{{}}}" : "";
      for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3, k = (i + 2) % 3;
        out += fmt::format("{:.10g}\\,\\dot\\omega_{} = ({:.10g})\\,\\omega_{}\\,\\omega_{}{}\n", I[i], i + 1,
                           I[j] - I[k], j + 1, k + 1, f.top ? fmt::format(fmt::runtime(tau), i + 1) : "");
      }
      out += "\\dot R_{WP} = R_{WP}\\,[\\omega]_\\times\n";
      if (f.top) {
        out += fmt::format("\\tau = {:.10g}\\, p_{{PC}} \\times (R_{{WP}}^T g),\\quad p_{{PC}} = ({:.10g}, {:.10g}, {:.10g})\n",
                           f.mass, f.heavy.p_PC_B.x(), f.heavy.p_PC_B.y(), f.heavy.p_PC_B.z());
      } else {
        out += fmt::format("{:.10g}\\,\\ddot c = {:.10g}\\,({:.10g}, {:.10g}, {:.10g})\n", f.mass, f.mass,
                           m.gravity.x(), m.gravity.y(), m.gravity.z());
      }
      continue;
    }
    out += fmt::format("body '{}' ({}): mass {:.10g} kg, principal moments about the {} I = {} kg·m²\n",
                       f.name, f.top ? fmt::format("heavy top on the pivot {} of B", format_vec(f.pivot_B)) : "free",
                       f.mass, f.top ? "pivot" : "COM", format_vec(I));
    out += fmt::format("  principal axes in the body frame B (columns of R_BP): {}, {}, {}\n",
                       format_vec(R_BP.col(0)), format_vec(R_BP.col(1)), format_vec(R_BP.col(2)));
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      out += fmt::format("  {:.10g} w{}_dot = ({:.10g}) w{} w{}{}\n", I[i], i + 1, I[j] - I[k], j + 1, k + 1,
                         f.top ? fmt::format(" + tau{}", i + 1) : "");
    }
    out += "  R_WP_dot = R_WP [w]x   (w = (w1, w2, w3) in the principal frame, rad/s)\n";
    if (f.top) {
      out += fmt::format("  tau = m p_PC x (R_WP^T g) with m = {:.10g} kg, p_PC = {} m, g = {} m/s²\n", f.mass,
                         format_vec(f.heavy.p_PC_B), format_vec(m.gravity));
    } else {
      out += fmt::format("  {:.10g} c_ddot = {:.10g} g with g = {} m/s² (the COM c moves on a parabola)\n",
                         f.mass, f.mass, format_vec(m.gravity));
    }
  }
  return out;
}

void Model::check(const RunOptions& options) const {
  const Impl& m = *impl_;
  const std::string method = integrator(options.integrator);
  if (m.kind == SceneKind::kCoordinates) {
    // one output interval runs every check of a full run: initial consistency, the mass
    // matrix, the step and output spacing
    lagrange::SimulationOptions so;
    so.method = integrate::parse_method(method);
    so.dt = m.dt;
    so.tolerance = m.tolerance;
    so.output_dt = m.output_dt;
    so.t_end = m.output_dt > 0 ? m.output_dt : std::min(m.t_end, m.dt);
    (void)m.system->simulate(so);
  }
}

namespace {

// The columns of `table` that match one of `patterns` (shell patterns, fnmatch), with `t`
// first. A pattern that matches nothing is an error that lists the columns.
io::Table select_columns(const io::Table& table, const std::vector<std::string>& patterns,
                         const SourceLocation& where) {
  const auto& cols = table.columns();
  std::vector<bool> keep(cols.size(), false);
  keep[0] = true;  // t
  for (const std::string& p : patterns) {
    bool any = false;
    for (std::size_t c = 0; c < cols.size(); ++c) {
      if (fnmatch(p.c_str(), cols[c].c_str(), 0) == 0) keep[c] = any = true;
    }
    if (!any) {
      std::string msg = fmt::format("[output] quantities: '{}' matches no column", p);
      if (auto g = did_you_mean(p, cols)) msg += fmt::format("; did you mean '{}'?", *g);
      detail::throw_error_at(where, msg + fmt::format(" (columns: {})", fmt::join(cols, ", ")));
    }
  }
  std::vector<std::string> names;
  for (std::size_t c = 0; c < cols.size(); ++c) {
    if (keep[c]) names.push_back(cols[c]);
  }
  io::Table out(names);
  std::vector<double> row;
  for (std::size_t k = 0; k < table.rows(); ++k) {
    row.clear();
    for (std::size_t c = 0; c < cols.size(); ++c) {
      if (keep[c]) row.push_back(table(k, c));
    }
    out.add_row(row);
  }
  return out;
}

}  // namespace

RunResult Model::run(const RunOptions& options) const {
  const std::string method = integrator(options.integrator);
  const auto start = Clock::now();
  RunResult r = impl_->kind == SceneKind::kCoordinates ? impl_->run_coordinates(method, options)
                                                       : impl_->run_free(method, options);
  r.summary.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  r.summary.integrator = method;
  r.summary.t_end = impl_->t_end;
  r.summary.samples = r.trajectory.rows();
  for (const auto& p : impl_->params) r.summary.parameters.emplace_back(p.name, p.value);
  r.summary.warnings = impl_->warnings;
  const Output& out = impl_->scene.output;
  if (!out.quantities.empty()) r.trajectory = select_columns(r.trajectory, out.quantities, out.quantities_where);
  return r;
}

namespace {

void add_pose_columns(std::vector<std::string>& cols, const std::string& body) {
  for (const char* c : {"x", "y", "z", "qw", "qx", "qy", "qz"}) cols.push_back(body + "." + c);
}

// Appends p and q (sign chosen to continue `previous`, so the columns are continuous).
void push_pose(std::vector<double>& row, const Eigen::Vector3d& p, Eigen::Quaterniond q,
               Eigen::Quaterniond& previous) {
  if (q.coeffs().dot(previous.coeffs()) < 0) q.coeffs() = -q.coeffs();
  previous = q;
  row.insert(row.end(), {p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z()});
}

// Largest |x_k − x_0| over the samples.
double max_change(const Eigen::VectorXd& x) {
  return x.size() ? (x.array() - x[0]).abs().maxCoeff() : 0.0;
}

}  // namespace

RunResult Model::Impl::run_coordinates(const std::string& method, const RunOptions& o) const {
  lagrange::SimulationOptions so;
  so.method = integrate::parse_method(method);
  so.t_end = t_end;
  so.dt = dt;
  so.tolerance = tolerance;
  so.output_dt = output_dt;
  so.progress = o.progress;
  const lagrange::Trajectory tr = system->simulate(so);

  std::vector<std::string> cols{"t"};
  for (const auto& c : tr.coordinate_names) cols.push_back(c);
  for (const auto& c : tr.coordinate_names) cols.push_back(c + "_dot");
  for (const auto& b : system->body_names()) add_pose_columns(cols, b);
  cols.push_back("energy");
  cols.push_back("jacobi");
  for (const auto& c : tr.constraint_names) cols.push_back("lambda_" + c);
  if (!tr.constraint_names.empty()) cols.push_back("constraint_residual");
  for (const auto& c : tr.cyclic_names) cols.push_back("p_" + c);

  RunResult r;
  r.trajectory = io::Table(cols);
  std::vector<Eigen::Quaterniond> previous(system->body_names().size(), Eigen::Quaterniond::Identity());
  std::vector<double> row;
  for (Eigen::Index k = 0; k < tr.t.size(); ++k) {
    row.clear();
    row.push_back(tr.t[k]);
    for (Eigen::Index i = 0; i < tr.q.cols(); ++i) row.push_back(tr.q(k, i));
    for (Eigen::Index i = 0; i < tr.q.cols(); ++i) row.push_back(tr.q_dot(k, i));
    const std::vector<lagrange::BodyPose> poses = system->body_poses(tr.t[k], tr.q.row(k).transpose());
    for (std::size_t b = 0; b < poses.size(); ++b) push_pose(row, poses[b].p_WB, poses[b].q_WB, previous[b]);
    row.push_back(tr.energy[k]);
    row.push_back(tr.jacobi[k]);
    for (Eigen::Index c = 0; c < tr.lambda.cols(); ++c) row.push_back(tr.lambda(k, c));
    if (!tr.constraint_names.empty()) row.push_back(tr.residual[k]);
    for (Eigen::Index c = 0; c < tr.cyclic_momenta.cols(); ++c) row.push_back(tr.cyclic_momenta(k, c));
    r.trajectory.add_row(row);
  }

  RunSummary& s = r.summary;
  s.kind = "coordinates";
  s.dt = dt;
  s.tolerance = so.method == integrate::Method::kDopri5 ? tolerance : 0.0;
  s.steps = tr.steps;
  s.rhs_evaluations = tr.rhs_evaluations;
  const double e0 = tr.energy.size() ? tr.energy[0] : 0.0;
  s.diagnostics.emplace_back("energy_initial", e0);
  s.diagnostics.emplace_back("energy_final", tr.energy.size() ? tr.energy[tr.energy.size() - 1] : 0.0);
  s.diagnostics.emplace_back("energy_max_change", max_change(tr.energy));
  s.diagnostics.emplace_back("jacobi_max_change", max_change(tr.jacobi));
  if (!tr.constraint_names.empty()) {
    s.diagnostics.emplace_back("constraint_residual_max", tr.residual.maxCoeff());
    s.diagnostics.emplace_back("constraint_velocity_residual_max", tr.velocity_residual.maxCoeff());
  }
  for (Eigen::Index c = 0; c < tr.cyclic_momenta.cols(); ++c) {
    s.diagnostics.emplace_back("p_" + tr.cyclic_names[static_cast<std::size_t>(c)] + "_max_change",
                               max_change(tr.cyclic_momenta.col(c)));
  }
  return r;
}

RunResult Model::Impl::run_free(const std::string& method_name, const RunOptions& o) const {
  // "exact": the closed-form rotation (Jacobi elliptic functions), evaluated at each output
  // time; otherwise a stepping method
  const bool exact = method_name == "exact";
  const body::FreeBodyMethod method =
      exact ? body::FreeBodyMethod::kSplitting4 : body::free_body_method_from_name(method_name);
  std::vector<body::FreeBodyMotion> motions;
  if (exact) {
    for (const FreeModel& f : free) motions.emplace_back(f.I_P, f.rot0.q_WB, f.rot0.w_B);
  }
  std::vector<std::string> cols{"t"};
  for (const FreeModel& f : free) {
    add_pose_columns(cols, f.name);
    for (const char* c : {"vx", "vy", "vz", "wx", "wy", "wz", "Lx", "Ly", "Lz"}) cols.push_back(f.name + "." + c);
  }
  cols.push_back("energy");
  RunResult r;
  r.trajectory = io::Table(cols);

  const std::vector<double> times = output_times();
  std::vector<body::FreeBodyState> state;
  for (const FreeModel& f : free) state.push_back(f.rot0);
  std::vector<Eigen::Quaterniond> previous(free.size(), Eigen::Quaterniond::Identity());
  // per body: |L| (free: about the COM) or g·L (top: about the pivot), and |RᵀR − 1|
  std::vector<double> L0(free.size()), L_change(free.size(), 0.0), ortho(free.size(), 0.0);
  Eigen::VectorXd energy(static_cast<Eigen::Index>(times.size()));
  const Eigen::Vector3d g_dir = gravity.norm() > 0 ? Eigen::Vector3d(gravity.normalized()) : Eigen::Vector3d::UnitZ();
  std::size_t steps = 0;
  std::vector<double> row;
  double t_prev = 0.0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const double t = times[k];
    if (k > 0 && exact) {
      for (std::size_t i = 0; i < free.size(); ++i) state[i] = motions[i].state(t);
      if (o.progress) o.progress(t);
    } else if (k > 0) {
      const auto n = static_cast<std::size_t>(std::max(1.0, std::ceil((t - t_prev) / dt * (1 - 1e-12))));
      const double h = (t - t_prev) / static_cast<double>(n);
      for (std::size_t i = 0; i < free.size(); ++i) {
        for (std::size_t j = 0; j < n; ++j) {
          state[i] = free[i].top ? body::step_heavy_top(free[i].heavy, state[i], h, method)
                                 : body::step_free_body(method, free[i].I_P, state[i], h);
        }
      }
      steps += n;
      if (!std::isfinite(state.front().w_B.sum())) {
        RIGID_THROW("the angular velocity became non-finite at t = {} s; reduce [simulation] dt "
                    "(now {} s)", t, dt);
      }
      if (o.progress) o.progress(t);
    }
    t_prev = t;
    row.clear();
    row.push_back(t);
    double e_total = 0;
    for (std::size_t i = 0; i < free.size(); ++i) {
      const FreeModel& f = free[i];
      const body::FreeBodyState& st = state[i];
      const Eigen::Quaterniond q_WB = st.q_WB * f.q_BP.conjugate();
      const Eigen::Vector3d w_B = f.q_BP * st.w_B;
      const body::FreeBodyDiagnostics d = body::diagnose(f.I_P, st);
      Eigen::Vector3d p_WB, v_WC;
      double e = d.energy;
      if (f.top) {
        p_WB = f.pivot_W - q_WB * f.pivot_B;
        v_WC = st.q_WB * st.w_B.cross(f.heavy.p_PC_B);
        e = body::heavy_top_energy(f.heavy, st);
      } else {
        const Eigen::Vector3d p_WC = f.p_WC0 + f.v_WC0 * t + 0.5 * gravity * t * t;
        v_WC = f.v_WC0 + gravity * t;
        p_WB = p_WC - q_WB * f.p_BC;
        e += 0.5 * f.mass * v_WC.squaredNorm() - f.mass * gravity.dot(p_WC);
      }
      push_pose(row, p_WB, q_WB, previous[i]);
      row.insert(row.end(), {v_WC.x(), v_WC.y(), v_WC.z(), w_B.x(), w_B.y(), w_B.z(), d.L_W.x(), d.L_W.y(), d.L_W.z()});
      e_total += e;
      const double L = f.top ? g_dir.dot(d.L_W) : d.L_W.norm();
      if (k == 0) L0[i] = L;
      L_change[i] = std::max(L_change[i], std::abs(L - L0[i]));
      ortho[i] = std::max(ortho[i], d.orthonormality_error);
    }
    row.push_back(e_total);
    energy[static_cast<Eigen::Index>(k)] = e_total;
    r.trajectory.add_row(row);
  }

  RunSummary& s = r.summary;
  s.kind = "free_bodies";
  s.dt = dt;
  s.steps = steps;
  s.diagnostics.emplace_back("energy_initial", energy[0]);
  s.diagnostics.emplace_back("energy_final", energy[energy.size() - 1]);
  s.diagnostics.emplace_back("energy_max_change", max_change(energy));
  for (std::size_t i = 0; i < free.size(); ++i) {
    const std::string& n = free[i].name;
    if (free[i].top) {
      s.diagnostics.emplace_back(n + ".L_vertical_max_change", L_change[i]);
    } else {
      s.diagnostics.emplace_back(n + ".L_norm_max_change", L_change[i]);
    }
    s.diagnostics.emplace_back(n + ".orthonormality_max", ortho[i]);
  }
  return r;
}

}  // namespace rigid::scene
