#include "rigid/lagrange/system.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <fmt/format.h>
#include <ginac/ginac.h>

#include "rigid/common/format.hpp"
#include "detail/parser.hpp"
#include "detail/tape.hpp"

namespace rigid::lagrange {
namespace {

using GiNaC::ex;
using GiNaC::symbol;

bool is_identifier(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  return std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  });
}

const std::set<std::string>& reserved_names() {
  static const std::set<std::string> kReserved = {
      "t", "pi", "sin", "cos", "tan", "asin", "acos", "atan", "exp", "log", "sqrt", "abs",
      "sinh", "cosh", "tanh"};
  return kReserved;
}

// TeX for a name: Greek letter names become the letter, trailing digits or "_x" a subscript
std::string tex_name(const std::string& name) {
  static const std::set<std::string> kGreek = {
      "alpha", "beta",  "gamma", "delta", "epsilon", "zeta", "eta",   "theta", "iota",
      "kappa", "lambda", "mu",   "nu",    "xi",      "rho",  "sigma", "tau",   "upsilon",
      "phi",   "chi",   "psi",   "omega", "Gamma",   "Delta", "Theta", "Lambda", "Xi",
      "Pi",    "Sigma", "Phi",   "Psi",   "Omega"};
  std::string base = name, sub;
  if (auto u = name.find('_'); u != std::string::npos && u > 0) {
    base = name.substr(0, u);
    sub = name.substr(u + 1);
  } else {
    auto d = name.find_last_not_of("0123456789");
    if (d != std::string::npos && d + 1 < name.size()) {
      base = name.substr(0, d + 1);
      sub = name.substr(d + 1);
    }
  }
  std::string out = kGreek.count(base) ? "\\" + base : (base.size() > 1 ? "\\mathrm{" + base + "}" : base);
  if (!sub.empty()) out += "_{" + sub + "}";
  return out;
}

// sinⁿx → sin^(n mod 2)x · (1 − cos²x)^(n/2) for n ≥ 2, so that expand() cancels the
// sin² + cos² pairs that |ċ|² and ωᵀIω produce
struct ReduceSines : GiNaC::map_function {
  ex operator()(const ex& e) override {
    if (GiNaC::is_a<GiNaC::power>(e) && GiNaC::is_a<GiNaC::function>(e.op(0)) &&
        GiNaC::ex_to<GiNaC::function>(e.op(0)).get_name() == "sin" &&
        GiNaC::is_a<GiNaC::numeric>(e.op(1)) && GiNaC::ex_to<GiNaC::numeric>(e.op(1)).is_integer()) {
      const long n = GiNaC::ex_to<GiNaC::numeric>(e.op(1)).to_long();
      if (n >= 2) {
        const ex x = e.op(0).op(0);
        return GiNaC::pow(GiNaC::sin(x), n % 2) * GiNaC::pow(1 - GiNaC::pow(GiNaC::cos(x), 2), n / 2);
      }
    }
    return e.map(*this);
  }
};

// ∂e/∂x by the sum, product, power and chain rules. GiNaC's own ex::diff signals "no explicit
// derivative" of sin/cos by throwing and catching an exception per call, which dominated the
// derivation time; subtrees free of x are skipped.
ex d(const ex& e, const symbol& x) {
  using namespace GiNaC;
  if (is_a<symbol>(e)) return e.is_equal(x) ? 1 : 0;
  if (is_a<numeric>(e) || is_a<constant>(e) || !e.has(x)) return 0;
  if (is_a<add>(e)) {
    exvector terms;
    terms.reserve(e.nops());
    for (const ex& term : e) terms.push_back(d(term, x));
    return add(terms);
  }
  if (is_a<mul>(e)) {
    exvector terms;
    const exvector factors(e.begin(), e.end());
    for (std::size_t i = 0; i < factors.size(); ++i) {
      ex di = d(factors[i], x);
      if (di.is_zero()) continue;
      exvector f = factors;
      f[i] = di;
      terms.push_back(mul(f));
    }
    return add(terms);
  }
  if (is_a<power>(e)) {
    const ex b = e.op(0), p = e.op(1);
    if (!p.has(x)) return p * pow(b, p - 1) * d(b, x);
    return e * (d(p, x) * log(b) + p * d(b, x) / b);
  }
  if (is_a<function>(e) && e.nops() == 1) {
    const std::string name = ex_to<function>(e).get_name();
    const ex a = e.op(0), da = d(a, x);
    if (name == "sin") return cos(a) * da;
    if (name == "cos") return -sin(a) * da;
    if (name == "tan") return (1 + pow(tan(a), 2)) * da;
    if (name == "asin") return da / sqrt(1 - pow(a, 2));
    if (name == "acos") return -da / sqrt(1 - pow(a, 2));
    if (name == "atan") return da / (1 + pow(a, 2));
    if (name == "exp") return exp(a) * da;
    if (name == "log") return da / a;
    if (name == "sinh") return cosh(a) * da;
    if (name == "cosh") return sinh(a) * da;
    if (name == "tanh") return (1 - pow(tanh(a), 2)) * da;
  }
  return e.diff(x);
}

