#include "rigid/lagrange/system.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>

#include <fmt/format.h>
#include <ginac/ginac.h>

#include "rigid/common/did_you_mean.hpp"
#include "rigid/common/format.hpp"
#include "detail/parser.hpp"
#include "detail/recursive.hpp"
#include "detail/symbolic.hpp"
#include "rigid/common/escape.hpp"
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
  for (int i = 0; i < nq; ++i) {
    s += fmt::format("{}{} = {}", i ? ", " : "", coord_names[static_cast<std::size_t>(i)], qv[i]);
  }
  return s + ")";
}

namespace {

// The symbol table of a System: every name an expression may use → its symbol.
using Names = std::map<std::string, ex>;
// Named bodies → (p_WB, R_WB), for the springs attached to them.
using Poses = std::map<std::string, std::pair<Vec3, Mat3>>;

// Declares t, the parameters, the coordinates and their velocities in `s` and `names`,
// with every name checked once.
void declare_symbols(System::Impl& s, const SystemSpec& spec, Names& names) {
  std::map<std::string, std::string> owner;  // name → what declared it, for duplicates
  names["t"] = s.t;
  auto declare = [&](const std::string& name, const std::string& what, const ex& value) {
    // named as System's checks (inside a lambda RIGID_REQUIRE would name "operator()")
    RIGID_REQUIRE_AS("System", is_identifier(name), "{} name '{}' is not a valid name; expected "
                     "letters, digits and '_', not starting with a digit", what, rigid::escaped(name));
    RIGID_REQUIRE_AS("System", !reserved_names().count(name), "{} name '{}' is reserved (t, pi "
                     "and the function names)", what, name);
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
  s.q0.resize(s.nq);
  s.qd0.resize(s.n);
  Eigen::Index iq = 0, iv = 0;
  for (const Coordinate& c : spec.coordinates) {
    RIGID_REQUIRE_AS("System", std::isfinite(c.initial) && std::isfinite(c.velocity),
                  "coordinate '{}': initial value {} and velocity {} must be finite", c.name,
                  c.initial, c.velocity);
    if (c.kind == Coordinate::Kind::kBall) {
      const Eigen::Vector4d quat(c.orientation[0], c.orientation[1], c.orientation[2], c.orientation[3]);
      RIGID_REQUIRE_AS("System", quat.allFinite() && c.angular_velocity.allFinite(),
                       "ball coordinate '{}': orientation ({}, {}, {}, {}) and angular velocity ({}, "
                       "{}, {}) must be finite", c.name, quat[0], quat[1], quat[2], quat[3],
                       c.angular_velocity.x(), c.angular_velocity.y(), c.angular_velocity.z());
      RIGID_REQUIRE_AS("System", std::abs(quat.norm() - 1) <= 1e-6,
                       "ball coordinate '{}': the orientation ({}, {}, {}, {}) has norm {}; expected "
                       "a unit quaternion (w, x, y, z) within 1e-6", c.name, quat[0], quat[1],
                       quat[2], quat[3], quat.norm());
      s.balls.push_back({static_cast<std::size_t>(iq), static_cast<std::size_t>(iv), c.name});
      constexpr std::array<const char*, 4> kPart{"w", "x", "y", "z"};
      for (std::size_t k = 0; k < 4; ++k) {
        const std::string name = c.name + "_q" + kPart[k];
        s.coord_names.push_back(name);
        s.q.emplace_back(name, "q_{" + tex_name(c.name) + "," + kPart[k] + "}");
        s.q0[iq++] = quat[static_cast<Eigen::Index>(k)] / quat.norm();
        declare(name, "coordinate", s.q.back());
      }
      for (std::size_t k = 0; k < 3; ++k) {
        const std::string name = c.name + "_w" + kPart[k + 1];
        s.velocity_names.push_back(name);
        s.qd.emplace_back(name, "\\omega_{" + tex_name(c.name) + "," + kPart[k + 1] + "}");
        s.qdd.emplace_back(name + "_dot", "\\dot\\omega_{" + tex_name(c.name) + "," + kPart[k + 1] + "}");
        s.q_of_v.push_back(-1);
        s.qd0[iv++] = c.angular_velocity[static_cast<Eigen::Index>(k)];
        declare(name, "velocity", s.qd.back());
      }
      continue;
    }
    s.coord_names.push_back(c.name);
    s.velocity_names.push_back(c.name + "_dot");
    s.q.emplace_back(c.name, tex_name(c.name));
    s.qd.emplace_back(c.name + "_dot", "\\dot{" + tex_name(c.name) + "}");
    s.qdd.emplace_back(c.name + "_ddot", "\\ddot{" + tex_name(c.name) + "}");
    s.q_of_v.push_back(static_cast<int>(iq));
    s.q0[iq++] = c.initial;
    s.qd0[iv++] = c.velocity;
    declare(c.name, "coordinate", s.q.back());
    declare(c.name + "_dot", "velocity", s.qd.back());
  }
  // dq/dt: a coordinate's velocity, and ½ q ⊗ (0, ω) for a ball's quaternion
  s.q_rate.assign(s.q.size(), 0);
  for (std::size_t v = 0; v < s.qd.size(); ++v) {
    if (s.q_of_v[v] >= 0) s.q_rate[static_cast<std::size_t>(s.q_of_v[v])] = s.qd[v];
  }
  for (const System::Impl::Ball& b : s.balls) {
    const ex w = s.q[b.q], x = s.q[b.q + 1], y = s.q[b.q + 2], z = s.q[b.q + 3];
    const ex wx = s.qd[b.v], wy = s.qd[b.v + 1], wz = s.qd[b.v + 2];
    s.q_rate[b.q] = -(x * wx + y * wy + z * wz) / 2;
    s.q_rate[b.q + 1] = (w * wx + y * wz - z * wy) / 2;
    s.q_rate[b.q + 2] = (w * wy + z * wx - x * wz) / 2;
    s.q_rate[b.q + 3] = (w * wz + x * wy - y * wx) / 2;
  }
}

// Reads the expressions of a spec with the declared names, refusing at its column an
// expression that uses what its place does not allow.
class ExpressionReader {
 public:
  ExpressionReader(const System::Impl& s, const Names& names) : s_(s), names_(names) {}

  // an expression of q, t, the parameters and numbers, and of q̇ if `allow_velocity`
  [[nodiscard]] ex parse(const Expression& e, const std::string& context, bool allow_velocity) const {
    if (e.text.find_first_not_of(" \t") == std::string::npos) {
      detail::throw_at(e, 0, context, "empty expression; expected a number, a name or '('");
    }
    ex value = detail::parse_expression(e, names_, context);
    if (!allow_velocity) {
      for (const symbol& v : s_.qd) {
        if (value.has(v)) {
          detail::throw_at(e, e.text.find(v.get_name()), context,
                           fmt::format("depends on the velocity '{}'; only q and t may appear here",
                                       v.get_name()));
        }
      }
    }
    return value;
  }

  // an expression of the parameters and numbers only (masses, inertias, gravity)
  [[nodiscard]] ex parse_constant(const Expression& e, const std::string& context) const {
    const ex value = parse(e, context, false);
    for (std::size_t i = 0; i < s_.q.size(); ++i) {
      if (value.has(s_.q[i])) {
        detail::throw_at(e, e.text.find(s_.coord_names[i]), context,
                         fmt::format("depends on the coordinate '{}'; a constant of the model may "
                                     "use parameters and numbers only",
                                     s_.coord_names[i]));
      }
    }
    if (value.has(s_.t)) {
      detail::throw_at(e, e.text.find('t'), context,
                       "depends on the time 't'; a constant of the model may use parameters and "
                       "numbers only");
    }
    return value;
  }

 private:
  const System::Impl& s_;
  const Names& names_;
};

// Total time derivative d/dt e(q, t) = Σ ∂e/∂qᵢ q̇ᵢ + ∂e/∂t (q̇ᵢ of a ball's quaternion:
// ½ q ⊗ (0, ω)).
ex time_derivative(const System::Impl& s, const ex& e) {
  ex r = d(e, s.t);
  for (std::size_t i = 0; i < s.q.size(); ++i) r += d(e, s.q[i]) * s.q_rate[i];
  return r;
}

// A body frame's pose in the world and its angular velocity in its own axes.
struct Frame {
  Vec3 p;  // p_WB
  Mat3 R;  // R_WB
  Vec3 w;  // ω_B
};

// What the bodies add to the model: T and V, and the outputs of the mass and pose tapes.
struct BodyTerms {
  ex T = 0, V = 0;
  std::vector<ex> mass_outputs;  // per body: mass, COM (3), inertia xx yy zz xy xz yz
  Poses poses;                   // body name → (p_WB, R_WB)
  std::map<std::string, Frame> frames;  // body name → its frame, for the bodies hanging from it
  std::vector<ex> pose_outputs;  // per body: p_WB (3), R_WB row-major (9)
};

// A body's orientation R_WB and body-frame angular velocity ω_B.
struct Orientation {
  Mat3 R;
  Vec3 w;
};

// R_WB = R₁ ⋯ R_k; ω_B of a product: ω ← R_jᵀ ω + a_j θ̇_j, left to right.
Orientation body_orientation(const System::Impl& s, const ExpressionReader& reader, const Body& b,
                             const std::string& ctx) {
  Mat3 R = identity3();
  if (!b.orientation.isIdentity(0.0)) {
    const Eigen::Matrix3d& O = b.orientation;
    RIGID_REQUIRE_AS("System", O.allFinite() && (O.transpose() * O - Eigen::Matrix3d::Identity()).norm() < 1e-12 &&
                                   O.determinant() > 0,
                     "{} orientation: expected a proper rotation matrix", ctx);
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) R[i][k] = number(O(i, k));
  }
  Vec3 w{0, 0, 0};  // a constant leading rotation adds no angular velocity
  for (std::size_t j = 0; j < b.rotations.size(); ++j) {
    const AxisRotation& r = b.rotations[j];
    const double norm = r.axis.norm();
    RIGID_REQUIRE_AS("System", std::isfinite(norm) && norm > 0, "{} rotation {}: the axis must be a "
                  "non-zero finite vector, got ({}, {}, {})", ctx, j, r.axis.x(), r.axis.y(),
                  r.axis.z());
    const Eigen::Vector3d a = r.axis / norm;
    const ex theta = reader.parse(r.angle, fmt::format("{} rotation {} angle", ctx, j), false);
    const Mat3 Rj = rodrigues(a, theta);
    R = mat_mul(R, Rj);
    const ex theta_dot = time_derivative(s, theta);
    w = mat_t_vec(Rj, w);
    for (int k = 0; k < 3; ++k) w[k] = (w[k] + number(a[k]) * theta_dot).expand();
  }
  return {R, w};
}

// The frame of the parent a body names: a body declared before it (refused otherwise).
const Frame& parent_frame(const BodyTerms& terms, const SystemSpec& spec, const Body& b,
                          std::size_t index) {
  const std::string who = b.name.empty() ? fmt::format("body{}", index) : b.name;
  RIGID_REQUIRE_AS("System", b.parent != b.name,
                   "body '{}' names itself as its parent; expected the world (empty) or a body "
                   "declared before it",
                   who);
  auto it = terms.frames.find(b.parent);
  if (it != terms.frames.end()) return it->second;
  const auto later =
      std::find_if(spec.bodies.begin() + static_cast<std::ptrdiff_t>(index), spec.bodies.end(),
                   [&](const Body& o) { return o.name == b.parent; });
  if (later != spec.bodies.end()) {
    rigid::detail::throw_error(
        "System", fmt::format("body '{}' names the parent '{}', which is declared after it; "
                              "declare a parent before the bodies that hang from it",
                              who, b.parent));
  }
  std::vector<std::string> known;
  for (const auto& [name, _] : terms.frames) known.push_back(name);
  rigid::detail::throw_error(
      "System",
      fmt::format("body '{}' names the parent '{}', which is no body{}; bodies declared "
                  "before it: {}",
                  who, b.parent, did_you_mean_hint(b.parent, known),
                  known.empty() ? std::string("none") : fmt::format("{}", fmt::join(known, ", "))));
}

// Applies a body's joints to its pose (p, R) and angular velocity ω (in the frame the joints
// start from), left to right. A turn J = Trans(a) Rot(u, θ) Trans(−a):
//   p ← p + R (a − R_J a),  R ← R R_J,  ω ← R_Jᵀ ω + u θ̇;
// a slide by s along u: p ← p + R u s (R and ω stay).
void apply_joints(const System::Impl& s, const ExpressionReader& reader, const Body& b,
                  const std::string& ctx, Vec3& p, Mat3& R, Vec3& w) {
  for (std::size_t j = 0; j < b.joints.size(); ++j) {
    const JointMotion& J = b.joints[j];
    const double norm = J.axis.norm();
    RIGID_REQUIRE_AS("System", std::isfinite(norm) && norm > 0,
                     "{} joint {}: the axis must be a non-zero finite vector, got ({}, {}, {})",
                     ctx, j, J.axis.x(), J.axis.y(), J.axis.z());
    RIGID_REQUIRE_AS("System", J.anchor.allFinite(),
                     "{} joint {}: the anchor must be finite, got ({}, {}, {})",
                     ctx, j, J.anchor.x(), J.anchor.y(), J.anchor.z());
    const Eigen::Vector3d u = J.axis / norm;
    const bool turn = J.kind == JointMotion::Kind::kTurn;
    const ex amount = reader.parse(
        J.amount, fmt::format("{} joint {} {}", ctx, j, turn ? "turn" : "slide"), false);
    Vec3 shift;  // the joint's translation, in the frame it starts from
    if (turn) {
      const Mat3 RJ = rodrigues(u, amount);
      const Vec3 a{number(J.anchor.x()), number(J.anchor.y()), number(J.anchor.z())};
      const Vec3 RJa = mat_vec(RJ, a);
      for (int k = 0; k < 3; ++k) shift[k] = (a[k] - RJa[k]).expand();
      const ex amount_dot = time_derivative(s, amount);
      w = mat_t_vec(RJ, w);
      for (int k = 0; k < 3; ++k) w[k] = (w[k] + number(u[k]) * amount_dot).expand();
      const Vec3 Rshift = mat_vec(R, shift);
      for (int k = 0; k < 3; ++k) p[k] = (p[k] + Rshift[k]).expand();
      R = mat_mul(R, RJ);
    } else {
      for (int k = 0; k < 3; ++k) shift[k] = number(u[k]) * amount;
      const Vec3 Rshift = mat_vec(R, shift);
      for (int k = 0; k < 3; ++k) p[k] = (p[k] + Rshift[k]).expand();
    }
  }
}

// Adds body `b` (number `index` of the spec): its T and its V in `gravity`, its mass
// properties (constants: no q, q̇ or t) to the mass outputs, its world pose to the pose
// outputs, its frame for the bodies hanging from it, and its name to s.body_names.
void add_body(System::Impl& s, const ExpressionReader& reader, const SystemSpec& spec,
              std::size_t index, const Vec3& gravity, BodyTerms& terms) {
  const Body& b = spec.bodies[index];
  const std::string ctx = fmt::format("body '{}'", b.name);
  RIGID_REQUIRE_AS("System", b.name.empty() || !terms.poses.count(b.name), "body name '{}' is used twice",
                b.name);
  Vec3 p;
  // an empty position component means 0
  for (int k = 0; k < 3; ++k) {
    const bool empty = b.position[k].text.find_first_not_of(" \t") == std::string::npos;
    p[k] = empty ? ex(0) : reader.parse(b.position[k], fmt::format("{} position[{}]", ctx, k), false);
  }
  auto [R, w] = body_orientation(s, reader, b, ctx);
  // a body in a tree: its joints, then its pose in the parent's carried into the world
  // (p_WB = p_WP + R_WP p_PB, R_WB = R_WP R_PB, ω_B = R_PBᵀ ω_P + ω_PB_B); the other bodies
  // keep the expressions they always had
  if (!b.joints.empty()) apply_joints(s, reader, b, ctx, p, R, w);
  if (!b.parent.empty()) {
    const Frame& P = parent_frame(terms, spec, b, index);
    const Vec3 w_P_B = mat_t_vec(R, P.w);
    const Vec3 p_W = mat_vec(P.R, p);
    for (int k = 0; k < 3; ++k) {
      w[k] = (w_P_B[k] + w[k]).expand();
      p[k] = (P.p[k] + p_W[k]).expand();
    }
    R = mat_mul(P.R, R);
  }
  // mass properties as expressions of the parameters (constants: no q, q̇ or t)
  const ex mass = reader.parse_constant(b.mass.mass, ctx + " mass");
  Vec3 com_B;
  for (int k = 0; k < 3; ++k) com_B[k] = reader.parse_constant(b.mass.com[k], fmt::format("{} com[{}]", ctx, k));
  Mat3 I;
  for (std::size_t k = 0; k < 6; ++k) {
    const auto& [name, row, col] = BodyMass::kInertiaElements[k];
    I[row][col] = I[col][row] = reader.parse_constant(b.mass.inertia[k], ctx + " " + name);
  }
  terms.mass_outputs.push_back(mass);
  for (int k = 0; k < 3; ++k) terms.mass_outputs.push_back(com_B[k]);
  for (const auto& e : BodyMass::kInertiaElements) terms.mass_outputs.push_back(I[e.row][e.col]);
  Vec3 c = mat_vec(R, com_B);
  ex v2 = 0;
  for (int k = 0; k < 3; ++k) {
    c[k] = (c[k] + p[k]).expand();
    const ex v = time_derivative(s, c[k]);
    v2 += v * v;
  }
  ex rot = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (!I[i][j].is_zero()) rot += I[i][j] * w[i] * w[j];
  terms.T += mass / 2 * v2 + rot / 2;
  for (int k = 0; k < 3; ++k) {
    if (!gravity[k].is_zero()) terms.V -= mass * gravity[k] * c[k];
  }
  if (!b.name.empty()) {
    terms.poses.emplace(b.name, std::make_pair(p, R));
    terms.frames.emplace(b.name, Frame{p, R, w});
  }
  s.body_names.push_back(b.name.empty() ? fmt::format("body{}", s.body_names.size()) : b.name);
  for (int k = 0; k < 3; ++k) terms.pose_outputs.push_back(p[k]);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) terms.pose_outputs.push_back(R[i][k]);
}

