// Euler's equations of a free body or a heavy top, printed with the body's inertia as the
// scene (or caller) wrote it: parameters keep their names.
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <ginac/ginac.h>

#include "detail/symbolic_lock.hpp"
#include "detail/parser.hpp"
#include "detail/symbolic.hpp"
#include "rigid/lagrange/system.hpp"

namespace rigid::lagrange {

std::vector<std::string> free_body_equations(const std::vector<Parameter>& parameters,
                                             const FreeBodyEquationsSpec& body, bool latex) {
  detail::SymbolicLock lock;
  using GiNaC::ex;
  using GiNaC::symbol;
  std::map<std::string, ex> names;
  for (const Parameter& p : parameters) names[p.name] = symbol(p.name, detail::tex_name(p.name));
  auto parse = [&](const Expression& e, const std::string& what) {
    return detail::parse_expression(e, names, fmt::format("body '{}' {}", body.name, what));
  };
  auto print = [&](const ex& e) { return latex ? detail::to_latex(e) : detail::to_text(e); };

  // inertia about the COM, then about the pivot by the parallel-axis theorem
  const ex m = parse(body.mass.mass, "mass");
  detail::Mat3 I;
  for (std::size_t k = 0; k < 6; ++k) {
    const auto& [name, row, col] = BodyMass::kInertiaElements[k];
    I[row][col] = I[col][row] = parse(body.mass.inertia[k], name);
  }
  detail::Vec3 d;  // COM from the pivot (or 0)
  for (std::size_t k = 0; k < 3; ++k) {
    d[k] = parse(body.mass.com[k], fmt::format("com[{}]", k));
    if (body.has_pivot) d[k] -= parse(body.pivot_B[k], fmt::format("pivot[{}]", k));
  }
  if (body.has_pivot) {
    // I_P = I_C + m (|d|² 1 − d dᵀ)
    const ex d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) I[i][j] = I[i][j] + m * ((i == j ? d2 : ex(0)) - d[i] * d[j]);
  }
  for (auto& row : I)
    for (ex& e : row) e = detail::simplify(e);

  // I ω̇ = −ω × (I ω) + τ, one line per body axis; ω and τ in B
  const symbol w[3] = {symbol("w1", "\\omega_1"), symbol("w2", "\\omega_2"), symbol("w3", "\\omega_3")};
  const symbol wd[3] = {symbol("w1_dot", "\\dot\\omega_1"), symbol("w2_dot", "\\dot\\omega_2"),
                        symbol("w3_dot", "\\dot\\omega_3")};
  const symbol tau[3] = {symbol("tau1", "\\tau_1"), symbol("tau2", "\\tau_2"), symbol("tau3", "\\tau_3")};
  ex Iw[3];
  for (int i = 0; i < 3; ++i) Iw[i] = I[i][0] * w[0] + I[i][1] * w[1] + I[i][2] * w[2];
  std::vector<std::string> lines;
  const std::string about = body.has_pivot ? "pivot" : "COM";
  lines.push_back(latex ? fmt::format("% body {}: {}, inertia about the {} in the body frame B",
                                      body.name, body.has_pivot ? "heavy top" : "free", about)
                        : fmt::format("body '{}' ({}): mass {} kg, inertia about the {} in the body "
                                      "frame B (kg·m²):",
                                      body.name, body.has_pivot ? "heavy top on a pivot" : "free",
                                      print(m), about));
  if (!latex) {
    for (int i = 0; i < 3; ++i) {
      lines.push_back(fmt::format("  [{}, {}, {}]", print(I[i][0]), print(I[i][1]), print(I[i][2])));
    }
  }
  const GiNaC::lst ws{w[0], w[1], w[2]};
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    ex lhs = 0;
    for (int c = 0; c < 3; ++c) lhs += I[i][c] * wd[c];
    ex rhs = -(w[j] * Iw[k] - w[k] * Iw[j]);
    rhs = rhs.expand().collect(ws, true);
    if (body.has_pivot) rhs += tau[i];
    const std::string line = print(lhs) + " = " + print(rhs);
    lines.push_back(latex ? line : "  " + line);
  }
  lines.push_back(latex ? "\\dot R_{WB} = R_{WB}\\,[\\omega]_\\times"
                        : "  R_WB_dot = R_WB [w]x   (w = (w1, w2, w3) in the body frame B, rad/s)");
  detail::Vec3 g;
  for (std::size_t k = 0; k < 3; ++k) g[k] = parse(body.gravity_W[k], fmt::format("gravity[{}]", k));
  const std::string g_text = fmt::format("({}, {}, {})", print(g[0]), print(g[1]), print(g[2]));
  if (body.has_pivot) {
    const std::string d_text = fmt::format("({}, {}, {})", print(d[0]), print(d[1]), print(d[2]));
    lines.push_back(latex ? fmt::format("\\tau = {}\\, p_{{PC}} \\times (R_{{WB}}^T g),\\quad p_{{PC}} = {},\\quad g = {}",
                                        print(m), d_text, g_text)
                          : fmt::format("  tau = m p_PC x (R_WB^T g) with m = {} kg, p_PC = {} m (COM "
                                        "from the pivot, in B), g = {} m/s²",
                                        print(m), d_text, g_text));
  } else {
    lines.push_back(latex ? fmt::format("{}\\,\\ddot c = {}\\,g,\\quad g = {}", print(m), print(m), g_text)
                          : fmt::format("  m c_ddot = m g with m = {} kg, g = {} m/s² (the COM c moves "
                                        "on a parabola)",
                                        print(m), g_text));
  }
  return lines;
}

}  // namespace rigid::lagrange
