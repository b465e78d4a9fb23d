#include "detail/symbolic.hpp"
#include "detail/symbolic_lock.hpp"
#include "rigid/lagrange/symbolic_core.hpp"
#include "rigid/lagrange/names.hpp"

#include "detail/canonical.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <cctype>
#include <cmath>
#include <sstream>

#include <fmt/format.h>

namespace rigid::lagrange::detail {

using GiNaC::ex;
using GiNaC::symbol;

namespace {

// rewrite()'s walk: GiNaC's map() rebuilds a node from its operands, each passed through here
class GraphRewrite : public GiNaC::map_function {
 public:
  explicit GraphRewrite(const Rewrite& rule) : rule_(rule) {}
  ex operator()(const ex& e) override {
    if (e.nops() == 0) return rule_(e).value_or(e);
    // a node kept as it is comes back as the very object passed in (an operand of a product or
    // a sum is made anew by each op() call: equal, but another object)
    if (const std::optional<ex>* known = memo_.find(e)) return known->value_or(e);
    std::optional<ex> out = rule_(e);
    for (std::size_t i = 0; !out && i < e.nops(); ++i) {
      const ex op = e.op(i);
      if (!GiNaC::are_ex_trivially_equal((*this)(op), op)) out = e.map(*this);  // operands remembered now
    }
    return memo_.remember(e, std::move(out)).value_or(e);
  }

 private:
  const Rewrite& rule_;
  ExMemo<std::optional<ex>> memo_;  // the replacement, or nothing where the node is kept
};

}  // namespace

ex rewrite(const ex& e, const Rewrite& rule) {
  GraphRewrite walk(rule);
  return walk(e);
}

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

std::optional<ex> trig_power_through_pythagoras(const ex& e, std::string_view function, const ex* argument) {
  if (!GiNaC::is_a<GiNaC::power>(e) || !GiNaC::is_a<GiNaC::function>(e.op(0)) ||
      GiNaC::ex_to<GiNaC::function>(e.op(0)).get_name() != function || !GiNaC::is_a<GiNaC::numeric>(e.op(1)) ||
      !GiNaC::ex_to<GiNaC::numeric>(e.op(1)).is_integer()) {
    return std::nullopt;
  }
  const ex x = e.op(0).op(0);
  if (argument != nullptr && !x.is_equal(*argument)) return std::nullopt;
  const GiNaC::numeric& power = GiNaC::ex_to<GiNaC::numeric>(e.op(1));
  if (power < 2 || power > kMaxTrigPowerRewritten) return std::nullopt;  // before to_long(): any size
  const long n = power.to_long();
  const bool sine = function == "sin";
  const ex kept = sine ? GiNaC::sin(x) : GiNaC::cos(x), other = sine ? GiNaC::cos(x) : GiNaC::sin(x);
  return GiNaC::pow(kept, n % 2) * GiNaC::pow(1 - GiNaC::pow(other, 2), n / 2);
}

ex simplify(const ex& e) {
  const ex expanded = e.expand();
  // sinⁿx → sin^(n mod 2)x · (1 − cos²x)^(n/2), so that expand() cancels the sin² + cos² pairs
  // that |ċ|² and ωᵀIω produce. rewrite() hands back the same object when no sine power was
  // found: no second expansion then
  const ex reduced = rewrite(expanded, [](const ex& x) { return trig_power_through_pythagoras(x, "sin"); });
  return GiNaC::are_ex_trivially_equal(reduced, expanded) ? expanded : reduced.expand();
}

// the canonical printer (canonical.hpp) with symbols ranked by name: the same bytes on every
// run, which GiNaC's own printer does not give
std::string to_text(const ex& e) {
  const SymbolOrder order;
  return print(plain(e, order), order, false);
}
std::string to_latex(const ex& e) {
  const SymbolOrder order;
  return print(plain(e, order), order, true);
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


namespace {

// made on first use and never destroyed: a System kept in a static (a test's, Python's at exit)
// may be built before this file's statics or destroyed, under the lock, after them
std::recursive_mutex& symbolic_mutex() {
  static auto* mutex = new std::recursive_mutex;
  return *mutex;
}
thread_local int t_symbolic_depth = 0;  // this thread's nested entries
std::atomic<std::uint64_t> g_symbolic_entries{0};
std::atomic<std::int64_t> g_symbolic_nanoseconds{0};

}  // namespace

SymbolicLock::SymbolicLock() {
  symbolic_mutex().lock();
  if (t_symbolic_depth++ == 0) {
    outermost_ = true;
    since_ = std::chrono::steady_clock::now();
  }
}

SymbolicLock::~SymbolicLock() {
  if (outermost_) {
    const auto held = std::chrono::steady_clock::now() - since_;
    g_symbolic_nanoseconds.fetch_add(std::chrono::duration_cast<std::chrono::nanoseconds>(held).count(),
                                     std::memory_order_relaxed);
    g_symbolic_entries.fetch_add(1, std::memory_order_relaxed);
  }
  --t_symbolic_depth;
  symbolic_mutex().unlock();
}

}  // namespace rigid::lagrange::detail

namespace rigid::lagrange {

bool is_reserved_name(const std::string& name) { return detail::reserved_names().count(name) > 0; }

SymbolicCoreUsage symbolic_core_usage() {
  return {detail::g_symbolic_entries.load(std::memory_order_relaxed),
          1e-9 * static_cast<double>(detail::g_symbolic_nanoseconds.load(std::memory_order_relaxed))};
}

}  // namespace rigid::lagrange