// A spring's end in the world frame: `point` carried by the pose of `body` (the world if empty).
Vec3 world_point(const Poses& poses, const std::string& body, const Eigen::Vector3d& point,
                 std::size_t s_index, const char* which) {
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
}

// Adds the springs' potentials to V: V = ½ k (|p_a − p_b| − L)², points carried by their
// bodies' poses.
void add_springs(const SystemSpec& spec, const ExpressionReader& reader, const Poses& poses, ex& V) {
  for (std::size_t j = 0; j < spec.springs.size(); ++j) {
    const Spring& sp = spec.springs[j];
    RIGID_REQUIRE_AS("System", !sp.body_a.empty(), "spring {}: body_a must name a body", j);
    const Vec3 a = world_point(poses, sp.body_a, sp.point_a_B, j, "body_a");
    const Vec3 b = world_point(poses, sp.body_b, sp.point_b_B, j, "body_b");
    const ex k = reader.parse(sp.stiffness, fmt::format("spring {} stiffness", j), false);
    const ex rest = reader.parse(sp.rest_length, fmt::format("spring {} rest_length", j), false);
    ex d2 = 0;
    for (int i = 0; i < 3; ++i) d2 += GiNaC::pow(a[i] - b[i], 2);
    d2 = d2.expand();
    V += rest.is_zero() ? k / 2 * d2 : k / 2 * GiNaC::pow(GiNaC::sqrt(d2) - rest, 2);
  }
}

