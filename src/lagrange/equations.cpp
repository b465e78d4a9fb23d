// System::equations(): the derived quantities printed canonically and simplified as a
// textbook does (detail/canonical.hpp), and the documents `rigid eom --format` writes.
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <ginac/ginac.h>
#include <nlohmann/json.hpp>

#include "detail/canonical.hpp"
#include "detail/symbolic.hpp"
#include "detail/symbolic_lock.hpp"
#include "detail/system_impl.hpp"
#include "rigid/lagrange/system.hpp"

namespace rigid::lagrange {
namespace {

using GiNaC::ex;
using GiNaC::symbol;
using detail::d;
using detail::SymbolOrder;

// does x appear inside the argument of a trigonometric function of e?
bool in_angle(const ex& e, const symbol& x) {
  if (GiNaC::is_a<GiNaC::function>(e)) {
    const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
    if ((name == "sin" || name == "cos" || name == "tan") && e.op(0).has(x)) return true;
  }
  for (std::size_t i = 0; i < e.nops(); ++i) {
    if (in_angle(e.op(i), x)) return true;
  }
  return false;
}

// The order in which symbols are printed: coordinates (q, q̇, q̈ of each), multipliers (the
// holonomic ones first), time, parameters.
SymbolOrder symbol_order(const System::Impl& s) {
  SymbolOrder order;
  // a velocity ranks with its coordinate; a ball's ω_k with its quaternion's entry k + 1
  for (std::size_t i = 0; i < s.q.size(); ++i) order.add(s.q[i], SymbolOrder::kCoordinate, static_cast<int>(i), 0);
  for (std::size_t i = 0; i < s.qd.size(); ++i) {
    int rank = s.q_of_v[i];
    for (const System::Impl::Ball& b : s.balls) {
      if (i >= b.v && i < b.v + 3) rank = static_cast<int>(b.q + 1 + i - b.v);
    }
    order.add(s.qd[i], SymbolOrder::kCoordinate, rank, 1);
    order.add(s.qdd[i], SymbolOrder::kCoordinate, rank, 2);
  }
  for (std::size_t k = 0; k < s.lambda.size(); ++k) {
    order.add(s.lambda[k], SymbolOrder::kMultiplier, static_cast<int>(k));
  }
  for (std::size_t k = 0; k < s.mu.size(); ++k) {  // after the holonomic multipliers
    order.add(s.mu[k], SymbolOrder::kMultiplier, static_cast<int>(s.lambda.size() + k));
  }
  order.add(s.t, SymbolOrder::kTime, 0);
  for (std::size_t k = 0; k < s.params.size(); ++k) {
    order.add(s.params[k], SymbolOrder::kParameter, static_cast<int>(k));
  }
  return order;
}

// Simplifies expressions as a textbook does and prints them as text and LaTeX, with one
// simplification per distinct expression (M is symmetric; f often equals a part of it).
class Printer {
 public:
  explicit Printer(const System::Impl& s) : order_(symbol_order(s)) {}

  // a simplified sum printed as text and LaTeX
  [[nodiscard]] Printed both(const detail::Sum& sum) const {
    return Printed{detail::print(sum, order_, false), detail::print(sum, order_, true)};
  }
  // e simplified as a textbook does (once per distinct expression)
  [[nodiscard]] detail::Sum textbook(const ex& e) {
    const auto [lo, hi] = cache_.equal_range(e.gethash());
    for (auto it = lo; it != hi; ++it) {
      if (it->second.first.is_equal(e)) return it->second.second;
    }
    detail::Sum sum = detail::textbook(e, order_);
    cache_.emplace(e.gethash(), std::make_pair(e, sum));
    return sum;
  }
  // e simplified, then printed as text and LaTeX
  [[nodiscard]] Printed simplified(const ex& e) { return both(textbook(e)); }

