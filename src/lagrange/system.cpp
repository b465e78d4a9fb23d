#include "rigid/lagrange/system.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <fmt/format.h>
#include <ginac/ginac.h>

#include "rigid/common/did_you_mean.hpp"
#include "rigid/common/format.hpp"
#include "detail/parser.hpp"
#include "detail/symbolic.hpp"
#include "detail/symbolic_lock.hpp"
#include "detail/system_impl.hpp"
#include "detail/tape.hpp"
#include "detail/velocity_constraints.hpp"

namespace rigid::lagrange {
namespace {

using GiNaC::ex;
using GiNaC::symbol;
using detail::d;
using detail::identity3;
using detail::is_identifier;
using detail::Mat3;
using detail::mat_mul;
using detail::mat_t_vec;
using detail::mat_vec;
using detail::number;
using detail::reserved_names;
using detail::rodrigues;
using detail::simplify;
using detail::tex_name;
using detail::to_latex;
using detail::to_text;
using detail::Vec3;

}  // namespace

Vector3Expression::Vector3Expression(const Eigen::Vector3d& v)
    : e{Expression(fmt::format("{}", v.x())), Expression(fmt::format("{}", v.y())),
        Expression(fmt::format("{}", v.z()))} {}

BodyMass::BodyMass(const MassProperties& mp)
    : mass(fmt::format("{}", mp.mass())), com(mp.com()) {
  const Eigen::Matrix3d& I = mp.inertia_com();
  for (std::size_t k = 0; k < 6; ++k) {
    inertia[k] = Expression(fmt::format("{}", I(kInertiaElements[k].row, kInertiaElements[k].col)));
  }
}

std::size_t System::Impl::parameter_index(const std::string& name) const {
  auto it = std::find(param_names.begin(), param_names.end(), name);
  if (it == param_names.end()) {
    throw Error(fmt::format("unknown parameter '{}'{}; parameters: {}", name,
                            did_you_mean_hint(name, param_names),
                            param_names.empty() ? std::string("none") : fmt::format("{}", fmt::join(param_names, ", "))));
  }
  return static_cast<std::size_t>(it - param_names.begin());
}

void System::Impl::check_masses(const std::vector<double>& values, std::string_view context) const {
  if (masses.num_outputs() == 0) return;
  std::vector<double> out(masses.num_outputs());
  masses.evaluate(values.data(), out.data());
  for (std::size_t b = 0; b < body_names.size(); ++b) {
    const double* o = out.data() + 10 * b;
    Eigen::Matrix3d I;
    I << o[4], o[7], o[8], o[7], o[5], o[9], o[8], o[9], o[6];
    if (auto report = MassProperties::check(o[0], Eigen::Vector3d(o[1], o[2], o[3]), I)) {
      throw Error(fmt::format("body '{}' {}: {}", body_names[b], context, *report));
    }
  }
}

std::string System::Impl::state_text(double time, const Eigen::VectorXd& qv) const {
  std::string s = fmt::format("t = {} s, q = (", time);
  for (int i = 0; i < n; ++i) {
    s += fmt::format("{}{} = {}", i ? ", " : "", coord_names[static_cast<std::size_t>(i)], qv[i]);
  }
  return s + ")";
}

namespace {

// Parses, assembles, derives and compiles `spec` into `s` (under the symbolic lock).
void derive(System::Impl& s, const SystemSpec& spec) {
  s.n = static_cast<int>(spec.coordinates.size());
  s.m = static_cast<int>(spec.constraints.size());
  RIGID_REQUIRE_AS("System", s.n > 0, "a system needs at least one coordinate, got none");

  // symbol table, with every name checked once
  std::map<std::string, ex> names;
  std::map<std::string, std::string> owner;  // name → what declared it, for duplicates
  names["t"] = s.t;
  auto declare = [&](const std::string& name, const std::string& what, const ex& value) {
    RIGID_REQUIRE(is_identifier(name), "{} name '{}' is not a valid name; expected letters, "
                  "digits and '_', not starting with a digit", what, name);
    RIGID_REQUIRE(!reserved_names().count(name), "{} name '{}' is reserved (t, pi and the "
                  "function names)", what, name);
    auto [it, fresh] = owner.emplace(name, what);
    RIGID_REQUIRE(fresh, "{} name '{}' is already used by a {}", what, name, it->second);
    names[name] = value;
  };
  for (const Parameter& p : spec.parameters) {
    RIGID_REQUIRE_AS("System", std::isfinite(p.value), "parameter '{}' must be finite, got {}", p.name, p.value);
    s.params.emplace_back(p.name, tex_name(p.name));
    s.param_names.push_back(p.name);
    s.param_values.push_back(p.value);
    declare(p.name, "parameter", s.params.back());
  }
  s.q0.resize(s.n);
  s.qd0.resize(s.n);
  for (int i = 0; i < s.n; ++i) {
    const Coordinate& c = spec.coordinates[static_cast<std::size_t>(i)];
    RIGID_REQUIRE_AS("System", std::isfinite(c.initial) && std::isfinite(c.velocity),
                  "coordinate '{}': initial value {} and velocity {} must be finite", c.name,
                  c.initial, c.velocity);
    s.coord_names.push_back(c.name);
    s.q.emplace_back(c.name, tex_name(c.name));
    s.qd.emplace_back(c.name + "_dot", "\\dot{" + tex_name(c.name) + "}");
    s.qdd.emplace_back(c.name + "_ddot", "\\ddot{" + tex_name(c.name) + "}");
    s.q0[i] = c.initial;
    s.qd0[i] = c.velocity;
    declare(c.name, "coordinate", s.q.back());
    declare(c.name + "_dot", "velocity", s.qd.back());
  }

  auto parse = [&](const Expression& e, const std::string& context, bool allow_velocity) {
    if (e.text.find_first_not_of(" \t") == std::string::npos) {
      detail::throw_at(e, 0, context, "empty expression; expected a number, a name or '('");
    }
    ex value = detail::parse_expression(e, names, context);
    if (!allow_velocity) {
      for (int i = 0; i < s.n; ++i) {
        if (value.has(s.qd[static_cast<std::size_t>(i)])) {
          detail::throw_at(e, e.text.find(s.coord_names[static_cast<std::size_t>(i)] + "_dot"),
                           context, fmt::format("depends on the velocity '{}_dot'; only q and t "
                                                "may appear here",
                                                s.coord_names[static_cast<std::size_t>(i)]));
        }
      }
    }
    return value;
  };
  // total time derivative d/dt e(q, t) = Σ ∂e/∂qᵢ q̇ᵢ + ∂e/∂t
  auto dt = [&](const ex& e) {
    ex r = d(e, s.t);
    for (int i = 0; i < s.n; ++i) r += d(e, s.q[static_cast<std::size_t>(i)]) * s.qd[static_cast<std::size_t>(i)];
    return r;
  };

  // an expression of the parameters and numbers only (masses, inertias, gravity)
  auto parse_constant = [&](const Expression& e, const std::string& context) {
    const ex value = parse(e, context, false);
    for (int i = 0; i < s.n; ++i) {
      if (value.has(s.q[static_cast<std::size_t>(i)])) {
        detail::throw_at(e, e.text.find(s.coord_names[static_cast<std::size_t>(i)]), context,
                         fmt::format("depends on the coordinate '{}'; a constant of the model may "
                                     "use parameters and numbers only",
                                     s.coord_names[static_cast<std::size_t>(i)]));
      }
    }
    if (value.has(s.t)) {
      detail::throw_at(e, e.text.find('t'), context,
                       "depends on the time 't'; a constant of the model may use parameters and "
                       "numbers only");
    }
    return value;
  };
  Vec3 gravity;
  for (int k = 0; k < 3; ++k) gravity[k] = parse_constant(spec.gravity_W[k], fmt::format("gravity[{}]", k));

  // assemble T and V
  ex T_bodies = 0, V = 0, L_given = 0;
  std::vector<ex> mass_outputs;  // per body: mass, COM (3), inertia xx yy zz xy xz yz
  if (spec.lagrangian.text.find_first_not_of(" \t") != std::string::npos) {
    L_given = parse(spec.lagrangian, "Lagrangian", true).expand();
  }
  std::map<std::string, std::pair<Vec3, Mat3>> poses;  // body name → (p_WB, R_WB)
  std::vector<ex> pose_outputs;                         // per body: p_WB (3), R_WB row-major (9)
  for (const Body& b : spec.bodies) {
    const std::string ctx = fmt::format("body '{}'", b.name);
    RIGID_REQUIRE_AS("System", b.name.empty() || !poses.count(b.name), "body name '{}' is used twice",
                  b.name);
    Vec3 p;
    // an empty position component means 0
    for (int k = 0; k < 3; ++k) {
      const bool empty = b.position[k].text.find_first_not_of(" \t") == std::string::npos;
      p[k] = empty ? ex(0) : parse(b.position[k], fmt::format("{} position[{}]", ctx, k), false);
    }
    // R_WB = R₁ ⋯ R_k; ω_B of a product: ω ← R_jᵀ ω + a_j θ̇_j, left to right
    Mat3 R = identity3();
    Vec3 w{0, 0, 0};
    for (std::size_t j = 0; j < b.rotations.size(); ++j) {
      const AxisRotation& r = b.rotations[j];
      const double norm = r.axis.norm();
      RIGID_REQUIRE_AS("System", std::isfinite(norm) && norm > 0, "{} rotation {}: the axis must be a "
                    "non-zero finite vector, got ({}, {}, {})", ctx, j, r.axis.x(), r.axis.y(),
                    r.axis.z());
      const Eigen::Vector3d a = r.axis / norm;
      const ex theta = parse(r.angle, fmt::format("{} rotation {} angle", ctx, j), false);
      const Mat3 Rj = rodrigues(a, theta);
      R = mat_mul(R, Rj);
      const ex theta_dot = dt(theta);
      w = mat_t_vec(Rj, w);
      for (int k = 0; k < 3; ++k) w[k] = (w[k] + number(a[k]) * theta_dot).expand();
    }
    // mass properties as expressions of the parameters (constants: no q, q̇ or t)
    const ex mass = parse_constant(b.mass.mass, ctx + " mass");
    Vec3 com_B;
    for (int k = 0; k < 3; ++k) com_B[k] = parse_constant(b.mass.com[k], fmt::format("{} com[{}]", ctx, k));
    Mat3 I;
    for (std::size_t k = 0; k < 6; ++k) {
      const auto& [name, row, col] = BodyMass::kInertiaElements[k];
      I[row][col] = I[col][row] = parse_constant(b.mass.inertia[k], ctx + " " + name);
    }
    mass_outputs.push_back(mass);
    for (int k = 0; k < 3; ++k) mass_outputs.push_back(com_B[k]);
    for (const auto& e : BodyMass::kInertiaElements) mass_outputs.push_back(I[e.row][e.col]);
    Vec3 c = mat_vec(R, com_B);
    ex v2 = 0;
    for (int k = 0; k < 3; ++k) {
      c[k] = (c[k] + p[k]).expand();
      const ex v = dt(c[k]);
      v2 += v * v;
    }
    ex rot = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (!I[i][j].is_zero()) rot += I[i][j] * w[i] * w[j];
    T_bodies += mass / 2 * v2 + rot / 2;
    for (int k = 0; k < 3; ++k) {
      if (!gravity[k].is_zero()) V -= mass * gravity[k] * c[k];
    }
    if (!b.name.empty()) poses.emplace(b.name, std::make_pair(p, R));
    s.body_names.push_back(b.name.empty() ? fmt::format("body{}", s.body_names.size()) : b.name);
    for (int k = 0; k < 3; ++k) pose_outputs.push_back(p[k]);
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) pose_outputs.push_back(R[i][k]);
  }
  // springs: V = ½ k (|p_a − p_b| − L)², points carried by their bodies' poses
  auto world_point = [&](const std::string& body, const Eigen::Vector3d& point, std::size_t s_index,
                         const char* which) {
    const Vec3 local{number(point.x()), number(point.y()), number(point.z())};
    if (body.empty()) return local;
    auto it = poses.find(body);
    if (it == poses.end()) {
      std::string known;
      for (const auto& [name, _] : poses) known += (known.empty() ? "" : ", ") + name;
      rigid::detail::throw_error("System", fmt::format("spring {}: {} names the unknown body "
                                 "'{}'; bodies: {}", s_index, which, body,
                                 known.empty() ? "none" : known));
    }
    Vec3 w = mat_vec(it->second.second, local);
    for (int k = 0; k < 3; ++k) w[k] = (w[k] + it->second.first[k]).expand();
    return w;
  };
  for (std::size_t j = 0; j < spec.springs.size(); ++j) {
    const Spring& sp = spec.springs[j];
    RIGID_REQUIRE_AS("System", !sp.body_a.empty(), "spring {}: body_a must name a body", j);
    const Vec3 a = world_point(sp.body_a, sp.point_a_B, j, "body_a");
    const Vec3 b = world_point(sp.body_b, sp.point_b_B, j, "body_b");
    const ex k = parse(sp.stiffness, fmt::format("spring {} stiffness", j), false);
    const ex rest = parse(sp.rest_length, fmt::format("spring {} rest_length", j), false);
    ex d2 = 0;
    for (int i = 0; i < 3; ++i) d2 += GiNaC::pow(a[i] - b[i], 2);
    d2 = d2.expand();
    V += rest.is_zero() ? k / 2 * d2 : k / 2 * GiNaC::pow(GiNaC::sqrt(d2) - rest, 2);
  }
  for (const NamedExpression& pot : spec.potentials) {
    V += parse(pot.expression, fmt::format("potential '{}'", pot.name), false);
  }
  T_bodies = simplify(T_bodies);
  // the velocity-dependent part of a given L counts as kinetic energy, the rest as −V
  ex T_given = 0, V_given = 0;
  {
    const ex Lg = simplify(L_given);
    const GiNaC::exvector terms = GiNaC::is_a<GiNaC::add>(Lg) ? GiNaC::exvector(Lg.begin(), Lg.end())
                                                              : GiNaC::exvector{Lg};
    for (const ex& term : terms) {
      bool has_velocity = false;
      for (const symbol& v : s.qd) has_velocity = has_velocity || term.has(v);
      (has_velocity ? T_given : V_given) += term;
    }
  }
  s.T = T_bodies + T_given;
  s.V = simplify(V - V_given);
  s.L = simplify(s.T - s.V);