ex simplify(const ex& e) {
  ReduceSines reduce;
  return reduce(e.expand()).expand();
}

std::string to_text(const ex& e) {
  std::ostringstream os;
  os << e;
  return os.str();
}
std::string to_latex(const ex& e) {
  std::ostringstream os;
  os << GiNaC::latex << e;
  return os.str();
}

// a double as the exact rational of its shortest round-trip decimal (0.7 → 7/10), so that
// printed equations show 7/10 rather than 0.6999999999999999556 and products stay exact
ex number(double v) {
  if (v == std::round(v) && std::abs(v) < 1e15) return GiNaC::numeric(static_cast<long>(v));
  const std::string text = fmt::format("{}", v);
  std::string digits;
  long scale = 0;
  bool fraction = false, negative = false;
  std::size_t k = 0;
  if (k < text.size() && text[k] == '-') {
    negative = true;
    ++k;
  }
  for (; k < text.size(); ++k) {
    const char c = text[k];
    if (c == '.') {
      fraction = true;
    } else if (c == 'e' || c == 'E') {
      scale += std::stol(text.substr(k + 1));
      break;
    } else {
      digits += c;
      if (fraction) --scale;
    }
  }
  const GiNaC::numeric r = GiNaC::numeric(digits.c_str()) * GiNaC::numeric(10).power(scale);
  return negative ? -r : r;
}

using Mat3 = std::array<std::array<ex, 3>, 3>;
using Vec3 = std::array<ex, 3>;

Mat3 mat_mul(const Mat3& A, const Mat3& B) {
  Mat3 C;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) C[i][j] = A[i][0] * B[0][j] + A[i][1] * B[1][j] + A[i][2] * B[2][j];
  return C;
}
Vec3 mat_vec(const Mat3& A, const Vec3& v) {
  Vec3 w;
  for (int i = 0; i < 3; ++i) w[i] = A[i][0] * v[0] + A[i][1] * v[1] + A[i][2] * v[2];
  return w;
}
Vec3 mat_t_vec(const Mat3& A, const Vec3& v) {
  Vec3 w;
  for (int i = 0; i < 3; ++i) w[i] = A[0][i] * v[0] + A[1][i] * v[1] + A[2][i] * v[2];
  return w;
}
Mat3 identity3() {
  Mat3 I;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) I[i][j] = i == j ? 1 : 0;
  return I;
}

// R = exp(θ[a]ₓ) = 1 + sin θ [a]ₓ + (1 − cos θ)[a]ₓ² (Rodrigues), a a unit vector
Mat3 rodrigues(const Eigen::Vector3d& a, const ex& theta) {
  const Vec3 u{number(a.x()), number(a.y()), number(a.z())};
  const ex s = GiNaC::sin(theta), c = GiNaC::cos(theta);
  Mat3 K;
  K[0] = {0, -u[2], u[1]};
  K[1] = {u[2], 0, -u[0]};
  K[2] = {-u[1], u[0], 0};
  const Mat3 K2 = mat_mul(K, K);
  Mat3 R = identity3();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[i][j] = (R[i][j] + s * K[i][j] + (1 - c) * K2[i][j]).expand();
  return R;
}

}  // namespace

