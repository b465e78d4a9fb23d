// Forward-mode derivatives through the named intermediates (detail/derivatives.hpp).
#include "detail/derivatives.hpp"

#include <map>
#include <string>

#include <fmt/format.h>

#include "detail/symbolic.hpp"

namespace rigid::lagrange::detail {
namespace {

using GiNaC::ex;

// The intermediates an expression reads (their indices into aux), each once.
std::vector<std::size_t> intermediates_in(const ex& e,
                                          const std::map<ex, std::size_t, GiNaC::ex_is_less>& index) {
  std::vector<std::size_t> out;
  std::map<ex, bool, GiNaC::ex_is_less> seen;
  for (auto it = e.preorder_begin(); it != e.preorder_end(); ++it) {
    if (!GiNaC::is_a<GiNaC::symbol>(*it)) continue;
    const auto found = index.find(*it);
    if (found != index.end() && seen.emplace(*it, true).second) out.push_back(found->second);
  }
  return out;
}

bool trivial(const ex& e) {
  return GiNaC::is_a<GiNaC::numeric>(e) || GiNaC::is_a<GiNaC::symbol>(e);
}

}  // namespace

ForwardDerivatives forward_derivatives(const std::vector<GiNaC::symbol>& aux,
                                       const std::vector<ex>& defs, const std::vector<ex>& outputs,
                                       const std::vector<GiNaC::symbol>& vars) {
  const std::size_t nv = vars.size();
  std::map<ex, std::size_t, GiNaC::ex_is_less> index;
  for (std::size_t k = 0; k < aux.size(); ++k) index.emplace(aux[k], k);
  ForwardDerivatives out;
  // D[k * nv + j] = ∂a_k/∂x_j: 0, a number, a variable or a named derivative intermediate
  std::vector<ex> D(aux.size() * nv, 0);
  // Σ-rule of one expression: ∂e/∂x_j through the intermediates it reads
  auto derivative = [&](const ex& e, const std::vector<std::size_t>& reads, std::size_t j) {
    ex sum = d(e, vars[j]);
    for (std::size_t i : reads) {
      if (D[i * nv + j].is_zero()) continue;
      sum += d(e, aux[i]) * D[i * nv + j];
    }
    return sum.expand();
  };
  // only the intermediates the outputs read, directly or through others (each reads only
  // earlier ones), are differentiated
  std::vector<bool> needed(aux.size(), false);
  for (const ex& e : outputs) {
    for (std::size_t i : intermediates_in(e, index)) needed[i] = true;
  }
  for (std::size_t k = aux.size(); k-- > 0;) {
    if (!needed[k]) continue;
    for (std::size_t i : intermediates_in(defs[k], index)) needed[i] = true;
  }
  for (std::size_t k = 0; k < aux.size(); ++k) {
    if (!needed[k]) continue;
    const std::vector<std::size_t> reads = intermediates_in(defs[k], index);
    for (std::size_t j = 0; j < nv; ++j) {
      const ex value = derivative(defs[k], reads, j);
      if (trivial(value)) {
        D[k * nv + j] = value;
        continue;
      }
      GiNaC::symbol name(fmt::format("d_{}_{}", aux[k].get_name(), j));
      out.definitions.emplace_back(name, value);
      D[k * nv + j] = name;
    }
  }
  out.d.reserve(outputs.size() * nv);
  for (const ex& e : outputs) {
    const std::vector<std::size_t> reads = intermediates_in(e, index);
    for (std::size_t j = 0; j < nv; ++j) out.d.push_back(derivative(e, reads, j));
  }
  return out;
}

}  // namespace rigid::lagrange::detail