// Splits a given Lagrangian: the velocity-dependent part counts as kinetic energy (T_given),
// the rest as −V (V_given).
void split_given_lagrangian(const System::Impl& s, const ex& L_given, ex& T_given, ex& V_given) {
  const ex Lg = simplify(L_given);
  const GiNaC::exvector terms = GiNaC::is_a<GiNaC::add>(Lg) ? GiNaC::exvector(Lg.begin(), Lg.end())
                                                            : GiNaC::exvector{Lg};
  for (const ex& term : terms) {
    bool has_velocity = false;
    for (const symbol& v : s.qd) has_velocity = has_velocity || term.has(v);
    (has_velocity ? T_given : V_given) += term;
  }
}

// Sets s.T, s.V and s.L from the bodies, springs, potentials and the given Lagrangian; returns
// the outputs of the mass and pose tapes.
// The gravity g_W (m/s², constants) and the given Lagrangian (0 when empty) of `spec`.
std::pair<Vec3, ex> gravity_and_given_lagrangian(const SystemSpec& spec, const ExpressionReader& reader) {
  Vec3 gravity;
  for (int k = 0; k < 3; ++k) gravity[k] = reader.parse_constant(spec.gravity_W[k], fmt::format("gravity[{}]", k));
  ex L_given = 0;
  if (spec.lagrangian.text.find_first_not_of(" \t") != std::string::npos) {
    L_given = reader.parse(spec.lagrangian, "Lagrangian", true).expand();
  }
  return {gravity, L_given};
}