struct System::Impl {
  // symbols and names
  std::vector<std::string> coord_names, constraint_names, cyclic_names, param_names;
  std::vector<double> param_values;
  std::vector<symbol> q, qd, qdd, params, lambda;
  symbol t{"t"};
  Eigen::VectorXd q0, qd0;
  // derived expressions
  ex L, T, V, h;
  std::vector<ex> M, f, G, gamma, g, c, p;
  std::vector<int> cyclic_index;
  bool verlet_ok = false;
  // compiled
  detail::Tape dyn, diag, pose;
  std::vector<std::string> body_names;
  int n = 0, m = 0;
  // work space (the evaluation is not re-entrant)
  mutable std::vector<double> in, out, diag_out;
  mutable Eigen::MatrixXd Mw, Gw, Yw, Sw;
  mutable Eigen::VectorXd fw, gammaw, cw, gw, Minv_f, rhs_m;
  mutable Eigen::LLT<Eigen::MatrixXd> llt_M;
  mutable Eigen::LDLT<Eigen::MatrixXd> ldlt_S;
  mutable double mass_scale = 0.0;  // largest pivot of M at the start of a run

  void load_inputs(double time, const Eigen::VectorXd& qv, const Eigen::VectorXd& qdv) const {
    for (int i = 0; i < n; ++i) {
      in[static_cast<std::size_t>(i)] = qv[i];
      in[static_cast<std::size_t>(n + i)] = qdv[i];
    }
    in[static_cast<std::size_t>(2 * n)] = time;
    std::copy(param_values.begin(), param_values.end(), in.begin() + 2 * n + 1);
  }

  std::string state_text(double time, const Eigen::VectorXd& qv) const {
    std::string s = fmt::format("t = {} s, q = (", time);
    for (int i = 0; i < n; ++i) {
      s += fmt::format("{}{} = {}", i ? ", " : "", coord_names[static_cast<std::size_t>(i)], qv[i]);
    }
    return s + ")";
  }

  void evaluate_dynamics(double time, const Eigen::VectorXd& qv, const Eigen::VectorXd& qdv) const {
    load_inputs(time, qv, qdv);
    dyn.evaluate(in.data(), out.data());
    std::size_t k = 0;
    for (int i = 0; i < n; ++i)
      for (int j = i; j < n; ++j) Mw(i, j) = Mw(j, i) = out[k++];
    for (int i = 0; i < n; ++i) fw[i] = out[k++];
    for (int a = 0; a < m; ++a)
      for (int i = 0; i < n; ++i) Gw(a, i) = out[k++];
    for (int a = 0; a < m; ++a) gammaw[a] = out[k++];
    for (int a = 0; a < m; ++a) cw[a] = out[k++];
    for (int a = 0; a < m; ++a) gw[a] = out[k++];
  }

  void solve(double time, const Eigen::VectorXd& qv, Eigen::VectorXd& qdd_out,
             Eigen::VectorXd& lambda_out, double alpha) const {
    llt_M.compute(Mw);
    bool singular = llt_M.info() != Eigen::Success;
    if (!singular) {
      // pivots of the Cholesky factor: M is numerically singular when the smallest squared
      // pivot falls below 1e-13 of the largest (condition number ≳ 1e13)
      // (or since the start of the run)
      // (a loop rather than minCoeff(): g++ 12 -O3 reports a false null dereference in
      // Eigen's vectorised reduction here)
      double dmin = std::numeric_limits<double>::infinity(), dmax = 0.0;
      for (Eigen::Index i = 0; i < n; ++i) {
        const double di = llt_M.matrixLLT()(i, i) * llt_M.matrixLLT()(i, i);
        dmin = std::min(dmin, di);
        dmax = std::max(dmax, di);
      }
      singular = !(dmin > 1e-13 * std::max(dmax, mass_scale));
    }
    if (singular) {
      rigid::detail::throw_error(
          "lagrange::System",
          fmt::format("mass matrix M = ∂²L/∂q̇∂q̇ is singular or not positive definite at {}; "
                      "M = {}. Every coordinate needs a positive kinetic energy term",
                      state_text(time, qv), rigid::to_string(Mw)));
    }
    Minv_f = llt_M.solve(fw);
    if (m == 0) {
      qdd_out = Minv_f;
      lambda_out.resize(0);
      return;
    }
    Yw = llt_M.solve(Gw.transpose());
    Sw.noalias() = Gw * Yw;
    ldlt_S.compute(Sw);
    const Eigen::VectorXd dS = ldlt_S.vectorD();
    if (ldlt_S.info() != Eigen::Success ||
        !(dS.minCoeff() > 1e-12 * std::max(1e-300, dS.cwiseAbs().maxCoeff()))) {
      rigid::detail::throw_error(
          "lagrange::System",
          fmt::format("the constraint Jacobian ∂g/∂q lost rank at {}: the constraints are "
                      "dependent there (G = {})", state_text(time, qv), rigid::to_string(Gw)));
    }
    // λ = (G M⁻¹ Gᵀ)⁻¹ (γ − 2α ġ − α² g − G M⁻¹ f);  q̈ = M⁻¹ f + M⁻¹ Gᵀ λ
    rhs_m = gammaw - 2.0 * alpha * cw - alpha * alpha * gw - Gw * Minv_f;
    lambda_out = ldlt_S.solve(rhs_m);
    qdd_out = Minv_f + Yw * lambda_out;
  }
};