 private:
  SymbolOrder order_;
  std::unordered_multimap<unsigned, std::pair<ex, detail::Sum>> cache_;
};

// Σ_j M_ij q̈_j, collected per acceleration: the left side of equation i.
detail::Sum accelerations_sum(const System::Impl& s, const std::vector<detail::Sum>& M_sums,
                              std::size_t i) {
  const auto n = static_cast<std::size_t>(s.n);
  detail::Sum lhs_sum;
  lhs_sum.keep_order = true;
  for (std::size_t j = 0; j < n; ++j) {
    const detail::Sum& c = M_sums[i * n + j];
    if (c.terms.empty()) continue;
    detail::Term t;
    if (c.terms.size() == 1) {
      t = c.terms.front();
    } else {
      t.sums.push_back(c);
    }
    t.factors.push_back(s.qdd[j]);
    lhs_sum.terms.push_back(std::move(t));
  }
  return lhs_sum;
}

// Prints M, f and its parts, and the equations M q̈ = f + Gᵀλ + Aᵀμ into `eq`; returns
// whether a generalized force acts.
bool print_motion(const System::Impl& s, Printer& printer, Equations& eq) {
  const auto n = static_cast<std::size_t>(s.n);
  const std::size_t m = s.g.size();
  // f = ∂L/∂q − (∂p/∂q) q̇ − ∂p/∂t + Q: the potential part is −∂V/∂q, the generalized part Q,
  // the inertial part (from T) what remains
  bool forced = false;
  eq.mass_matrix.resize(n);
  std::vector<detail::Sum> M_sums;  // simplified once, printed in M and in the equations
  for (std::size_t k = 0; k < n * n; ++k) M_sums.push_back(printer.textbook(s.M[k]));
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) eq.mass_matrix[i].push_back(printer.both(M_sums[i * n + j]));
    const ex generalized = s.Q[i].expand();
    // −∂V/∂q; a recursive derivation gives it apart (V is in terms of its intermediates)
    const ex potential = s.f_potential.empty() ? ex(-d(s.V, s.q[i])) : s.f_potential[i];  // (balls: recursive)
    forced = forced || !detail::simplify(generalized).is_zero();
    const detail::Sum f_sum = printer.textbook(s.f[i]);
    eq.forcing.push_back(printer.both(f_sum));
    eq.forcing_inertial.push_back(printer.simplified(s.f[i] - potential - generalized));
    eq.forcing_potential.push_back(printer.simplified(potential));
    eq.forcing_generalized.push_back(printer.simplified(generalized));

    // Σ_j M_ij q̈_j, collected per acceleration, = f_i + Σ_k λ_k G_ki
    const Printed lhs = printer.both(accelerations_sum(s, M_sums, i));
    ex rhs = s.f[i];
    for (std::size_t k = 0; k < m; ++k) rhs += s.lambda[k] * s.G[k * n + i];
    for (std::size_t k = 0; k < s.mu.size(); ++k) rhs += s.mu[k] * s.A[k * n + i];  // Aᵀ μ
    const Printed r = m == 0 && s.mu.empty() ? eq.forcing.back() : printer.simplified(rhs);
    eq.equations.push_back({lhs.text + " = " + r.text, lhs.latex + " = " + r.latex});
  }
  return forced;
}

// Prints the holonomic and velocity constraints and their matrices into `eq`; returns
// whether L or a constraint depends on the time.
bool print_constraints(const System::Impl& s, Printer& printer, Equations& eq) {
  const auto n = static_cast<std::size_t>(s.n);
  const std::size_t m = s.g.size();
  bool time_dependent = s.L.has(s.t);
  eq.constraint_jacobian.resize(m);
  for (std::size_t k = 0; k < m; ++k) {
    eq.constraints.push_back(printer.simplified(s.g[k]));
    for (std::size_t i = 0; i < n; ++i) eq.constraint_jacobian[k].push_back(printer.simplified(s.G[k * n + i]));
    time_dependent = time_dependent || s.g[k].has(s.t);
  }
  eq.velocity_constraint_names = s.velocity_constraint_names;
  eq.velocity_constraint_matrix.resize(s.mu.size());
  for (std::size_t k = 0; k < s.mu.size(); ++k) {
    eq.velocity_constraints.push_back(printer.simplified(s.cv[k]));
    for (std::size_t i = 0; i < n; ++i) {
      eq.velocity_constraint_matrix[k].push_back(printer.simplified(s.A[k * n + i]));
    }
    time_dependent = time_dependent || s.cv[k].has(s.t) || !detail::simplify(s.a[k]).is_zero();
  }
  return time_dependent;
}