BodyTerms derive_energies(System::Impl& s, const SystemSpec& spec, const ExpressionReader& reader) {
  // assemble T and V
  const auto [gravity, L_given] = gravity_and_given_lagrangian(spec, reader);
  BodyTerms terms;
  for (std::size_t i = 0; i < spec.bodies.size(); ++i) add_body(s, reader, spec, i, gravity, terms);
  add_springs(spec, reader, terms.poses, terms.V);
  for (const NamedExpression& pot : spec.potentials) {
    terms.V += reader.parse(pot.expression, fmt::format("potential '{}'", pot.name), false);
  }
  terms.T = simplify(terms.T);
  // the velocity-dependent part of a given L counts as kinetic energy, the rest as −V
  ex T_given = 0, V_given = 0;
  split_given_lagrangian(s, L_given, T_given, V_given);
  s.T = terms.T + T_given;
  s.V = simplify(terms.V - V_given);
  s.L = simplify(s.T - s.V);
  return terms;
}

// The ball coordinate `text` names (blanks around it ignored), or nullptr.
const System::Impl::Ball* find_ball(const System::Impl& s, const std::string& text) {
  const auto first = text.find_first_not_of(" \t"), last = text.find_last_not_of(" \t");
  if (first == std::string::npos) return nullptr;
  const std::string name = text.substr(first, last - first + 1);
  for (const System::Impl::Ball& b : s.balls) {
    if (b.name == name) return &b;
  }
  return nullptr;
}

// Why the tree's recursions do not derive `spec` (empty: they do); `depth` receives the most
// joints on one chain from the world.
std::string recursion_refusal(const System::Impl& s, const SystemSpec& spec,
                              const ExpressionReader& reader, int& depth) {
  depth = 0;
  if (!spec.springs.empty()) return "springs act between the bodies' points, not along a tree";
  if (spec.bodies.empty()) return "there are no bodies";
  std::map<std::string, int> depth_of;  // body name → joints from the world to it
  std::vector<bool> driven(s.q.size(), false);  // per entry of q (a ball: its w)
  for (std::size_t i = 0; i < spec.bodies.size(); ++i) {
    const Body& b = spec.bodies[i];
    const std::string who = b.name.empty() ? fmt::format("body{}", i) : b.name;
    if (!b.rotations.empty()) {
      return fmt::format("body '{}' turns by `rotations`; give its motion as joints", who);
    }
    int d = 0;
    if (!b.parent.empty()) {
      auto it = depth_of.find(b.parent);
      if (it == depth_of.end() || b.parent == b.name) {
        return fmt::format("body '{}' names the parent '{}', which is no earlier body", who, b.parent);
      }
      d = it->second;
    }
    for (int k = 0; k < 3; ++k) {
      if (b.position[k].text.find_first_not_of(" \t") == std::string::npos) continue;
      const ex x = reader.parse(b.position[k], fmt::format("body '{}' position[{}]", b.name, k), false);
      bool moves = x.has(s.t);
      for (const symbol& q : s.q) moves = moves || x.has(q);
      if (moves) return fmt::format("body '{}' has a position that moves; give its motion as joints", who);
    }
    const Eigen::Matrix3d& O = b.orientation;
    if (!O.allFinite() || (O.transpose() * O - Eigen::Matrix3d::Identity()).norm() >= 1e-12 ||
        O.determinant() <= 0) {
      return fmt::format("body '{}' has an orientation that is no rotation", who);
    }
    for (std::size_t j = 0; j < b.joints.size(); ++j) {
      const JointMotion& J = b.joints[j];
      const double norm = J.axis.norm();
      const bool ball = J.kind == JointMotion::Kind::kBall;
      if ((!ball && (!std::isfinite(norm) || norm <= 0)) || !J.anchor.allFinite()) {
        return fmt::format("body '{}' joint {} has no valid axis or anchor", who, j);
      }
      const System::Impl::Ball* named_ball = find_ball(s, J.amount.text);
      if (ball != (named_ball != nullptr)) {
        return ball ? fmt::format("body '{}' joint {} is a ball turned by '{}', which is no ball "
                                  "coordinate", who, j, J.amount.text)
                    : fmt::format("body '{}' joint {} is a {} by the ball coordinate '{}'; a ball "
                                  "coordinate turns a ball joint", who, j,
                                  J.kind == JointMotion::Kind::kTurn ? "turn" : "slide", J.amount.text);
      }
      std::size_t c = 0;
      if (ball) {
        c = named_ball->q;
      } else {
        const ex amount = reader.parse(J.amount, fmt::format("body '{}' joint {} {}", b.name, j,
                                       J.kind == JointMotion::Kind::kTurn ? "turn" : "slide"), false);
        auto it = std::find_if(s.q.begin(), s.q.end(), [&](const symbol& q) { return amount.is_equal(q); });
        if (it == s.q.end() || s.q_of_v.end() == std::find(s.q_of_v.begin(), s.q_of_v.end(),
                                                           static_cast<int>(it - s.q.begin()))) {
          return fmt::format("body '{}' joint {} moves by '{}', which is not a coordinate", who, j,
                             J.amount.text);
        }
        c = static_cast<std::size_t>(it - s.q.begin());
      }
      if (driven[c]) {
        return fmt::format("the coordinate '{}' drives two joints", ball ? named_ball->name : s.coord_names[c]);
      }
      driven[c] = true;
    }
    d += static_cast<int>(b.joints.size());
    depth = std::max(depth, d);
    depth_of[b.name] = d;
  }
  for (const System::Impl::Ball& ball : s.balls) {
    if (!driven[ball.q]) return fmt::format("the ball coordinate '{}' turns no ball joint", ball.name);
  }
  return {};
}