System::System(const SystemSpec& spec) : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.n = static_cast<int>(spec.coordinates.size());
  s.m = static_cast<int>(spec.constraints.size());
  RIGID_REQUIRE(s.n > 0, "a system needs at least one coordinate, got none");

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
    RIGID_REQUIRE(std::isfinite(p.value), "parameter '{}' must be finite, got {}", p.name, p.value);
    s.params.emplace_back(p.name, tex_name(p.name));
    s.param_names.push_back(p.name);
    s.param_values.push_back(p.value);
    declare(p.name, "parameter", s.params.back());
  }
  s.q0.resize(s.n);
  s.qd0.resize(s.n);
  for (int i = 0; i < s.n; ++i) {
    const Coordinate& c = spec.coordinates[static_cast<std::size_t>(i)];
    RIGID_REQUIRE(std::isfinite(c.initial) && std::isfinite(c.velocity),
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

  // assemble T and V
  ex T_bodies = 0, V = 0, L_given = 0;
  if (spec.lagrangian.text.find_first_not_of(" \t") != std::string::npos) {
    L_given = parse(spec.lagrangian, "Lagrangian", true).expand();
  }
  std::map<std::string, std::pair<Vec3, Mat3>> poses;  // body name → (p_WB, R_WB)
  std::vector<ex> pose_outputs;                         // per body: p_WB (3), R_WB row-major (9)
  for (const Body& b : spec.bodies) {
    const std::string ctx = fmt::format("body '{}'", b.name);
    RIGID_REQUIRE(b.name.empty() || !poses.count(b.name), "body name '{}' is used twice",
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
      RIGID_REQUIRE(std::isfinite(norm) && norm > 0, "{} rotation {}: the axis must be a "
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
    const Eigen::Vector3d& com = b.mass.com();
    const Vec3 com_B{number(com.x()), number(com.y()), number(com.z())};
    Vec3 c = mat_vec(R, com_B);
    ex v2 = 0;
    for (int k = 0; k < 3; ++k) {
      c[k] = (c[k] + p[k]).expand();
      const ex v = dt(c[k]);
      v2 += v * v;
    }
    const double mass = b.mass.mass();
    const Eigen::Matrix3d& I = b.mass.inertia_com();
    ex rot = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (I(i, j) != 0) rot += number(I(i, j)) * w[i] * w[j];
    T_bodies += number(mass) / 2 * v2 + rot / 2;
    for (int k = 0; k < 3; ++k) {
      if (spec.gravity_W[k] != 0) V -= number(mass) * number(spec.gravity_W[k]) * c[k];
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
    RIGID_REQUIRE(!sp.body_a.empty(), "spring {}: body_a must name a body", j);
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
      RIGID_THROW("force on '{}': no coordinate of that name; coordinates: {}", F.name, known);
    }
    const auto i = static_cast<std::size_t>(it - s.coord_names.begin());
    Q[i] += parse(F.expression, fmt::format("force on '{}'", F.name), true);
    forced[i] = true;
  }

  // Euler–Lagrange: p = ∂L/∂q̇, M = ∂p/∂q̇, f = ∂L/∂q − (∂p/∂q) q̇ − ∂p/∂t + Q
  const auto n = static_cast<std::size_t>(s.n);
  s.p.resize(n);
  s.M.assign(n * n, 0);
  s.f.resize(n);
  for (std::size_t i = 0; i < n; ++i) s.p[i] = d(s.L, s.qd[i]);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) s.M[i * n + j] = d(s.p[i], s.qd[j]);
    if (s.M[i * n + i].expand().is_zero()) {
      RIGID_THROW("the Lagrangian is not quadratic in the velocity '{}_dot' (∂²L/∂{}_dot² ≡ 0), "
                  "so the mass matrix is singular; L = {}", s.coord_names[i], s.coord_names[i],
                  to_text(s.L));
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
    RIGID_REQUIRE(is_identifier(con.name), "constraint name '{}' is not a valid name", con.name);
    RIGID_REQUIRE(std::find(s.constraint_names.begin(), s.constraint_names.end(), con.name) ==
                      s.constraint_names.end(),
                  "constraint name '{}' is used twice", con.name);
    const ex gk = parse(con.expression, fmt::format("constraint '{}'", con.name), false).expand();
    bool depends = false;
    for (std::size_t i = 0; i < n; ++i) {
      const ex Gki = d(gk, s.q[i]);
      s.G.push_back(Gki);
      if (!Gki.is_zero()) depends = constrained[i] = true;
    }
    RIGID_REQUIRE(depends, "constraint '{}' = {} does not depend on any coordinate; it is either "
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

  // cyclic coordinates
  for (std::size_t i = 0; i < n; ++i) {
    if (!forced[i] && !constrained[i] && d(s.L, s.q[i]).expand().is_zero()) {
      s.cyclic_index.push_back(static_cast<int>(i));
      s.cyclic_names.push_back(s.coord_names[i]);
    }
  }
  // Störmer–Verlet applies when M is constant and f does not depend on q̇ (and no constraints)
  s.verlet_ok = s.m == 0;
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
  detail::TapeBuilder dyn(inputs);
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

  s.in.assign(inputs.size(), 0.0);
  s.out.assign(s.dyn.num_outputs(), 0.0);
  s.diag_out.assign(s.diag.num_outputs(), 0.0);
  s.Mw.resize(s.n, s.n);
  s.fw.resize(s.n);
  s.Gw.resize(s.m, s.n);
  s.gammaw.resize(s.m);
  s.cw.resize(s.m);
  s.gw.resize(s.m);
}

System::~System() = default;
System::System(System&&) noexcept = default;
System& System::operator=(System&&) noexcept = default;

int System::num_coordinates() const { return impl_->n; }
int System::num_constraints() const { return impl_->m; }
const std::vector<std::string>& System::coordinate_names() const { return impl_->coord_names; }
const std::vector<std::string>& System::constraint_names() const {
  return impl_->constraint_names;
}
const std::vector<std::string>& System::cyclic_coordinates() const { return impl_->cyclic_names; }
Eigen::VectorXd System::initial_q() const { return impl_->q0; }
Eigen::VectorXd System::initial_q_dot() const { return impl_->qd0; }
std::size_t System::tape_size() const { return impl_->dyn.size(); }
const std::vector<std::string>& System::body_names() const { return impl_->body_names; }

std::vector<BodyPose> System::body_poses(double time, const Eigen::VectorXd& q) const {
  const Impl& s = *impl_;
  RIGID_REQUIRE(q.size() == s.n, "expected q of size {}, got {}", s.n, q.size());
  s.load_inputs(time, q, Eigen::VectorXd::Zero(s.n));
  std::vector<double> out(s.pose.num_outputs());
  s.pose.evaluate(s.in.data(), out.data());
  std::vector<BodyPose> poses(s.body_names.size());
  for (std::size_t b = 0; b < poses.size(); ++b) {
    const double* o = out.data() + 12 * b;
    poses[b].p_WB = Eigen::Vector3d(o[0], o[1], o[2]);
    Eigen::Matrix3d R;
    R << o[3], o[4], o[5], o[6], o[7], o[8], o[9], o[10], o[11];
    // R is a product of exact rotations, orthonormal to round-off; the sign is made
    // canonical (w ≥ 0) so that equal poses give equal quaternions
    Eigen::Quaterniond qr(R);
    if (qr.w() < 0) qr.coeffs() = -qr.coeffs();
    poses[b].q_WB = qr.normalized();
  }
  return poses;
}

void System::set_parameter(const std::string& name, double value) {
  auto& s = *impl_;
  auto it = std::find(s.param_names.begin(), s.param_names.end(), name);
  RIGID_REQUIRE(it != s.param_names.end(), "unknown parameter '{}'", name);
  RIGID_REQUIRE(std::isfinite(value), "parameter '{}' must be finite, got {}", name, value);
  s.param_values[static_cast<std::size_t>(it - s.param_names.begin())] = value;
}

Equations System::equations() const {
  const Impl& s = *impl_;
  Equations eq;
  eq.lagrangian_text = to_text(s.L);
  eq.lagrangian_latex = to_latex(s.L);
  const auto n = static_cast<std::size_t>(s.n);
  for (std::size_t i = 0; i < n; ++i) {
    ex lhs = 0;
    for (std::size_t j = 0; j < n; ++j) lhs += s.M[i * n + j] * s.qdd[j];
    ex rhs = s.f[i];
    for (std::size_t k = 0; k < s.lambda.size(); ++k) rhs += s.lambda[k] * s.G[k * n + i];
    eq.text.push_back(to_text(lhs) + " = " + to_text(rhs));
    eq.latex.push_back(to_latex(lhs) + " = " + to_latex(rhs));
  }
  for (const ex& gk : s.g) {
    eq.constraints_text.push_back(to_text(gk) + " = 0");
    eq.constraints_latex.push_back(to_latex(gk) + " = 0");
  }
  eq.energy_text = to_text(s.h);
  eq.cyclic = s.cyclic_names;
  return eq;
}

void System::mass_matrix_and_forces(double t, const Eigen::VectorXd& q,
                                    const Eigen::VectorXd& q_dot, Eigen::MatrixXd& M,
                                    Eigen::VectorXd& f) const {
  const Impl& s = *impl_;
  RIGID_REQUIRE(q.size() == s.n && q_dot.size() == s.n, "expected q and q_dot of size {}, got "
                "{} and {}", s.n, q.size(), q_dot.size());
  s.evaluate_dynamics(t, q, q_dot);
  M = s.Mw;
  f = s.fw;
}

void System::accelerations(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& q_dot,
                           Eigen::VectorXd& q_ddot, Eigen::VectorXd& lambda,
                           double stabilization) const {
  const Impl& s = *impl_;
  RIGID_REQUIRE(q.size() == s.n && q_dot.size() == s.n, "expected q and q_dot of size {}, got "
                "{} and {}", s.n, q.size(), q_dot.size());
  s.evaluate_dynamics(t, q, q_dot);
  s.solve(t, q, q_ddot, lambda, stabilization);
}

double System::energy(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& q_dot) const {
  const Impl& s = *impl_;
  RIGID_REQUIRE(q.size() == s.n && q_dot.size() == s.n, "expected q and q_dot of size {}", s.n);
  s.load_inputs(t, q, q_dot);
  s.diag.evaluate(s.in.data(), s.diag_out.data());
  return s.diag_out[0];
}

double System::jacobi_integral(double t, const Eigen::VectorXd& q,
                               const Eigen::VectorXd& q_dot) const {
  const Impl& s = *impl_;
  RIGID_REQUIRE(q.size() == s.n && q_dot.size() == s.n, "expected q and q_dot of size {}", s.n);
  s.load_inputs(t, q, q_dot);
  s.diag.evaluate(s.in.data(), s.diag_out.data());
  return s.diag_out[1];
}

Eigen::VectorXd System::constraint_residual(double t, const Eigen::VectorXd& q) const {
  const Impl& s = *impl_;
  RIGID_REQUIRE(q.size() == s.n, "expected q of size {}, got {}", s.n, q.size());
  s.evaluate_dynamics(t, q, Eigen::VectorXd::Zero(s.n));
  return s.gw;
}

Trajectory System::simulate(const SimulationOptions& options) const {
  return simulate(options, impl_->q0, impl_->qd0);
}

Trajectory System::simulate(const SimulationOptions& o, const Eigen::VectorXd& q0_in,
                            const Eigen::VectorXd& qd0_in) const {
  const Impl& s = *impl_;
  RIGID_REQUIRE(q0_in.size() == s.n && qd0_in.size() == s.n,
                "expected initial q and q_dot of size {}, got {} and {}", s.n, q0_in.size(),
                qd0_in.size());
  RIGID_REQUIRE(std::isfinite(o.stabilization) && o.stabilization >= 0,
                "stabilization rate must be ≥ 0 and finite, got {} 1/s", o.stabilization);
  RIGID_REQUIRE(o.consistency_tolerance > 0, "consistency_tolerance must be positive, got {}",
                o.consistency_tolerance);
  if (o.method == integrate::Method::kStormerVerlet) {
    RIGID_REQUIRE(s.verlet_ok, "stormer_verlet needs T = ½ q̇ᵀ M q̇ with a constant M, forces "
                  "that do not depend on q̇ and no constraints; use implicit_midpoint");
  }
  Eigen::VectorXd q0 = q0_in, qd0 = qd0_in;
  const double t0 = 0.0;

  if (s.m > 0) {
    auto names_of = [&](const Eigen::VectorXd& weights) {
      std::string out;
      for (int k = 0; k < s.m; ++k) {
        if (std::abs(weights[k]) > 1e-8) {
          out += fmt::format("{}'{}'", out.empty() ? "" : ", ", s.constraint_names[static_cast<std::size_t>(k)]);
        }
      }
      return out;
    };
    // dependent constraints: a left null vector u of G (uᵀG = 0) combines them into 0 = uᵀg,
    // which is redundant if uᵀg = 0 and inconsistent otherwise
    s.evaluate_dynamics(t0, q0, qd0);
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(s.Gw, Eigen::ComputeFullU);
    const Eigen::VectorXd sv = svd.singularValues();
    const double smax = sv.size() ? sv.maxCoeff() : 0.0;
    for (int k = 0; k < s.m; ++k) {
      const double sk = k < sv.size() ? sv[k] : 0.0;
      if (sk <= 1e-10 * std::max(smax, 1e-300)) {
        const Eigen::VectorXd u = svd.matrixU().col(k);
        const double combined = u.dot(s.gw);
        if (std::abs(combined) > o.consistency_tolerance) {
          RIGID_THROW("constraints {} are inconsistent: their gradients ∂g/∂q are dependent at "
                      "q(0) and no q satisfies all of them (the combination Σ uₖ gₖ = {} "
                      "cannot vanish)", names_of(u), combined);
        }
        RIGID_THROW("constraints {} are redundant: their gradients ∂g/∂q are linearly "
                    "dependent at q(0) (rank {} < {}); remove one", names_of(u), k, s.m);
      }
    }
    const double res = s.gw.lpNorm<Eigen::Infinity>();
    const double vres = s.cw.lpNorm<Eigen::Infinity>();
    if (res > o.consistency_tolerance || vres > o.consistency_tolerance) {
      if (!o.project_initial) {
        Eigen::Index worst = 0;
        (res > o.consistency_tolerance ? s.gw : s.cw).cwiseAbs().maxCoeff(&worst);
        RIGID_THROW("initial conditions violate constraint '{}': |g| = {}, |ġ| = {} (tolerance "
                    "{}); fix q(0), q̇(0) or set project_initial to project them",
                    s.constraint_names[static_cast<std::size_t>(worst)], res, vres,
                    o.consistency_tolerance);
      }
      // minimum-norm Newton: q ← q − Gᵀ (G Gᵀ)⁻¹ g, then q̇ ← q̇ − Gᵀ (G Gᵀ)⁻¹ ġ
      for (int it = 0; it < 50 && s.gw.lpNorm<Eigen::Infinity>() > 1e-3 * o.consistency_tolerance; ++it) {
        const Eigen::MatrixXd GGt = s.Gw * s.Gw.transpose();
        q0 -= s.Gw.transpose() * GGt.ldlt().solve(s.gw);
        s.evaluate_dynamics(t0, q0, qd0);
      }
      RIGID_REQUIRE(s.gw.lpNorm<Eigen::Infinity>() <= o.consistency_tolerance,
                    "projection of q(0) onto the constraints did not converge: |g| = {}",
                    s.gw.lpNorm<Eigen::Infinity>());
      const Eigen::MatrixXd GGt = s.Gw * s.Gw.transpose();
      // ġ = G q̇ + g_t is affine in q̇
      qd0 -= s.Gw.transpose() * GGt.ldlt().solve(s.cw);
    }
  }
  // the mass matrix at the start (named error if not positive definite) sets the scale
  // against which it is called singular during the run
  Eigen::VectorXd qdd(s.n), lam(s.m);
  s.mass_scale = 0.0;
  accelerations(t0, q0, qd0, qdd, lam, o.stabilization);
  s.mass_scale = s.llt_M.matrixLLT().diagonal().cwiseAbs2().maxCoeff();

  integrate::Problem problem;
  const Eigen::Index n = s.n;
  problem.y0.resize(2 * n);
  problem.y0 << q0, qd0;
  problem.t0 = t0;
  problem.t_end = o.t_end;
  problem.n_position = s.n;
  for (const auto& c : s.coord_names) problem.names.push_back(c);
  for (const auto& c : s.coord_names) problem.names.push_back(c + "_dot");
  Eigen::VectorXd qv(n), qdv(n), acc(n), lw(s.m);
  const double alpha = o.stabilization;
  problem.rhs = [&, alpha](double t, const Eigen::VectorXd& y, Eigen::VectorXd& dydt) {
    qv = y.head(n);
    qdv = y.tail(n);
    if (!y.allFinite()) [[unlikely]] {
      std::string velocities;
      for (Eigen::Index i = 0; i < n; ++i) {
        velocities += fmt::format("{}{}_dot = {}", i ? ", " : "", s.coord_names[static_cast<std::size_t>(i)], qdv[i]);
      }
      rigid::detail::throw_error(
          "lagrange::System",
          fmt::format("non-finite state at {}, q̇ = ({}); the motion diverged: reduce the step "
                      "or check the model", s.state_text(t, qv), velocities));
    }
    if (o.progress) o.progress(t);
    s.evaluate_dynamics(t, qv, qdv);
    s.solve(t, qv, acc, lw, alpha);
    dydt.head(n) = qdv;
    dydt.tail(n) = acc;
  };
  const integrate::Solution sol = integrate::integrate(
      problem, integrate::Options{.method = o.method, .dt = o.dt, .rtol = o.tolerance,
                                  .atol = o.tolerance, .output_dt = o.output_dt});

  Trajectory tr;
  tr.coordinate_names = s.coord_names;
  tr.constraint_names = s.constraint_names;
  tr.cyclic_names = s.cyclic_names;
  const auto rows = static_cast<Eigen::Index>(sol.t.size());
  tr.t.resize(rows);
  tr.q.resize(rows, n);
  tr.q_dot.resize(rows, n);
  tr.lambda.resize(rows, s.m);
  tr.energy.resize(rows);
  tr.jacobi.resize(rows);
  tr.cyclic_momenta.resize(rows, static_cast<Eigen::Index>(s.cyclic_index.size()));
  tr.residual.resize(rows);
  tr.velocity_residual.resize(rows);
  for (Eigen::Index k = 0; k < rows; ++k) {
    const double t = sol.t[static_cast<std::size_t>(k)];
    const Eigen::VectorXd& y = sol.y[static_cast<std::size_t>(k)];
    qv = y.head(n);
    qdv = y.tail(n);
    tr.t[k] = t;
    tr.q.row(k) = qv;
    tr.q_dot.row(k) = qdv;
    s.evaluate_dynamics(t, qv, qdv);
    tr.residual[k] = s.m ? s.gw.lpNorm<Eigen::Infinity>() : 0.0;
    tr.velocity_residual[k] = s.m ? s.cw.lpNorm<Eigen::Infinity>() : 0.0;
    s.solve(t, qv, acc, lw, alpha);
    if (s.m) tr.lambda.row(k) = lw;
    s.load_inputs(t, qv, qdv);
    s.diag.evaluate(s.in.data(), s.diag_out.data());
    tr.energy[k] = s.diag_out[0];
    tr.jacobi[k] = s.diag_out[1];
    for (Eigen::Index c = 0; c < tr.cyclic_momenta.cols(); ++c) {
      tr.cyclic_momenta(k, c) = s.diag_out[static_cast<std::size_t>(2 + c)];
    }
  }
  tr.steps = sol.steps;
  tr.rhs_evaluations = sol.rhs_evaluations;
  return tr;
}

}  // namespace rigid::lagrange

#if defined(__SANITIZE_ADDRESS__)
// CLN (GiNaC's number library) allocates 26 bytes in a static initializer that it never
// frees; LeakSanitizer would fail every sanitized program that links rigid::lagrange. This
// is LeakSanitizer's documented hook for default suppressions.
extern "C" const char* __lsan_default_suppressions() { return "leak:libcln.so\n"; }
#endif