// The symbols' table: a coordinate inside an angle or turning a joint is in rad, one sliding a joint
// (and inside no angle) in m; otherwise the equations do not say.
std::vector<EquationSymbol> symbols_table(const System::Impl& s) {
  std::vector<EquationSymbol> symbols;
  auto tex = [](const symbol& x) { return x.get_TeX_name().empty() ? detail::tex_name(x.get_name()) : x.get_TeX_name(); };
  for (const System::Impl::Ball& b : s.balls) {
    for (std::size_t k = 0; k < 4; ++k) {
      symbols.push_back({s.q[b.q + k].get_name(), tex(s.q[b.q + k]),
                         fmt::format("orientation of the ball '{}' (unit quaternion w x y z)", b.name), "1"});
    }
    for (std::size_t k = 0; k < 3; ++k) {
      symbols.push_back({s.qd[b.v + k].get_name(), tex(s.qd[b.v + k]),
                         fmt::format("angular velocity of the ball '{}' in its body's frame", b.name), "rad/s"});
      symbols.push_back({s.qdd[b.v + k].get_name(), tex(s.qdd[b.v + k]), "angular acceleration", "rad/s^2"});
    }
  }
  for (std::size_t v = 0; v < s.qd.size(); ++v) {
    if (s.q_of_v[v] < 0) continue;  // a ball's, above
    const auto i = static_cast<std::size_t>(s.q_of_v[v]);
    bool angle = in_angle(s.L, s.q[i]);
    for (const ex& a : s.aux_def) angle = angle || in_angle(a, s.q[i]);
    for (const ex& g : s.g) angle = angle || in_angle(g, s.q[i]);
    // a slide joint's amount is a length unless something takes its sine too
    const std::string& joint = s.joint_unit.empty() ? std::string() : s.joint_unit[i];
    const bool length = joint == "m" && !angle;
    angle = angle || joint == "rad";
    const std::string unit = length ? "m" : angle ? "rad" : "m or rad";
    const std::string per_s = length ? "m/s" : angle ? "rad/s" : "m/s or rad/s";
    const std::string per_s2 = length ? "m/s^2" : angle ? "rad/s^2" : "m/s^2 or rad/s^2";
    symbols.push_back({s.q[i].get_name(), tex(s.q[i]), "coordinate", unit});
    symbols.push_back({s.qd[v].get_name(), tex(s.qd[v]), "velocity", per_s});
    symbols.push_back({s.qdd[v].get_name(), tex(s.qdd[v]), "acceleration", per_s2});
  }
  for (std::size_t k = 0; k < s.lambda.size(); ++k) {
    symbols.push_back({s.lambda[k].get_name(), tex(s.lambda[k]),
                       fmt::format("multiplier of constraint '{}'", s.constraint_names[k]),
                       "N or N·m (per unit of the constraint)"});
  }
  for (std::size_t k = 0; k < s.mu.size(); ++k) {
    symbols.push_back({s.mu[k].get_name(), tex(s.mu[k]),
                       fmt::format("multiplier of velocity constraint '{}'", s.velocity_constraint_names[k]),
                       "N or N·m (per unit of the constraint)"});
  }
  symbols.push_back({"t", "t", "time", "s"});
  for (std::size_t k = 0; k < s.params.size(); ++k) {
    symbols.push_back({s.param_names[k], tex(s.params[k]), "parameter", "SI"});
  }
  return symbols;
}