// Whether the bodies are derived by the tree's recursions (SystemSpec::Derivation).
bool use_recursion(const System::Impl& s, const SystemSpec& spec, const ExpressionReader& reader) {
  using Derivation = SystemSpec::Derivation;
  Derivation derivation = spec.derivation;
  if (!s.balls.empty()) {
    // a ball's velocity is no q̇: its equations are the tree's (Euler–Poincaré), not
    // Lagrange's of an expanded L
    RIGID_REQUIRE_AS("System", derivation != Derivation::kExpanded,
                     "the ball coordinate '{}' needs the recursive derivation (its velocity ω is "
                     "not the rate of its quaternion, so Lagrange's equations of the expanded L do "
                     "not apply); use derivation auto or recursive", s.balls.front().name);
    derivation = Derivation::kRecursive;
  }
  if (derivation == Derivation::kExpanded) return false;
  int depth = 0;
  const std::string why = recursion_refusal(s, spec, reader, depth);
  if (derivation == Derivation::kRecursive) {
    if (why.empty()) return true;
    rigid::detail::throw_error(
        "System", s.balls.empty()
                      ? fmt::format("the recursive derivation applies to a tree of bodies moved by "
                                    "joints; here {}", why)
                      : fmt::format("a system with the ball coordinate '{}' is derived by the tree's "
                                    "recursions, which apply to a tree of bodies moved by joints; here {}",
                                    s.balls.front().name, why));
  }
  return why.empty() && depth > SystemSpec::kAutoRecursiveDepth;
}

// A name fit to carry into the intermediates' names: letters, digits and '_'.
std::string name_part(const std::string& name) {
  std::string out = name;
  for (char& c : out) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return out;
}

// The bodies as the recursion takes them (recursion_refusal has passed), their mass
// properties into the mass outputs and their names into s.body_names.
std::vector<detail::TreeBody> tree_bodies(System::Impl& s, const SystemSpec& spec,
                                          const ExpressionReader& reader, BodyTerms& terms) {
  std::vector<detail::TreeBody> bodies;
  std::map<std::string, int> index;
  for (std::size_t i = 0; i < spec.bodies.size(); ++i) {
    const Body& b = spec.bodies[i];
    const std::string ctx = fmt::format("body '{}'", b.name);
    RIGID_REQUIRE_AS("System", b.name.empty() || !index.count(b.name), "body name '{}' is used twice",
                     b.name);
    detail::TreeBody t;
    t.name = name_part(b.name.empty() ? fmt::format("body{}", i) : b.name);
    t.parent = b.parent.empty() ? -1 : index.at(b.parent);
    for (int k = 0; k < 3; ++k) {
      const bool empty = b.position[k].text.find_first_not_of(" \t") == std::string::npos;
      t.position[k] = empty ? ex(0) : reader.parse(b.position[k], fmt::format("{} position[{}]", ctx, k), false);
    }
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) t.orientation[r][c] = number(b.orientation(r, c));
    for (const JointMotion& J : b.joints) {
      if (J.kind == JointMotion::Kind::kBall) {
        const System::Impl::Ball* ball = find_ball(s, J.amount.text);
        t.joints.push_back({false, Eigen::Vector3d::UnitZ(), J.anchor, ball->v, true, ball->q});
        continue;
      }
      const ex amount = reader.parse(J.amount, ctx, false);
      const auto it = std::find_if(s.q.begin(), s.q.end(), [&](const symbol& q) { return amount.is_equal(q); });
      const auto q = static_cast<std::size_t>(it - s.q.begin());
      const auto v = static_cast<std::size_t>(
          std::find(s.q_of_v.begin(), s.q_of_v.end(), static_cast<int>(q)) - s.q_of_v.begin());
      t.joints.push_back({J.kind == JointMotion::Kind::kTurn, J.axis / J.axis.norm(), J.anchor, v});
    }
    t.mass = reader.parse_constant(b.mass.mass, ctx + " mass");
    for (int k = 0; k < 3; ++k) t.com[k] = reader.parse_constant(b.mass.com[k], fmt::format("{} com[{}]", ctx, k));
    for (std::size_t k = 0; k < 6; ++k) {
      const auto& [name, row, col] = BodyMass::kInertiaElements[k];
      t.inertia[row][col] = t.inertia[col][row] = reader.parse_constant(b.mass.inertia[k], ctx + " " + name);
    }
    terms.mass_outputs.push_back(t.mass);
    for (int k = 0; k < 3; ++k) terms.mass_outputs.push_back(t.com[k]);
    for (const auto& e : BodyMass::kInertiaElements) terms.mass_outputs.push_back(t.inertia[e.row][e.col]);
    if (!b.name.empty()) index.emplace(b.name, static_cast<int>(i));
    s.body_names.push_back(b.name.empty() ? fmt::format("body{}", s.body_names.size()) : b.name);
    bodies.push_back(std::move(t));
  }
  return bodies;
}

