// Velocity (nonholonomic) constraints: rows A(q, t) q̇ + a(q, t) = 0 with multipliers μ.
//
// With c(q, q̇, t) = A q̇ + a, keeping c = 0 along the motion needs ċ = 0:
//   ċ = A q̈ + Σⱼ ∂c/∂qⱼ q̇ⱼ + ∂c/∂t,   so   A q̈ = η,   η = −(Σⱼ ∂c/∂qⱼ q̇ⱼ + ∂c/∂t)
// (the Ȧ q̇ + ȧ of the row). These rows join the holonomic G q̈ = γ below it, and the one solve
// of evaluate.cpp gives q̈ with M q̈ = f + Gᵀ λ + Aᵀ μ [Bloch2015, ch. 5; NeimarkFufaev1972].
// Drift: a row is a holonomic row with g ≡ 0 and ġ replaced by c, so the Baumgarte right side
// γ − 2α ġ − α² g becomes η − 2α c: the residual obeys ċ + 2α c = 0.
#include "detail/velocity_constraints.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/SVD>
#include <fmt/format.h>

#include "rigid/common/did_you_mean.hpp"
#include "detail/parser.hpp"
#include "detail/symbolic.hpp"
#include "detail/tape.hpp"

namespace rigid::lagrange::detail {
namespace {

using GiNaC::ex;

// The first velocity symbol in e (by coordinate order), or n if none.
std::size_t first_velocity(const System::Impl& s, const ex& e) {
  for (std::size_t i = 0; i < s.qd.size(); ++i) {
    if (e.has(s.qd[i])) return i;
  }
  return s.qd.size();
}

// Position of `<coordinate>_dot` in the text (0 if not found), for the error's column.
std::size_t velocity_offset(const Expression& e, const std::string& coordinate) {
  const std::size_t at = e.text.find(coordinate + "_dot");
  return at == std::string::npos ? 0 : at;
}

// Throws at the row's declaration when it has one, else as an error of System.
[[noreturn]] void fail_at(const SourceLocation& where, const std::string& message) {
  if (!where.file.empty() || where.line > 0) rigid::detail::throw_error_at(where, message);
  rigid::detail::throw_error("System", message);
}

// The rows of A as text, "[A₀₀, A₀₁, …], […]", for messages.
std::string rows_text(const System::Impl& s) {
  std::string out;
  const auto n = static_cast<std::size_t>(s.n);
  for (std::size_t k = 0; k < s.A.size() / n; ++k) {
    out += k ? ", [" : "[";
    for (std::size_t i = 0; i < n; ++i) out += (i ? ", " : "") + to_text(s.A[k * n + i]);
    out += "]";
  }
  return out;
}

}  // namespace

void derive_velocity_constraints(const SystemSpec& spec, System::Impl& s,
                                 const std::map<std::string, ex>& names,
                                 std::vector<bool>& constrained) {
  const auto n = static_cast<std::size_t>(s.n);
  s.r = static_cast<int>(spec.velocity_constraints.size());
  if (s.r == 0) return;
  std::vector<SourceLocation> sources;  // per row: where it is declared
  for (std::size_t k = 0; k < spec.velocity_constraints.size(); ++k) {
    const VelocityConstraint& vc = spec.velocity_constraints[k];
    const std::string ctx = fmt::format("velocity constraint '{}'", vc.name);
    auto fail_row = [&](const std::string& message) { fail_at(vc.where, ctx + ": " + message); };
    RIGID_REQUIRE_AS("System", is_identifier(vc.name), "velocity constraint name '{}' is not a "
                     "valid name; expected letters, digits and '_', not starting with a digit",
                     vc.name);
    const bool taken = std::count(s.velocity_constraint_names.begin(),
                                  s.velocity_constraint_names.end(), vc.name) ||
                       std::count(s.constraint_names.begin(), s.constraint_names.end(), vc.name);
    if (taken) fail_row("the name is already used by another constraint");

    // e = Σ (given coefficient) q̇ᵢ + term; A = ∂e/∂q̇ and a = e − A q̇ when e is linear in q̇
    ex e = 0;
    std::vector<bool> given(n, false);
    for (const NamedExpression& coefficient : vc.coefficients) {
      auto it = std::find(s.coord_names.begin(), s.coord_names.end(), coefficient.name);
      const std::string cctx = fmt::format("{} coefficient of '{}'", ctx, coefficient.name);
      if (it == s.coord_names.end()) {
        fail_at(coefficient.expression.where,
                fmt::format("{}: no coordinate of that name{} (coordinates: {})", cctx,
                            did_you_mean_hint(coefficient.name, s.coord_names),
                            fmt::join(s.coord_names, ", ")));
      }
      const auto i = static_cast<std::size_t>(it - s.coord_names.begin());
      if (given[i]) {
        fail_at(coefficient.expression.where, cctx + ": the coordinate has a coefficient already; "
                                                   "give each coordinate's coefficient once");
      }
      given[i] = true;
      if (coefficient.expression.text.find_first_not_of(" \t") == std::string::npos) {
        throw_at(coefficient.expression, 0, cctx, "empty expression; expected a number, a name or '('");
      }
      const ex Ai = parse_expression(coefficient.expression, names, cctx);
      if (const std::size_t j = first_velocity(s, Ai); j < n) {
        throw_at(coefficient.expression, velocity_offset(coefficient.expression, s.coord_names[j]),
                 cctx, fmt::format("depends on the velocity '{}_dot', so the constraint is not linear "
                                   "in the velocities; a coefficient Aᵢ(q, t) may use q, t and the "
                                   "parameters only",
                                   s.coord_names[j]));
      }
      e += Ai * s.qd[i];
    }
    const bool has_term = vc.term.text.find_first_not_of(" \t") != std::string::npos;
    if (has_term) {
      const ex term = parse_expression(vc.term, names, ctx + " term");
      // linear in q̇: every second derivative by velocities vanishes
      for (std::size_t i = 0; i < n; ++i) {
        const ex di = d(term, s.qd[i]);
        if (const std::size_t j = first_velocity(s, di); j < n) {
          throw_at(vc.term, velocity_offset(vc.term, s.coord_names[i]), ctx + " term",
                   fmt::format("is not linear in the velocities (∂²/∂{}_dot∂{}_dot = {} ≠ 0); a "
                               "velocity constraint is Σᵢ Aᵢ(q, t) q̇ᵢ + a(q, t) = 0",
                               s.coord_names[i], s.coord_names[j],
                               to_text(d(di, s.qd[j]).expand())));
        }
      }
      e += term;
    }
    e = e.expand();
    std::vector<ex> row(n);
    bool any = false;
    for (std::size_t i = 0; i < n; ++i) {
      row[i] = d(e, s.qd[i]).expand();
      any = any || !row[i].is_zero();
    }
    if (!any) {
      fail_row(fmt::format("no velocity has a non-zero coefficient ({} = 0), so it does not "
                           "constrain the motion's velocities; a relation g(q, t) = 0 of the "
                           "coordinates alone is a holonomic constraint",
                           to_text(e)));
    }
    ex a = e;
    for (std::size_t i = 0; i < n; ++i) a -= row[i] * s.qd[i];
    a = a.expand();
    // η = −(Σⱼ ∂c/∂qⱼ q̇ⱼ + ∂c/∂t) with c = e
    ex eta = -d(e, s.t);
    for (std::size_t j = 0; j < n; ++j) eta -= d(e, s.q[j]) * s.qd[j];
    for (std::size_t i = 0; i < n; ++i) {
      if (!row[i].is_zero()) constrained[i] = true;
      s.A.push_back(row[i]);
    }
    s.a.push_back(a);
    s.eta.push_back(eta.expand());
    s.cv.push_back(e);
    s.velocity_constraint_names.push_back(vc.name);
    s.mu.emplace_back("mu_" + vc.name, "\\mu_{\\mathrm{" + vc.name + "}}");
    sources.push_back(vc.where);
  }

  // compile: inputs (q, q̇, t, parameters) as the dynamics tape
  std::vector<GiNaC::symbol> inputs;
  inputs.insert(inputs.end(), s.q.begin(), s.q.end());
  inputs.insert(inputs.end(), s.qd.begin(), s.qd.end());
  inputs.push_back(s.t);
  inputs.insert(inputs.end(), s.params.begin(), s.params.end());
  TapeBuilder vel(inputs);
  for (const ex& x : s.A) vel.add_output(x);
  for (const ex& x : s.eta) vel.add_output(x);
  for (const ex& x : s.cv) vel.add_output(x);
  s.vel = vel.build();

  // rows that are dependent for every q: A at a generic point (no coordinate, time or
  // parameter value is special there) has a left null vector. Rows dependent only at some q
  // are found when a run starts (at q(0)) or while it runs (the solve's rank check).
  std::vector<double> in(s.num_inputs(), 0.0), out(s.vel.num_outputs());
  for (std::size_t i = 0; i < n; ++i) in[i] = 0.6180339887 + 0.4142135623 * static_cast<double>(i);
  in[2 * n] = 0.5772156649;
  std::copy(s.param_values.begin(), s.param_values.end(), in.begin() + static_cast<std::ptrdiff_t>(2 * n + 1));
  s.vel.evaluate(in.data(), out.data());
  Eigen::MatrixXd A(s.r, s.n);
  for (int k = 0; k < s.r; ++k)
    for (int i = 0; i < s.n; ++i) A(k, i) = out[static_cast<std::size_t>(k * s.n + i)];
  if (!A.allFinite()) return;  // not defined at that point: left to the checks of a run
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullU);
  const Eigen::VectorXd sv = svd.singularValues();
  const double smax = sv.size() ? sv.maxCoeff() : 0.0;
  for (int k = 0; k < s.r; ++k) {
    const double sk = k < sv.size() ? sv[k] : 0.0;
    // the 1e-10 relative threshold of the holonomic rows' check (evaluate.cpp)
    if (sk <= 1e-10 * std::max(smax, 1e-300)) {
      const Eigen::VectorXd u = svd.matrixU().col(k);
      std::vector<std::string> rows;
      std::size_t last = 0;
      for (int j = 0; j < s.r; ++j) {
        if (std::abs(u[j]) > 1e-8) {
          rows.push_back(fmt::format("'{}'", s.velocity_constraint_names[static_cast<std::size_t>(j)]));
          last = static_cast<std::size_t>(j);
        }
      }
      fail_at(sources[last],
              fmt::format("velocity constraints {} are dependent for every q (their rows of A "
                          "have rank {} < {}; A = {}): one is a combination of the others; "
                          "remove it",
                          fmt::join(rows, ", "), k, s.r, rows_text(s)));
    }
  }
}

void evaluate_velocity_constraints(const System::Impl& s, Workspace::Impl& w) {
  s.vel.evaluate(w.in.data(), w.vel_out.data(), w.vel_scratch);
  const int n = s.n, m = s.m, r = s.r;
  std::size_t k = 0;
  for (int a = 0; a < r; ++a)
    for (int i = 0; i < n; ++i) w.Gw(m + a, i) = w.vel_out[k++];
  for (int a = 0; a < r; ++a) w.gammaw[m + a] = w.vel_out[k++];
  for (int a = 0; a < r; ++a) w.cw[m + a] = w.vel_out[k++];
  for (int a = 0; a < r; ++a) w.gw[m + a] = 0.0;
}

}  // namespace rigid::lagrange::detail
