#pragma once

// Canonical printing of the equations (text and LaTeX) and the simplification a textbook does
// before printing. GiNaC orders the operands of a sum or a product by hashes that change from
// run to run, so its own printer gives different bytes on every run; this printer walks the
// expression tree and sorts with a key of its own:
//   terms of a sum    by their coordinates (index, then derivative order), then multipliers,
//                     t, parameters in declaration order; terms without any of these last;
//   factors of a term numbers, parenthesised sums, parameters, functions, then coordinates
//                     and their derivatives;
// ties are broken by the printed text, so equal inputs give equal bytes.

#include <map>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <ginac/ginac.h>

namespace rigid::lagrange::detail {

/// Values remembered per subexpression (by hash, then structural equality). The printer's walks
/// go through a GiNaC expression as a tree, but GiNaC shares subexpressions: without a memo a
/// part used k times is printed and keyed k times, and nested uses multiply (the equations of
/// nested powers of sums took seconds to print 21 KB).
template <typename V>
class ExMemo {
 public:
  [[nodiscard]] const V* find(const GiNaC::ex& e) const {
    const auto [lo, hi] = items_.equal_range(e.gethash());
    for (auto it = lo; it != hi; ++it) {
      if (it->second.first.is_equal(e)) return &it->second.second;
    }
    return nullptr;
  }
  const V& remember(const GiNaC::ex& e, V value) {
    return items_.emplace(e.gethash(), std::make_pair(e, std::move(value)))->second.second;
  }

 private:
  std::unordered_multimap<unsigned, std::pair<GiNaC::ex, V>> items_;
};

/// The symbols' codes of a subexpression as counts (code → number of occurrences, a power's
/// base counted by its small integer exponent; GiNaC's constants once per occurrence, whatever
/// the exponent): what orders the terms of a sum.
struct SymbolCodes {
  std::map<std::string, double> dynamic, rest, constants;
};

/// The rank of each named symbol in the canonical order. Unknown symbols rank after all known
/// ones, by name. It also holds the printer's memos (printed text, symbol codes, whether a
/// part depends on the dynamic symbols), valid while the order is in use; one order is used by
/// one thread at a time.
class SymbolOrder {
 public:
  enum Group : int { kCoordinate = 0, kMultiplier = 1, kTime = 2, kParameter = 3, kOther = 4 };
  /// `index`: coordinate, multiplier or parameter number; `order`: derivative order (0 for q,
  /// 1 for q̇, 2 for q̈).
  void add(const GiNaC::symbol& s, Group group, int index, int order = 0);
  /// A fixed-width code whose byte order is the canonical order.
  [[nodiscard]] std::string code(const GiNaC::symbol& s) const;
  /// True for coordinates, their derivatives, multipliers and t: the "dynamic" atoms that
  /// terms are grouped by; everything else is a constant of the model.
  [[nodiscard]] bool is_dynamic(const GiNaC::symbol& s) const;
  /// Printed functions (text, LaTeX), remembered while this order is in use: sin(q1 − q2)
  /// appears in many terms.
  [[nodiscard]] const std::string* find_printed(const GiNaC::ex& f, bool latex) const;
  void remember_printed(const GiNaC::ex& f, bool latex, std::string text) const;
  /// number_text(x, latex), once per distinct number.
  [[nodiscard]] const std::string& number_text_of(const GiNaC::numeric& x, bool latex) const;
  /// The codes of the symbols in e (SymbolCodes), computed once per distinct subexpression.
  [[nodiscard]] const SymbolCodes& codes_of(const GiNaC::ex& e) const;
  /// Whether e holds a coordinate, a derivative, a multiplier or t, once per subexpression.
  [[nodiscard]] bool has_dynamic(const GiNaC::ex& e) const;

 private:
  struct Rank {
    Group group;
    int index, order;
    std::string code;
  };
  std::map<std::string, Rank> ranks_;
  mutable ExMemo<std::string> printed_[2];
  mutable ExMemo<std::string> numbers_[2];
  mutable ExMemo<SymbolCodes> codes_;
  mutable ExMemo<bool> dynamic_;
};

struct Term;
/// A printable sum: terms in canonical order (or in the given order, `keep_order`).
struct Sum {
  std::vector<Term> terms;
  bool keep_order = false;
};
/// coef · Π sums · Π factors; factors are GiNaC atoms, functions and powers (a power with a
/// negative exponent prints in the denominator).
struct Term {
  GiNaC::numeric coef{1};
  std::vector<Sum> sums;
  GiNaC::exvector factors;
};

/// The expression as it stands (no simplification), as a sum in canonical order.
[[nodiscard]] Sum plain(const GiNaC::ex& e, const SymbolOrder& order);
/// The simplification a textbook does before printing: expand; sin² + cos² = 1 (the form
/// with fewer terms); cos a cos b ± sin a sin b = cos(a ∓ b), sin a cos b ± cos a sin b =
/// sin(a ± b); terms collected per product of dynamic atoms (coordinates, velocities,
/// accelerations, multipliers, t) with the common factors of their coefficients (numbers,
/// parameters) taken out. The result equals `e` identically.
[[nodiscard]] Sum textbook(const GiNaC::ex& e, const SymbolOrder& order);
/// Σ_j a_j x_j in the order of j, each a_j simplified as by textbook(): "collected per x_j".
[[nodiscard]] Sum collected(const std::vector<GiNaC::ex>& coefficients,
                            const std::vector<GiNaC::ex>& atoms, const SymbolOrder& order);

[[nodiscard]] std::string print(const Sum& s, const SymbolOrder& order, bool latex);
/// The same sum rebuilt as a GiNaC expression (for checks).
[[nodiscard]] GiNaC::ex to_ex(const Sum& s);

/// A number as text or LaTeX: integers as they are; a rational with a terminating decimal
/// expansion as that decimal when it is shorter (7/10 → 0.7, 1/2 stays 1/2); other rationals
/// as p/q while short, else the shortest round-trip decimal of the double nearest to it.
[[nodiscard]] std::string number_text(const GiNaC::numeric& x, bool latex);

}  // namespace rigid::lagrange::detail