// The recursive derivation (SystemSpec::Derivation): the bodies' M, bias forces, T and V by
// the tree's recursions (recursive.cpp), the given Lagrangian and the potentials by Lagrange's
// equations of their own (they are expressions of q, q̇ and t); sets s.T, V, L, h, M, f (but
// the generalized forces) and f_potential; returns the outputs of the mass and pose tapes.
BodyTerms derive_recursive(System::Impl& s, const SystemSpec& spec, const ExpressionReader& reader,
                           const Names& names) {
  const auto n = static_cast<std::size_t>(s.n);
  const auto [gravity, L_given] = gravity_and_given_lagrangian(spec, reader);
  BodyTerms terms;
  const std::vector<detail::TreeBody> bodies = tree_bodies(s, spec, reader, terms);
  std::set<std::string> taken(reserved_names());
  for (const auto& [name, _] : names) taken.insert(name);
  const detail::TreeEquations tree = detail::tree_equations(s, bodies, gravity, taken);
  s.tree_bodies = bodies;
  s.tree_gravity = gravity;
  s.tree_M = tree.M;
  s.tree_bias.resize(n);
  for (std::size_t i = 0; i < n; ++i) s.tree_bias[i] = (tree.inertial[i] + tree.gravity[i]).expand();
  for (const auto& [p, R] : tree.poses) {
    for (int k = 0; k < 3; ++k) terms.pose_outputs.push_back(p[k]);
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) terms.pose_outputs.push_back(R[i][k]);
  }
  // the rest of L: L_extra = (velocity part of L_given) + (the rest of L_given) − Σ potentials
  ex V_pot = 0;
  for (const NamedExpression& pot : spec.potentials) {
    V_pot += reader.parse(pot.expression, fmt::format("potential '{}'", pot.name), false);
  }
  ex T_given = 0, V_given = 0;
  split_given_lagrangian(s, L_given, T_given, V_given);
  const ex V_extra = simplify(V_pot - V_given);
  const ex L_extra = T_given - V_extra;
  s.T = tree.T + T_given;
  s.V = tree.V + V_extra;
  s.L = s.T - s.V;
  s.M = tree.M;
  s.f.resize(n);
  s.f_potential.resize(n);
  // a ball's velocity ω is no q̇: L_extra's generalized force on it is Nᵀ ∂L/∂q over its
  // quaternion (N = ∂q̇/∂ω, the virtual work of a turn), and its momentum ∂L/∂ω adds
  // Euler–Poincaré's (∂L/∂ω) × ω [Holm, Schmah and Stoica 2009, §7.3]; both hold where the
  // velocity part of L does not depend on the quaternion, which is refused otherwise
  for (const System::Impl::Ball& b : s.balls) {
    for (std::size_t r = 0; r < 4; ++r) {
      if (T_given.has(s.q[b.q + r])) {
        rigid::detail::throw_error("System", fmt::format(
            "the Lagrangian's velocity-dependent part depends on the ball coordinate's '{}'; "
            "a term of q̇ may depend on the hinges' and slides' coordinates, not on a ball's "
            "orientation", s.coord_names[b.q + r]));
      }
    }
  }
  // ∂L/∂(entry v of the velocities) through the coordinates: ∂L/∂q of its coordinate, or
  // (Nᵀ ∂L/∂q)_k for component k of a ball's ω
  auto coordinate_force = [&](const ex& L, std::size_t v) -> ex {
    if (s.q_of_v[v] >= 0) return d(L, s.q[static_cast<std::size_t>(s.q_of_v[v])]);
    for (const System::Impl::Ball& b : s.balls) {
      if (v < b.v || v >= b.v + 3) continue;
      ex sum = 0;
      for (std::size_t r = 0; r < 4; ++r) sum += d(s.q_rate[b.q + r], s.qd[v]) * d(L, s.q[b.q + r]);
      return sum;
    }
    return 0;
  };
  std::vector<ex> p(n);
  for (std::size_t i = 0; i < n; ++i) p[i] = d(L_extra, s.qd[i]);
  ex h = tree.T + tree.V - L_extra;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) s.M[i * n + j] = (s.M[i * n + j] + d(p[i], s.qd[j])).expand();
    if (s.M[i * n + i].is_zero()) {
      const std::string& c = s.q_of_v[i] >= 0 ? s.coord_names[static_cast<std::size_t>(s.q_of_v[i])]
                                              : s.velocity_names[i];
      rigid::detail::throw_error("System", fmt::format("no body moves with the coordinate '{}' and the "
                  "Lagrangian is not quadratic in '{}', so the mass matrix is singular",
                  c, s.velocity_names[i]));
    }
    ex fi = tree.inertial[i] + tree.gravity[i] + coordinate_force(L_extra, i) - d(p[i], s.t);
    for (std::size_t j = 0; j < s.q.size(); ++j) fi -= d(p[i], s.q[j]) * s.q_rate[j];
    s.f[i] = fi;
    s.f_potential[i] = (tree.gravity[i] - coordinate_force(V_extra, i)).expand();
    h += s.qd[i] * p[i];
  }
  for (const System::Impl::Ball& b : s.balls) {
    // (∂L/∂ω) × ω, body frame
    for (std::size_t k = 0; k < 3; ++k) {
      const std::size_t k1 = b.v + (k + 1) % 3, k2 = b.v + (k + 2) % 3;
      s.f[b.v + k] += p[k1] * s.qd[k2] - p[k2] * s.qd[k1];
    }
  }
  for (ex& fi : s.f) fi = fi.expand();
  s.h = h.expand();
  return terms;
}

// Sets s.Q, the generalized forces on the coordinates; returns which coordinates have one.
std::vector<bool> derive_generalized_forces(System::Impl& s, const SystemSpec& spec,
                                            const ExpressionReader& reader) {
  std::vector<ex> Q(static_cast<std::size_t>(s.n), 0);
  std::vector<bool> forced(static_cast<std::size_t>(s.n), false);
  // a force acts on a coordinate by its name, or on a ball's ω_k (a torque about the body's
  // axis k, N·m) by the velocity's name b_wx, b_wy, b_wz
  std::vector<std::string> targets(static_cast<std::size_t>(s.n));
  for (std::size_t v = 0; v < targets.size(); ++v) {
    targets[v] = s.q_of_v[v] >= 0 ? s.coord_names[static_cast<std::size_t>(s.q_of_v[v])] : s.velocity_names[v];
  }
  for (const NamedExpression& F : spec.forces) {
    auto it = std::find(targets.begin(), targets.end(), F.name);
    if (it == targets.end()) {
      std::string known;
      for (const auto& c : targets) known += (known.empty() ? "" : ", ") + c;
      rigid::detail::throw_error("System", fmt::format("force on '{}': no coordinate of that name; coordinates: {}", F.name, known));
    }
    const auto i = static_cast<std::size_t>(it - targets.begin());
    Q[i] += reader.parse(F.expression, fmt::format("force on '{}'", F.name), true);
    forced[i] = true;
  }
  s.Q = Q;
  return forced;
}

// Refuses a derived quantity whose expanded form would exceed kMaxEquationNodes, estimated
// before anything is expanded: the derivatives of an accepted L can still multiply out far
// beyond it (the chain rule through a power whose exponent is a long sum makes every term of
// one factor hold all of another).
// `what` names the quantity, called only for the refusal (not once per entry of M).
template <typename What>
void refuse_beyond_expansion_limit(const ex& e, const What& what, std::string_view derived_from) {
  const double size = detail::expanded_size_log10(e);
  if (size <= std::log10(kMaxEquationNodes)) return;
  rigid::detail::throw_error(
      "System", fmt::format("{} multiplies out to about 10^{:.3g} symbols and operations (products of long "
                            "sums in the derivatives of {}); at most {:.0f} are allowed, since the "
                            "equations are derived, compiled and printed expanded",
                            what(), size, derived_from, kMaxEquationNodes));
}