// Fills the flat fields of `eq` (text and LaTeX lists) from the printed ones.
void fill_flat_fields(const System::Impl& s, Equations& eq) {
  eq.lagrangian_text = eq.lagrangian.text;
  eq.lagrangian_latex = eq.lagrangian.latex;
  for (const Printed& e : eq.equations) {
    eq.text.push_back(e.text);
    eq.latex.push_back(e.latex);
  }
  for (const Printed& g : eq.constraints) {
    eq.constraints_text.push_back(g.text + " = 0");
    eq.constraints_latex.push_back(g.latex + " = 0");
  }
  for (const Printed& c : eq.velocity_constraints) {
    eq.constraints_text.push_back(c.text + " = 0");
    eq.constraints_latex.push_back(c.latex + " = 0");
  }
  eq.energy_text = eq.jacobi_integral.text;
  eq.cyclic = s.cyclic_names;
}

// The equations printed from the derived expressions (GiNaC; the caller holds the lock).
Equations print_equations(const System::Impl& s) {
  Printer printer(s);

  Equations eq;
  eq.coordinates = s.coord_names;
  if (!s.balls.empty()) {
    eq.velocities = s.velocity_names;
    for (const ex& rate : s.q_rate) eq.coordinate_rates.push_back(printer.simplified(rate));
  }
  eq.constraint_names = s.constraint_names;
  for (std::size_t k = 0; k < s.param_names.size(); ++k) {
    eq.parameters.push_back({s.param_names[k], s.param_values[k]});
  }
  for (std::size_t k = 0; k < s.aux.size(); ++k) {
    eq.intermediates.emplace_back(printer.simplified(s.aux[k]), printer.simplified(s.aux_def[k]));
  }
  eq.lagrangian = printer.simplified(s.L);
  eq.kinetic_energy = printer.simplified(s.T);
  eq.potential_energy = printer.simplified(s.V);

  const bool forced = print_motion(s, printer, eq);
  const bool time_dependent = print_constraints(s, printer, eq);
  eq.jacobi_integral = printer.simplified(s.h);
  eq.jacobi_conserved = !time_dependent && !forced;
  for (int i : s.cyclic_index) eq.cyclic_momenta.push_back(printer.simplified(s.p[static_cast<std::size_t>(i)]));

  // symbols: a coordinate inside an angle is in rad; otherwise the equations do not say
  eq.symbols = symbols_table(s);

  // the flat fields
  fill_flat_fields(s, eq);
  return eq;
}

}  // namespace

Equations System::equations() const {
  detail::SymbolicLock lock;
  if (!impl_->equations) impl_->equations = print_equations(*impl_);
  Equations eq = *impl_->equations;
  // the parameters' current values (set_parameter may have changed them since)
  for (std::size_t k = 0; k < eq.parameters.size(); ++k) eq.parameters[k].value = impl_->param_values[k];
  return eq;
}

EquationFormat parse_equation_format(std::string_view name) {
  if (name == "text") return EquationFormat::kText;
  if (name == "latex") return EquationFormat::kLatex;
  if (name == "json") return EquationFormat::kJson;
  throw Error(fmt::format("unknown equation format '{}'; expected text, latex or json", name));
}