  // generalized forces
  std::vector<ex> Q(static_cast<std::size_t>(s.n), 0);
  std::vector<bool> forced(static_cast<std::size_t>(s.n), false);
  for (const NamedExpression& F : spec.forces) {
    auto it = std::find(s.coord_names.begin(), s.coord_names.end(), F.name);
    if (it == s.coord_names.end()) {
      std::string known;
      for (const auto& c : s.coord_names) known += (known.empty() ? "" : ", ") + c;
      rigid::detail::throw_error("System", fmt::format("force on '{}': no coordinate of that name; coordinates: {}", F.name, known));
    }
    const auto i = static_cast<std::size_t>(it - s.coord_names.begin());
    Q[i] += parse(F.expression, fmt::format("force on '{}'", F.name), true);
    forced[i] = true;
  }

  s.Q = Q;
  // Euler–Lagrange: p = ∂L/∂q̇, M = ∂p/∂q̇, f = ∂L/∂q − (∂p/∂q) q̇ − ∂p/∂t + Q
  const auto n = static_cast<std::size_t>(s.n);
  s.p.resize(n);
  s.M.assign(n * n, 0);
  s.f.resize(n);
  for (std::size_t i = 0; i < n; ++i) s.p[i] = d(s.L, s.qd[i]);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) s.M[i * n + j] = d(s.p[i], s.qd[j]);
    if (s.M[i * n + i].expand().is_zero()) {
      rigid::detail::throw_error("System", fmt::format("the Lagrangian is not quadratic in the velocity '{}_dot' (∂²L/∂{}_dot² ≡ 0), "
                  "so the mass matrix is singular; L = {}", s.coord_names[i], s.coord_names[i],
                  to_text(s.L)));
    }
    ex fi = d(s.L, s.q[i]) - d(s.p[i], s.t) + Q[i];
    for (std::size_t j = 0; j < n; ++j) fi -= d(s.p[i], s.q[j]) * s.qd[j];
    s.f[i] = fi.expand();
  }
  s.h = 0;
  for (std::size_t i = 0; i < n; ++i) s.h += s.qd[i] * s.p[i];
  s.h = simplify(s.h - s.L);

  // constraints: G = ∂g/∂q, ġ = G q̇ + ∂g/∂t, γ = −(∂ġ/∂q q̇ + ∂ġ/∂t)
  std::vector<bool> constrained(n, false);
  for (const NamedExpression& con : spec.constraints) {
    RIGID_REQUIRE_AS("System", is_identifier(con.name), "constraint name '{}' is not a valid name", con.name);
    RIGID_REQUIRE_AS("System", std::find(s.constraint_names.begin(), s.constraint_names.end(), con.name) ==
                      s.constraint_names.end(),
                  "constraint name '{}' is used twice", con.name);
    const ex gk = parse(con.expression, fmt::format("constraint '{}'", con.name), false).expand();
    bool depends = false;
    for (std::size_t i = 0; i < n; ++i) {
      const ex Gki = d(gk, s.q[i]);
      s.G.push_back(Gki);
      if (!Gki.is_zero()) depends = constrained[i] = true;
    }
    RIGID_REQUIRE_AS("System", depends, "constraint '{}' = {} does not depend on any coordinate; it is either "
                  "always or never satisfied", con.name, to_text(gk));
    const ex ck = dt(gk).expand();
    ex gamma = -d(ck, s.t);
    for (std::size_t j = 0; j < n; ++j) gamma -= d(ck, s.q[j]) * s.qd[j];
    s.g.push_back(gk);
    s.c.push_back(ck);
    s.gamma.push_back(gamma.expand());
    s.constraint_names.push_back(con.name);
    s.lambda.emplace_back("lambda_" + con.name, "\\lambda_{\\mathrm{" + con.name + "}}");
  }

  // velocity (nonholonomic) constraints A q̇ + a = 0 (velocity_constraints.cpp)
  detail::derive_velocity_constraints(spec, s, names, constrained);

  // cyclic coordinates
  for (std::size_t i = 0; i < n; ++i) {
    if (!forced[i] && !constrained[i] && d(s.L, s.q[i]).expand().is_zero()) {
      s.cyclic_index.push_back(static_cast<int>(i));
      s.cyclic_names.push_back(s.coord_names[i]);
    }
  }
  // Störmer–Verlet applies when M is constant and f does not depend on q̇ (and no constraints)
  s.verlet_ok = s.m == 0 && s.r == 0;
  for (std::size_t i = 0; i < n && s.verlet_ok; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      for (std::size_t k = 0; k < n; ++k) {
        if (s.M[i * n + j].has(s.q[k]) || s.f[i].has(s.qd[k])) s.verlet_ok = false;
      }
      if (s.M[i * n + j].has(s.t)) s.verlet_ok = false;
    }
  }

  // compile: inputs (q, q̇, t, parameters)
  std::vector<symbol> inputs;
  inputs.insert(inputs.end(), s.q.begin(), s.q.end());
  inputs.insert(inputs.end(), s.qd.begin(), s.qd.end());
  inputs.push_back(s.t);
  inputs.insert(inputs.end(), s.params.begin(), s.params.end());
  detail::TapeBuilder dyn(inputs, inputs.size() - s.params.size());
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) dyn.add_output(s.M[i * n + j]);
  for (const ex& e : s.f) dyn.add_output(e);
  for (const ex& e : s.G) dyn.add_output(e);
  for (const ex& e : s.gamma) dyn.add_output(e);
  for (const ex& e : s.c) dyn.add_output(e);
  for (const ex& e : s.g) dyn.add_output(e);
  s.dyn = dyn.build();
  detail::TapeBuilder diag(inputs);
  diag.add_output(simplify(s.T + s.V));
  diag.add_output(s.h);
  for (int i : s.cyclic_index) diag.add_output(s.p[static_cast<std::size_t>(i)]);
  s.diag = diag.build();
  detail::TapeBuilder pose(inputs);
  for (const ex& e : pose_outputs) pose.add_output(e);
  s.pose = pose.build();

  std::vector<symbol> param_inputs(s.params.begin(), s.params.end());
  detail::TapeBuilder masses(param_inputs);
  for (const ex& e : mass_outputs) masses.add_output(e);
  s.masses = masses.build();
  s.check_masses(s.param_values, "for the parameters' values");
}

}  // namespace