// Euler–Lagrange: p = ∂L/∂q̇, M = ∂p/∂q̇, f = ∂L/∂q − (∂p/∂q) q̇ − ∂p/∂t + Q, and the
// Jacobi integral h = q̇ᵀ p − L; refuses a singular M.
void derive_euler_lagrange(System::Impl& s) {
  const auto n = static_cast<std::size_t>(s.n);
  s.p.resize(n);
  s.M.assign(n * n, 0);
  s.f.resize(n);
  for (std::size_t i = 0; i < n; ++i) s.p[i] = d(s.L, s.qd[i]);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      s.M[i * n + j] = d(s.p[i], s.qd[j]);
      refuse_beyond_expansion_limit(s.M[i * n + j], [&] {
        return fmt::format("the mass matrix entry ('{}', '{}')", s.coord_names[i], s.coord_names[j]);
      }, "the Lagrangian");
    }
    if (s.M[i * n + i].expand().is_zero()) {
      rigid::detail::throw_error("System", fmt::format("the Lagrangian is not quadratic in the velocity '{}_dot' (∂²L/∂{}_dot² ≡ 0), "
                  "so the mass matrix is singular; L = {}", s.coord_names[i], s.coord_names[i],
                  to_text(s.L)));
    }
    ex fi = d(s.L, s.q[i]) - d(s.p[i], s.t) + s.Q[i];
    for (std::size_t j = 0; j < n; ++j) fi -= d(s.p[i], s.q[j]) * s.qd[j];
    refuse_beyond_expansion_limit(fi, [&] { return fmt::format("the equation of motion of '{}'", s.coord_names[i]); },
                                  "the Lagrangian");
    s.f[i] = fi.expand();
  }
  s.h = 0;
  for (std::size_t i = 0; i < n; ++i) s.h += s.qd[i] * s.p[i];
  s.h = simplify(s.h - s.L);
}

// Holonomic constraints: g, G = ∂g/∂q, ġ = G q̇ + ∂g/∂t, γ = −(∂ġ/∂q q̇ + ∂ġ/∂t) and the
// multipliers' symbols into `s`; returns which coordinates a constraint involves.
std::vector<bool> derive_constraints(System::Impl& s, const SystemSpec& spec,
                                     const ExpressionReader& reader) {
  const auto n = static_cast<std::size_t>(s.n);
  std::vector<bool> constrained(n, false);
  for (const NamedExpression& con : spec.constraints) {
    RIGID_REQUIRE_AS("System", is_identifier(con.name), "constraint name '{}' is not a valid name", con.name);
    RIGID_REQUIRE_AS("System", std::find(s.constraint_names.begin(), s.constraint_names.end(), con.name) ==
                      s.constraint_names.end(),
                  "constraint name '{}' is used twice", con.name);
    const ex gk = reader.parse(con.expression, fmt::format("constraint '{}'", con.name), false).expand();
    bool depends = false;
    for (std::size_t i = 0; i < n; ++i) {
      const ex Gki = d(gk, s.q[i]);
      s.G.push_back(Gki);
      if (!Gki.is_zero()) depends = constrained[i] = true;
    }
    RIGID_REQUIRE_AS("System", depends, "constraint '{}' = {} does not depend on any coordinate; it is either "
                  "always or never satisfied", con.name, to_text(gk));
    const ex c_unexpanded = time_derivative(s, gk);
    refuse_beyond_expansion_limit(c_unexpanded, [&] { return fmt::format("the rate ġ of constraint '{}'", con.name); },
                                  "the constraint");
    const ex ck = c_unexpanded.expand();
    ex gamma = -d(ck, s.t);
    for (std::size_t j = 0; j < n; ++j) gamma -= d(ck, s.q[j]) * s.qd[j];
    refuse_beyond_expansion_limit(
        gamma, [&] { return fmt::format("the acceleration term γ of constraint '{}'", con.name); }, "the constraint");
    s.g.push_back(gk);
    s.c.push_back(ck);
    s.gamma.push_back(gamma.expand());
    s.constraint_names.push_back(con.name);
    s.lambda.emplace_back("lambda_" + con.name, "\\lambda_{\\mathrm{" + con.name + "}}");
  }
  return constrained;
}

// Cyclic coordinates: neither forced nor constrained, and L does not depend on them.
void find_cyclic_coordinates(System::Impl& s, const std::vector<bool>& forced,
                             const std::vector<bool>& constrained) {
  const auto n = static_cast<std::size_t>(s.n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!forced[i] && !constrained[i] && d(s.L, s.q[i]).expand().is_zero()) {
      s.cyclic_index.push_back(static_cast<int>(i));
      s.cyclic_names.push_back(s.coord_names[i]);
    }
  }
}

// Whether Störmer–Verlet applies: M constant, f not dependent on q̇, and no constraints.
bool verlet_applies(const System::Impl& s) {
  const auto n = static_cast<std::size_t>(s.n);
  bool ok = s.m == 0 && s.r == 0;
  for (std::size_t i = 0; i < n && ok; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      for (std::size_t k = 0; k < n; ++k) {
        if (s.M[i * n + j].has(s.q[k]) || s.f[i].has(s.qd[k])) ok = false;
      }
      if (s.M[i * n + j].has(s.t)) ok = false;
    }
  }
  return ok;
}

// Compiles the dynamics, diagnostics and pose tapes (inputs q, q̇, t, parameters) and the
// mass tape (inputs: the parameters).
void compile_tapes(System::Impl& s, const BodyTerms& terms) {
  const auto n = static_cast<std::size_t>(s.n);
  std::vector<symbol> inputs;
  inputs.insert(inputs.end(), s.q.begin(), s.q.end());
  inputs.insert(inputs.end(), s.qd.begin(), s.qd.end());
  inputs.push_back(s.t);
  inputs.insert(inputs.end(), s.params.begin(), s.params.end());
  detail::TapeBuilder dyn(inputs, inputs.size() - s.params.size());
  detail::define_intermediates(dyn, s);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) dyn.add_output(s.M[i * n + j]);
  for (const ex& e : s.f) dyn.add_output(e);
  for (const ex& e : s.G) dyn.add_output(e);
  for (const ex& e : s.gamma) dyn.add_output(e);
  for (const ex& e : s.c) dyn.add_output(e);
  for (const ex& e : s.g) dyn.add_output(e);
  s.dyn = dyn.build();
  detail::TapeBuilder diag(inputs);
  detail::define_intermediates(diag, s);
  diag.add_output(simplify(s.T + s.V));
  diag.add_output(s.h);
  for (int i : s.cyclic_index) diag.add_output(s.p[static_cast<std::size_t>(i)]);
  s.diag = diag.build();
  detail::TapeBuilder pose(inputs);
  detail::define_intermediates(pose, s);
  for (const ex& e : terms.pose_outputs) pose.add_output(e);
  s.pose = pose.build();

  std::vector<symbol> param_inputs(s.params.begin(), s.params.end());
  detail::TapeBuilder masses(param_inputs);
  for (const ex& e : terms.mass_outputs) masses.add_output(e);
  s.masses = masses.build();
}

