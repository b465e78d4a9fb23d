#pragma once

// Symbolic building blocks of the Lagrangian engine (GiNaC): names, derivatives, the
// simplification that cancels sin² + cos², printing, exact numbers and 3×3 rotations.

#include <array>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <string_view>

#include <Eigen/Core>
#include <ginac/ginac.h>

namespace rigid::lagrange::detail {

/// Letters, digits and '_', not starting with a digit.
[[nodiscard]] bool is_identifier(const std::string& s);
/// t, pi and the function names.
[[nodiscard]] const std::set<std::string>& reserved_names();
/// TeX for a name: Greek letter names become the letter, trailing digits or "_x" a subscript.
[[nodiscard]] std::string tex_name(const std::string& name);
/// ∂e/∂x by the sum, product, power and chain rules (subtrees free of x are skipped).
[[nodiscard]] GiNaC::ex d(const GiNaC::ex& e, const GiNaC::symbol& x);
/// A node's replacement, or nothing where the node is to be kept (its operands then visited).
using Rewrite = std::function<std::optional<GiNaC::ex>(const GiNaC::ex&)>;
/// `rule` applied over e's graph, each distinct subexpression once; a node is rebuilt only when
/// one of its operands changed, and e itself comes back when nothing did. GiNaC's map() walks a
/// shared subexpression once per use and rebuilds (and re-evaluates) every node it passes.
[[nodiscard]] GiNaC::ex rewrite(const GiNaC::ex& e, const Rewrite& rule);
/// Highest power of a sine or cosine rewritten through sin² + cos² = 1: the rewrite makes a
/// power of a sum, (1 − cos²x)^(n/2), which expands to n/2 + 1 terms (sin(a + pi)^730452665 from
/// the fuzz target asked for gigabytes). Kinetic energies give powers up to 4.
inline constexpr long kMaxTrigPowerRewritten = 64;
/// Through sin² + cos² = 1: sinⁿx → sin^(n mod 2)x · (1 − cos²x)^(n/2) when `function` is "sin",
/// cosⁿx → cos^(n mod 2)x · (1 − sin²x)^(n/2) when it is "cos", for 2 ≤ n ≤
/// kMaxTrigPowerRewritten and, when `argument` is given, x equal to it; nothing otherwise.
[[nodiscard]] std::optional<GiNaC::ex> trig_power_through_pythagoras(const GiNaC::ex& e, std::string_view function,
                                                                     const GiNaC::ex* argument = nullptr);
/// expand, with sinⁿx → sin^(n mod 2)x · (1 − cos²x)^(n/2) so that sin² + cos² cancels.
[[nodiscard]] GiNaC::ex simplify(const GiNaC::ex& e);
[[nodiscard]] std::string to_text(const GiNaC::ex& e);
[[nodiscard]] std::string to_latex(const GiNaC::ex& e);
/// A double as the exact rational of its shortest round-trip decimal (0.7 → 7/10).
[[nodiscard]] GiNaC::ex number(double v);

using Mat3 = std::array<std::array<GiNaC::ex, 3>, 3>;
using Vec3 = std::array<GiNaC::ex, 3>;
[[nodiscard]] Mat3 mat_mul(const Mat3& A, const Mat3& B);
[[nodiscard]] Vec3 mat_vec(const Mat3& A, const Vec3& v);
[[nodiscard]] Vec3 mat_t_vec(const Mat3& A, const Vec3& v);
[[nodiscard]] Mat3 identity3();
/// R = exp(θ[a]ₓ) = 1 + sin θ [a]ₓ + (1 − cos θ)[a]ₓ² (Rodrigues), a a unit vector.
[[nodiscard]] Mat3 rodrigues(const Eigen::Vector3d& a, const GiNaC::ex& theta);

}  // namespace rigid::lagrange::detail