System::System(const SystemSpec& spec) {
  detail::SymbolicLock lock;
  // built aside, so that a throw destroys the partial expressions while the lock is held
  auto impl = std::make_unique<Impl>();
  derive(*impl, spec);
  impl_ = std::move(impl);
}

// The expressions of a System are destroyed under the symbolic lock (their nodes are shared
// with every other expression of the process).
System::~System() {
  detail::SymbolicLock lock;
  impl_.reset();
}
System::System(System&&) noexcept = default;
System& System::operator=(System&& other) noexcept {
  detail::SymbolicLock lock;
  impl_ = std::move(other.impl_);
  return *this;
}

int System::num_coordinates() const { return impl_->n; }
int System::num_constraints() const { return impl_->m; }
const std::vector<std::string>& System::coordinate_names() const { return impl_->coord_names; }
const std::vector<std::string>& System::constraint_names() const {
  return impl_->constraint_names;
}
const std::vector<std::string>& System::cyclic_coordinates() const { return impl_->cyclic_names; }
int System::num_velocity_constraints() const { return impl_->r; }
const std::vector<std::string>& System::velocity_constraint_names() const {
  return impl_->velocity_constraint_names;
}
Eigen::VectorXd System::initial_q() const { return impl_->q0; }
Eigen::VectorXd System::initial_q_dot() const { return impl_->qd0; }
std::size_t System::tape_size() const { return impl_->dyn.size(); }
const std::vector<std::string>& System::body_names() const { return impl_->body_names; }


void System::set_parameter(const std::string& name, double value) {
  Impl& s = *impl_;
  const std::size_t k = s.parameter_index(name);
  RIGID_REQUIRE(std::isfinite(value), "parameter '{}' must be finite, got {}", name, value);
  std::vector<double> values = s.param_values;
  values[k] = value;
  s.check_masses(values, fmt::format("with {} = {}", name, value));
  s.param_values = std::move(values);
}

std::vector<Parameter> System::parameters() const {
  std::vector<Parameter> out;
  for (std::size_t k = 0; k < impl_->param_names.size(); ++k) {
    out.push_back({impl_->param_names[k], impl_->param_values[k]});
  }
  return out;
}

// System::equations() is in equations.cpp

}  // namespace rigid::lagrange

#if defined(__SANITIZE_ADDRESS__)
// CLN (GiNaC's number library) allocates 26 bytes in a static initializer that it never
// frees; LeakSanitizer would fail every sanitized program that links rigid::lagrange. This
// is LeakSanitizer's documented hook for default suppressions.
extern "C" const char* __lsan_default_suppressions() { return "leak:libcln.so\n"; }
#endif