// Parses, assembles, derives and compiles `spec` into `s` (under the symbolic lock).
void derive(System::Impl& s, const SystemSpec& spec) {
  for (const Coordinate& c : spec.coordinates) {
    const bool ball = c.kind == Coordinate::Kind::kBall;
    s.n += ball ? 3 : 1;
    s.nq += ball ? 4 : 1;
  }
  s.m = static_cast<int>(spec.constraints.size());
  RIGID_REQUIRE_AS("System", s.n > 0, "a system needs at least one coordinate, got none");

  // symbol table, with every name checked once
  Names names;
  declare_symbols(s, spec, names);
  // a coordinate that is a joint's amount as written has that joint's unit
  s.joint_unit.assign(static_cast<std::size_t>(s.nq), "");
  for (const Body& b : spec.bodies) {
    for (const JointMotion& J : b.joints) {
      const std::string& a = J.amount.text;
      const auto first = a.find_first_not_of(" \t"), last = a.find_last_not_of(" \t");
      if (first == std::string::npos) continue;
      const auto it = std::find(s.coord_names.begin(), s.coord_names.end(), a.substr(first, last - first + 1));
      if (it == s.coord_names.end()) continue;
      std::string& unit = s.joint_unit[static_cast<std::size_t>(it - s.coord_names.begin())];
      const std::string mine = J.kind == JointMotion::Kind::kTurn ? "rad" : "m";
      unit = unit.empty() || unit == mine ? mine : "mixed";
    }
  }
  const ExpressionReader reader(s, names);

  // T, V and L; generalized forces; the Euler–Lagrange equations (of the expanded L, or by
  // the tree's recursions)
  const bool recursive = use_recursion(s, spec, reader);
  const BodyTerms terms = recursive ? derive_recursive(s, spec, reader, names)
                                    : derive_energies(s, spec, reader);
  const std::vector<bool> forced = derive_generalized_forces(s, spec, reader);
  if (recursive) {
    for (std::size_t i = 0; i < s.f.size(); ++i) s.f[i] = (s.f[i] + s.Q[i]).expand();
  } else {
    derive_euler_lagrange(s);
  }

  if (!s.balls.empty() && (!spec.constraints.empty() || !spec.velocity_constraints.empty())) {
    s.refuse_balls(spec.constraints.empty() ? "velocity constraints" : "constraints");
  }
  // constraints: G = ∂g/∂q, ġ = G q̇ + ∂g/∂t, γ = −(∂ġ/∂q q̇ + ∂ġ/∂t)
  std::vector<bool> constrained = derive_constraints(s, spec, reader);
  // velocity (nonholonomic) constraints A q̇ + a = 0 (velocity_constraints.cpp)
  detail::derive_velocity_constraints(spec, s, names, constrained);

  // the recursion's intermediates hide which coordinates L and M depend on: no coordinate is
  // called cyclic and Störmer–Verlet is not offered (both are conservative)
  if (!recursive) {
    find_cyclic_coordinates(s, forced, constrained);
    s.verlet_ok = verlet_applies(s);
  }

  // compile: inputs (q, q̇, t, parameters)
  compile_tapes(s, terms);
  s.check_masses(s.param_values, "for the parameters' values");
}

}  // namespace

System::System(const SystemSpec& spec) {
  detail::SymbolicLock lock;
  // built aside, so that a throw destroys the partial expressions while the lock is held
  auto impl = std::make_unique<Impl>();
  try {
    derive(*impl, spec);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    // GiNaC or CLN failing on what the parser accepted: a derivative with a pole (d/dq 0^q has
    // log 0), an exact power expanded beyond CLN's integers; worded, not their own texts
    throw Error(fmt::format(
        "a term of the Lagrangian, its energies or their derivatives {} (a power of 0 whose "
        "exponent depends on a coordinate, velocity or time has no derivative)",
        detail::reason_of_library_failure(e)));
  }
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

int System::num_coordinates() const { return impl_->nq; }
int System::num_velocities() const { return impl_->n; }
const std::vector<std::string>& System::velocity_names() const { return impl_->velocity_names; }
bool System::has_ball_coordinates() const { return !impl_->balls.empty(); }

void System::Impl::refuse_balls(std::string_view what) const {
  if (balls.empty()) return;
  throw Error(fmt::format("{} of a system with ball coordinates (here '{}': a ball or free joint) "
                          "are not supported yet; its equations, runs and sweeps are",
                          what, balls.front().name));
}

void System::Impl::coordinate_rates(const double* qv, const double* v, double* out) const {
  for (std::size_t i = 0; i < q_of_v.size(); ++i) {
    if (q_of_v[i] >= 0) out[q_of_v[i]] = v[i];
  }
  for (const Ball& b : balls) {
    // ½ q ⊗ (0, ω)
    const double w = qv[b.q], x = qv[b.q + 1], y = qv[b.q + 2], z = qv[b.q + 3];
    const double wx = v[b.v], wy = v[b.v + 1], wz = v[b.v + 2];
    out[b.q] = -0.5 * (x * wx + y * wy + z * wz);
    out[b.q + 1] = 0.5 * (w * wx + y * wz - z * wy);
    out[b.q + 2] = 0.5 * (w * wy + z * wx - x * wz);
    out[b.q + 3] = 0.5 * (w * wz + x * wy - y * wx);
  }
}

Eigen::VectorXd System::coordinate_rates(const Eigen::VectorXd& q, const Eigen::VectorXd& q_dot) const {
  const Impl& s = *impl_;
  RIGID_REQUIRE(q.size() == s.nq && q_dot.size() == s.n,
                "expected q of size {} and q_dot of size {}, got {} and {}", s.nq, s.n, q.size(),
                q_dot.size());
  Eigen::VectorXd out(s.nq);
  s.coordinate_rates(q.data(), q_dot.data(), out.data());
  return out;
}
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
