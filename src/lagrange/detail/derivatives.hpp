#pragma once

// Exact first derivatives of expressions that use a system's named intermediates (the
// recursive derivation's aux), by forward-mode differentiation through them: each intermediate
// a_k = def_k(x, a_<k) gets, per variable x_j, the intermediate
//   ∂a_k/∂x_j = ∂def_k/∂x_j + Σ_i ∂def_k/∂a_i · ∂a_i/∂x_j,
// named in turn, so that the derivatives of a tree stay linear in its size (differentiating
// the expanded outputs instead would undo the intermediates). Where ∂a_k/∂x_j is zero (link k
// does not move with joint j) nothing is named.

#include <utility>
#include <vector>

#include <ginac/ginac.h>

#include "system_impl.hpp"

namespace rigid::lagrange::detail {

struct ForwardDerivatives {
  /// The derivative intermediates, in an order in which each uses only the system's
  /// intermediates and the ones before it: define them after s.aux.
  std::vector<std::pair<GiNaC::symbol, GiNaC::ex>> definitions;
  /// d[i * vars.size() + j] = ∂outputs[i]/∂vars[j].
  std::vector<GiNaC::ex> d;
};

/// ∂outputs/∂vars for outputs in the inputs (q, q̇, q̈, t, parameters) and the intermediates
/// `aux`, each defined by `defs` in terms of the inputs and the intermediates before it.
[[nodiscard]] ForwardDerivatives forward_derivatives(const std::vector<GiNaC::symbol>& aux,
                                                     const std::vector<GiNaC::ex>& defs,
                                                     const std::vector<GiNaC::ex>& outputs,
                                                     const std::vector<GiNaC::symbol>& vars);

}  // namespace rigid::lagrange::detail