namespace {

using Json = nlohmann::ordered_json;

std::string tex_text(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '_' ? std::string("\\_") : std::string(1, c);
  return out;
}

std::string format_text(const Equations& eq) {
  std::string out;
  auto line = [&](const std::string& s) { out += s + "\n"; };
  line(fmt::format("coordinates: {}", fmt::join(eq.coordinates, ", ")));
  std::vector<std::string> names;
  for (const Parameter& p : eq.parameters) names.push_back(p.name);
  if (!names.empty()) line(fmt::format("parameters: {}", fmt::join(names, ", ")));
  if (!eq.velocities.empty()) {
    line(fmt::format("velocities: {}", fmt::join(eq.velocities, ", ")));
    line("rates of the balls' quaternions (q_dot = q * (0, w)/2, w in the body's frame; the other "
         "coordinates' rates are their velocities):");
    for (std::size_t i = 0; i < eq.coordinates.size(); ++i) {
      if (eq.coordinate_rates[i].text == eq.coordinates[i] + "_dot") continue;
      line(fmt::format("  {}_dot = {}", eq.coordinates[i], eq.coordinate_rates[i].text));
    }
  }
  line(eq.velocities.empty() ? "equations of motion (one per coordinate):"
                             : "equations of motion (one per velocity; a ball's are Euler's):");
  for (const Printed& e : eq.equations) line("  " + e.text);
  if (!eq.intermediates.empty()) {
    line("where (the tree's recursions, each from those before it):");
    for (const auto& [name, value] : eq.intermediates) line(fmt::format("  {} = {}", name.text, value.text));
  }
  if (!eq.constraints.empty()) {
    line("constraints:");
    for (std::size_t k = 0; k < eq.constraints.size(); ++k) {
      line(fmt::format("  {}: {} = 0", eq.constraint_names[k], eq.constraints[k].text));
    }
  }
  if (!eq.velocity_constraints.empty()) {
    line("velocity constraints:");
    for (std::size_t k = 0; k < eq.velocity_constraints.size(); ++k) {
      line(fmt::format("  {}: {} = 0", eq.velocity_constraint_names[k], eq.velocity_constraints[k].text));
    }
  }
  line("Lagrangian:");
  line("  " + eq.lagrangian.text);
  line("kinetic energy:");
  line("  " + eq.kinetic_energy.text);
  line("potential energy:");
  line("  " + eq.potential_energy.text);
  line("mass matrix:");
  for (const auto& row : eq.mass_matrix) {
    std::vector<std::string> cells;
    for (const Printed& c : row) cells.push_back(c.text);
    line(fmt::format("  [{}]", fmt::join(cells, ", ")));
  }
  line("forcing (inertial + potential + generalized):");
  for (std::size_t i = 0; i < eq.forcing.size(); ++i) {
    line(fmt::format("  {}: {}", eq.velocities.empty() ? eq.coordinates[i] : eq.velocities[i], eq.forcing[i].text));
    const std::pair<const char*, const Printed*> parts[] = {{"inertial", &eq.forcing_inertial[i]},
                                                            {"potential", &eq.forcing_potential[i]},
                                                            {"generalized", &eq.forcing_generalized[i]}};
    for (const auto& [label, part] : parts) {
      if (part->text != "0" && part->text != eq.forcing[i].text) line(fmt::format("    {}: {}", label, part->text));
    }
  }
  if (!eq.constraint_jacobian.empty()) {
    line("constraint Jacobian:");
    for (std::size_t k = 0; k < eq.constraint_jacobian.size(); ++k) {
      std::vector<std::string> cells;
      for (const Printed& c : eq.constraint_jacobian[k]) cells.push_back(c.text);
      line(fmt::format("  {}: [{}]", eq.constraint_names[k], fmt::join(cells, ", ")));
    }
  }
  if (!eq.velocity_constraint_matrix.empty()) {
    line("velocity constraint matrix:");
    for (std::size_t k = 0; k < eq.velocity_constraint_matrix.size(); ++k) {
      std::vector<std::string> cells;
      for (const Printed& c : eq.velocity_constraint_matrix[k]) cells.push_back(c.text);
      line(fmt::format("  {}: [{}]", eq.velocity_constraint_names[k], fmt::join(cells, ", ")));
    }
  }
  line("conserved quantities:");
  line(fmt::format("  Jacobi integral{}: {}",
                   eq.jacobi_conserved ? "" : " (not conserved: t, forces or a moving constraint appear)",
                   eq.jacobi_integral.text));
  for (std::size_t c = 0; c < eq.cyclic_momenta.size(); ++c) {
    line(fmt::format("  momentum of the cyclic coordinate {}: {}", eq.cyclic[c], eq.cyclic_momenta[c].text));
  }
  line("symbols:");
  for (const EquationSymbol& s : eq.symbols) line(fmt::format("  {}: {} ({})", s.name, s.role, s.unit));
  if (!eq.note.empty()) line(eq.note);
  return out;
}

std::string pmatrix(const std::vector<std::vector<Printed>>& rows) {
  std::vector<std::string> lines;
  for (const auto& row : rows) {
    std::vector<std::string> cells;
    for (const Printed& c : row) cells.push_back(c.latex);
    lines.push_back(fmt::format("{}", fmt::join(cells, " & ")));
  }
  return fmt::format("\\begin{{pmatrix}} {} \\end{{pmatrix}}", fmt::join(lines, " \\\\ "));
}

std::string format_latex(const Equations& eq) {
  std::string out;
  auto align = [&](const std::string& comment, const std::vector<std::string>& rows) {
    if (rows.empty()) return;
    out += "% " + comment + "\n\\begin{align*}\n";
    for (std::size_t k = 0; k < rows.size(); ++k) out += rows[k] + (k + 1 < rows.size() ? " \\\\\n" : "\n");
    out += "\\end{align*}\n";
  };
  // `a = b` → `a &= b`
  auto at_equals = [](const std::string& s) {
    const auto k = s.find(" = ");
    return s.substr(0, k) + " &= " + s.substr(k + 3);
  };
  std::vector<std::string> rows;
  for (std::size_t i = 0; i < eq.coordinate_rates.size(); ++i) {
    if (eq.coordinate_rates[i].text == eq.coordinates[i] + "_dot") continue;  // a velocity
    std::string q_tex;
    for (const EquationSymbol& s : eq.symbols) {
      if (s.name == eq.coordinates[i]) q_tex = s.latex;
    }
    rows.push_back(fmt::format("\\dot{{{}}} &= {}", q_tex, eq.coordinate_rates[i].latex));
  }
  align("the balls' quaternions move by q' = q (0, omega)/2, omega in the body's frame", rows);
  rows.clear();
  for (const Printed& e : eq.equations) rows.push_back(at_equals(e.latex));
  align(eq.velocities.empty() ? "equations of motion, one per coordinate" : "equations of motion, one per velocity",
        rows);
  rows.clear();
  for (const auto& [name, value] : eq.intermediates) rows.push_back(name.latex + " &= " + value.latex);
  align("where: the tree's recursions, each from those before it", rows);
  rows.clear();
  for (std::size_t k = 0; k < eq.constraints.size(); ++k) {
    rows.push_back(fmt::format("{} &= 0 && \\text{{({})}}", eq.constraints[k].latex, tex_text(eq.constraint_names[k])));
  }
  align("holonomic constraints", rows);
  rows.clear();
  for (std::size_t k = 0; k < eq.velocity_constraints.size(); ++k) {
    rows.push_back(fmt::format("{} &= 0 && \\text{{({})}}", eq.velocity_constraints[k].latex,
                               tex_text(eq.velocity_constraint_names[k])));
  }
  align("velocity (nonholonomic) constraints", rows);
  align("Lagrangian, kinetic and potential energy (J)",
        {"\\mathcal{L} &= \\mathcal{T} - \\mathcal{V} = " + eq.lagrangian.latex,
         "\\mathcal{T} &= " + eq.kinetic_energy.latex, "\\mathcal{V} &= " + eq.potential_energy.latex});
  rows = {"\\mathbf{M} &= " + pmatrix(eq.mass_matrix)};
  std::vector<std::vector<Printed>> f;
  for (const Printed& x : eq.forcing) f.push_back({x});
  rows.push_back("\\mathbf{f} &= " + pmatrix(f));
  if (!eq.constraint_jacobian.empty()) rows.push_back("\\mathbf{G} &= " + pmatrix(eq.constraint_jacobian));
  if (!eq.velocity_constraint_matrix.empty()) {
    rows.push_back("\\mathbf{A} &= " + pmatrix(eq.velocity_constraint_matrix));
  }
  std::string what = "M(q) q'' = f(q, q', t)";
  if (!eq.constraint_jacobian.empty()) what += " + G^T lambda";
  if (!eq.velocity_constraint_matrix.empty()) what += " + A^T mu";
  if (!eq.constraint_jacobian.empty()) what += ", G = dg/dq";
  if (!eq.velocity_constraint_matrix.empty()) what += ", A q' + a = 0";
  align(what, rows);
  rows = {"\\mathcal{H} &= " + eq.jacobi_integral.latex +
          (eq.jacobi_conserved ? " && \\text{(Jacobi integral, conserved)}" : " && \\text{(Jacobi integral)}")};
  for (std::size_t c = 0; c < eq.cyclic_momenta.size(); ++c) {
    std::string q_tex;
    for (const EquationSymbol& s : eq.symbols) {
      if (s.name == eq.cyclic[c] + "_dot") q_tex = s.latex;
    }
    rows.push_back(fmt::format("\\frac{{\\partial \\mathcal{{L}}}}{{\\partial {}}} &= {} && \\text{{(cyclic, conserved)}}",
                               q_tex, eq.cyclic_momenta[c].latex));
  }
  align("conserved quantities", rows);
  if (!eq.note.empty()) out += "% " + eq.note + "\n";
  return out;
}

Json printed(const Printed& p) { return {{"text", p.text}, {"latex", p.latex}}; }
Json printed(const std::vector<Printed>& v) {
  Json text = Json::array(), latex = Json::array();
  for (const Printed& p : v) {
    text.push_back(p.text);
    latex.push_back(p.latex);
  }
  return {{"text", text}, {"latex", latex}};
}
Json printed(const std::vector<std::vector<Printed>>& rows) {
  Json text = Json::array(), latex = Json::array();
  for (const auto& row : rows) {
    const Json r = printed(row);
    text.push_back(r["text"]);
    latex.push_back(r["latex"]);
  }
  return {{"text", text}, {"latex", latex}};
}

std::string format_json(const Equations& eq) {
  Json j;
  j["kind"] = "coordinates";
  j["coordinates"] = eq.coordinates;
  if (!eq.velocities.empty()) {
    j["velocities"] = eq.velocities;
    j["coordinate_rates"] = printed(eq.coordinate_rates);
  }
  Json params = Json::array();
  for (const Parameter& p : eq.parameters) params.push_back({{"name", p.name}, {"value", p.value}});
  j["parameters"] = params;
  j["constraint_names"] = eq.constraint_names;
  j["equations"] = printed(eq.equations);
  if (!eq.intermediates.empty()) {
    Json where = Json::array();
    for (const auto& [name, value] : eq.intermediates) {
      where.push_back({{"name", name.text}, {"latex_name", name.latex}, {"text", value.text},
                       {"latex", value.latex}});
    }
    j["intermediates"] = where;
  }
  j["lagrangian"] = printed(eq.lagrangian);
  j["kinetic_energy"] = printed(eq.kinetic_energy);
  j["potential_energy"] = printed(eq.potential_energy);
  j["mass_matrix"] = printed(eq.mass_matrix);
  j["forcing"] = printed(eq.forcing);
  j["forcing_inertial"] = printed(eq.forcing_inertial);
  j["forcing_potential"] = printed(eq.forcing_potential);
  j["forcing_generalized"] = printed(eq.forcing_generalized);
  j["constraints"] = printed(eq.constraints);
  j["constraint_jacobian"] = printed(eq.constraint_jacobian);
  if (!eq.velocity_constraints.empty()) {
    j["velocity_constraint_names"] = eq.velocity_constraint_names;
    j["velocity_constraints"] = printed(eq.velocity_constraints);
    j["velocity_constraint_matrix"] = printed(eq.velocity_constraint_matrix);
  }
  Json h = printed(eq.jacobi_integral);
  h["conserved"] = eq.jacobi_conserved;
  j["jacobi_integral"] = h;
  j["cyclic_coordinates"] = eq.cyclic;
  j["cyclic_momenta"] = printed(eq.cyclic_momenta);
  Json symbols = Json::array();
  for (const EquationSymbol& s : eq.symbols) {
    symbols.push_back({{"name", s.name}, {"latex", s.latex}, {"role", s.role}, {"unit", s.unit}});
  }
  j["symbols"] = symbols;
  if (!eq.note.empty()) j["note"] = eq.note;
  return j.dump(2) + "\n";
}

}  // namespace

std::string format_equations(const Equations& eq, EquationFormat format) {
  switch (format) {
    case EquationFormat::kText: return format_text(eq);
    case EquationFormat::kLatex: return format_latex(eq);
    case EquationFormat::kJson: return format_json(eq);
  }
  return format_text(eq);
}

}  // namespace rigid::lagrange
