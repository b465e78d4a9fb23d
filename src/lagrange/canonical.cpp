// Canonical printing and textbook simplification of the equations (see detail/canonical.hpp).
// GiNaC's printer and its collect()/factor() follow GiNaC's internal operand order, which
// depends on hash values that differ between runs; nothing here iterates in that order
// without sorting by a key of its own first.
#include "detail/canonical.hpp"

#include <algorithm>
#include <optional>
#include <sstream>
#include <unordered_map>
#include <utility>

#include <fmt/format.h>

#include "detail/symbolic.hpp"

namespace rigid::lagrange::detail {

using GiNaC::ex;
using GiNaC::exvector;
using GiNaC::is_a;
using GiNaC::numeric;
using GiNaC::symbol;

void SymbolOrder::add(const symbol& s, Group group, int index, int order) {
  ranks_[s.get_name()] = Rank{group, index, order,
                              fmt::format("{}{:06d}{}", static_cast<int>(group), index, order)};
}

std::string SymbolOrder::code(const symbol& s) const {
  const auto it = ranks_.find(s.get_name());
  if (it == ranks_.end()) return "4" + s.get_name();
  return it->second.code;
}

const std::string* SymbolOrder::find_printed(const ex& f, bool latex) const {
  return printed_[latex ? 1 : 0].find(f);
}

void SymbolOrder::remember_printed(const ex& f, bool latex, std::string text) const {
  printed_[latex ? 1 : 0].remember(f, std::move(text));
}

const std::string& SymbolOrder::number_text_of(const numeric& x, bool latex) const {
  const ex key = x;
  if (const std::string* known = numbers_[latex ? 1 : 0].find(key)) return *known;
  return numbers_[latex ? 1 : 0].remember(key, number_text(x, latex));
}

bool SymbolOrder::is_dynamic(const symbol& s) const {
  const auto it = ranks_.find(s.get_name());
  return it != ranks_.end() && it->second.group <= kTime;
}

namespace {

// GiNaC's constants (Pi, Euler, Catalan) by the name its printer gives them
std::string constant_name(const ex& e) {
  std::ostringstream os;
  os << e;
  return os.str();
}

// number_text once per distinct number and flag: a long integer or rational is written out in
// decimal to be printed or measured, quadratic in its digits (CLN), and a sort prints the same
// coefficient again at every tie (a sum to the 8th of 99^999 and 699^-999 spent 20 s there)
std::string number_of(const numeric& x, bool latex, const SymbolOrder& order) {
  if (x.is_integer() && GiNaC::abs(x) < numeric(1000000000L)) return number_text(x, latex);
  return order.number_text_of(x, latex);
}

// counts add up to at most this (a code repeated more often in a key sorts as if it were
// repeated this often; no printed equation holds a symbol this often in one term)
constexpr double kMaxCodeCount = 1024;

void add_counts(std::map<std::string, double>& to, const std::map<std::string, double>& from, double times) {
  for (const auto& [code, n] : from) {
    double& c = to[code];
    c = std::min(c + n * times, kMaxCodeCount);
  }
}

}  // namespace

const SymbolCodes& SymbolOrder::codes_of(const ex& e) const {
  if (const SymbolCodes* known = codes_.find(e)) return *known;
  SymbolCodes out;
  if (is_a<symbol>(e)) {
    const symbol& s = GiNaC::ex_to<symbol>(e);
    (is_dynamic(s) ? out.dynamic : out.rest)[code(s)] = 1;
  } else if (is_a<GiNaC::constant>(e)) {
    out.constants["5" + constant_name(e)] = 1;
  } else if (is_a<GiNaC::power>(e) && is_a<numeric>(e.op(1))) {
    // the base repeated by its (small) integer exponent
    const numeric& p = GiNaC::ex_to<numeric>(e.op(1));
    const double n = p.is_pos_integer() && p <= 4 ? static_cast<double>(p.to_long()) : 1;
    const SymbolCodes& base = codes_of(e.op(0));
    add_counts(out.dynamic, base.dynamic, n);
    add_counts(out.rest, base.rest, n);
    add_counts(out.constants, base.constants, 1);
  } else if (!is_a<numeric>(e)) {
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const SymbolCodes& part = codes_of(e.op(i));
      add_counts(out.dynamic, part.dynamic, 1);
      add_counts(out.rest, part.rest, 1);
      add_counts(out.constants, part.constants, 1);
    }
  }
  return codes_.remember(e, std::move(out));
}

bool SymbolOrder::has_dynamic(const ex& e) const {
  if (is_a<symbol>(e)) return is_dynamic(GiNaC::ex_to<symbol>(e));
  if (e.nops() == 0) return false;
  if (const bool* known = dynamic_.find(e)) return *known;
  bool found = false;
  for (std::size_t i = 0; i < e.nops() && !found; ++i) found = has_dynamic(e.op(i));
  return dynamic_.remember(e, found);
}

namespace {

void collect_term_codes(const Term& t, const SymbolOrder& order, SymbolCodes& out) {
  for (const ex& f : t.factors) {
    const SymbolCodes& c = order.codes_of(f);
    add_counts(out.dynamic, c.dynamic, 1);
    add_counts(out.rest, c.rest, 1);
    add_counts(out.constants, c.constants, 1);
  }
  for (const Sum& s : t.sums) {
    for (const Term& u : s.terms) collect_term_codes(u, order, out);
  }
}

// each code followed by \x02, as often as it occurs, in byte order
void append_codes(std::string& key, const std::map<std::string, double>& counts) {
  for (const auto& [code, n] : counts) {
    for (double k = 0; k < n; ++k) key += code + '\x02';
  }
}

// the sort key of a term: its dynamic atoms (coordinates by index, then derivative order;
// multipliers; t), then the other symbols (parameters in declaration order); a term without
// dynamic atoms sorts after all that have some
std::string term_key(const Term& t, const SymbolOrder& order) {
  SymbolCodes codes;
  collect_term_codes(t, order, codes);
  for (const auto& [code, n] : codes.constants) codes.rest[code] += n;  // "5…": after the symbols
  std::string key = codes.dynamic.empty() ? std::string("\x7f") : std::string();
  append_codes(key, codes.dynamic);
  key += '\x01';
  append_codes(key, codes.rest);
  if (codes.rest.empty()) key += '\x7f';  // numbers after parameters
  return key;
}

// the sort key of a factor: numbers, constants, parameters (and other non-dynamic symbols),
// functions, dynamic symbols, then anything else
std::string factor_key(const ex& f, const SymbolOrder& order) {
  const ex base = is_a<GiNaC::power>(f) ? f.op(0) : f;
  const SymbolCodes& counts = order.codes_of(base);
  std::string codes;
  append_codes(codes, counts.dynamic);
  append_codes(codes, counts.rest);
  append_codes(codes, counts.constants);
  if (is_a<numeric>(base)) return "0";
  if (is_a<GiNaC::constant>(base)) return "1" + codes;
  if (is_a<symbol>(base)) {
    return (order.is_dynamic(GiNaC::ex_to<symbol>(base)) ? "4" : "2") + codes;
  }
  if (is_a<GiNaC::function>(base)) {
    return "3" + codes + GiNaC::ex_to<GiNaC::function>(base).get_name();
  }
  return "5" + codes;
}

Term term_of(const ex& e, const SymbolOrder& order);

// sorts by key; only items with equal keys are compared by their printed text (printing is
// the costly part), so the order never depends on the items' original (GiNaC) order
template <typename T, typename KeyFn, typename TextFn>
void canonical_sort(std::vector<T>& items, KeyFn key, TextFn text) {
  std::vector<std::pair<std::string, std::size_t>> keyed;
  keyed.reserve(items.size());
  for (std::size_t i = 0; i < items.size(); ++i) keyed.push_back({key(items[i]), i});
  std::sort(keyed.begin(), keyed.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  for (std::size_t lo = 0; lo < keyed.size();) {
    std::size_t hi = lo + 1;
    while (hi < keyed.size() && keyed[hi].first == keyed[lo].first) ++hi;
    if (hi - lo > 1) {
      std::vector<std::pair<std::string, std::size_t>> run;
      for (std::size_t k = lo; k < hi; ++k) run.push_back({text(items[keyed[k].second]), keyed[k].second});
      std::sort(run.begin(), run.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      for (std::size_t k = lo; k < hi; ++k) keyed[k].second = run[k - lo].second;
    }
    lo = hi;
  }
  std::vector<T> sorted;
  sorted.reserve(items.size());
  for (const auto& k : keyed) sorted.push_back(std::move(items[k.second]));
  items = std::move(sorted);
}

void sort_sum(Sum& s, const SymbolOrder& order) {
  if (s.keep_order) return;
  canonical_sort(
      s.terms, [&](const Term& t) { return term_key(t, order); },
      [&](const Term& t) {
        Sum one;
        one.terms.push_back(t);
        return print(one, order, false);
      });
}

Term term_of(const ex& e, const SymbolOrder& order) {
  Term t;
  auto take = [&](const ex& f) {
    if (is_a<numeric>(f)) {
      t.coef *= GiNaC::ex_to<numeric>(f);
    } else if (is_a<GiNaC::add>(f)) {
      t.sums.push_back(plain(f, order));
    } else {
      t.factors.push_back(f);
    }
  };
  if (is_a<GiNaC::mul>(e)) {
    for (std::size_t i = 0; i < e.nops(); ++i) take(e.op(i));
  } else {
    take(e);
  }
  return t;
}

bool is_fraction_text(const std::string& s) { return s.find('/') != std::string::npos; }

std::string join(const std::vector<std::string>& parts, const char* sep) {
  std::string out;
  for (std::size_t i = 0; i < parts.size(); ++i) out += (i ? sep : "") + parts[i];
  return out;
}

std::string print_atom(const ex& e, const SymbolOrder& order, bool latex);
std::string print_compound(const ex& e, const SymbolOrder& order, bool latex);

// a power's base: atoms as they are, anything else in parentheses
std::string print_base(const ex& b, const SymbolOrder& order, bool latex) {
  const std::string s = print_atom(b, order, latex);
  const bool atom = is_a<symbol>(b) || is_a<GiNaC::constant>(b) || is_a<GiNaC::function>(b) ||
                    (is_a<numeric>(b) && GiNaC::ex_to<numeric>(b).is_pos_integer());
  if (atom) return s;
  return latex ? "\\left(" + s + "\\right)" : "(" + s + ")";
}

bool is_trig(const ex& e) {
  if (!is_a<GiNaC::function>(e)) return false;
  const std::string n = GiNaC::ex_to<GiNaC::function>(e).get_name();
  return n == "sin" || n == "cos" || n == "tan" || n == "sinh" || n == "cosh" || n == "tanh";
}

// b^p with p > 0 (a negative power is printed by the term as a denominator)
std::string print_power(const ex& b, const ex& p, const SymbolOrder& order, bool latex) {
  if (p.is_equal(1)) return print_atom(b, order, latex);
  if (p.is_equal(GiNaC::numeric(1, 2))) {
    const std::string s = print_atom(b, order, latex);
    return latex ? "\\sqrt{" + s + "}" : "sqrt(" + s + ")";
  }
  const bool simple = is_a<numeric>(p) && GiNaC::ex_to<numeric>(p).is_pos_integer();
  const std::string ps = print_atom(p, order, latex);
  if (latex) {
    // sin²(θ) as a textbook writes it
    if (simple && is_trig(b)) {
      std::string s = print_atom(b, order, latex);
      const auto paren = s.find('(');
      return s.substr(0, paren) + "^{" + ps + "}" + s.substr(paren);
    }
    return print_base(b, order, latex) + "^{" + ps + "}";
  }
  return print_base(b, order, latex) + "^" + (simple ? ps : "(" + ps + ")");
}

std::string function_latex(const std::string& name) {
  if (name == "asin") return "\\arcsin";
  if (name == "acos") return "\\arccos";
  if (name == "atan") return "\\arctan";
  if (name == "log") return "\\ln";
  return "\\" + name;
}

std::string print_atom(const ex& e, const SymbolOrder& order, bool latex) {
  if (is_a<symbol>(e)) {
    const symbol& s = GiNaC::ex_to<symbol>(e);
    if (!latex) return s.get_name();
    const std::string tex = s.get_TeX_name();
    return tex.empty() ? tex_name(s.get_name()) : tex;
  }
  if (is_a<numeric>(e)) return number_of(GiNaC::ex_to<numeric>(e), latex, order);
  if (is_a<GiNaC::constant>(e)) {
    const std::string n = constant_name(e);
    return latex && n == "Pi" ? "\\pi" : (n == "Pi" ? "pi" : n);
  }
  // everything else once per distinct subexpression (SymbolOrder's memo)
  if (const std::string* known = order.find_printed(e, latex)) return *known;
  std::string out = print_compound(e, order, latex);
  order.remember_printed(e, latex, out);
  return out;
}

std::string print_compound(const ex& e, const SymbolOrder& order, bool latex) {
  if (is_a<GiNaC::power>(e)) {
    const ex p = e.op(1);
    if (is_a<numeric>(p) && GiNaC::ex_to<numeric>(p).is_negative()) {
      return print(plain(e, order), order, latex);  // a lone 1/x: the term prints it
    }
    return print_power(e.op(0), p, order, latex);
  }
  if (is_a<GiNaC::function>(e)) {
    const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
    std::vector<std::string> args;
    for (std::size_t i = 0; i < e.nops(); ++i) args.push_back(print(plain(e.op(i), order), order, latex));
    std::string out;
    if (!latex) {
      out = name + "(" + join(args, ", ") + ")";
    } else if (name == "abs") {
      out = "\\left|" + join(args, ", ") + "\\right|";
    } else if (name == "exp") {
      out = "e^{" + join(args, ", ") + "}";
    } else {
      out = function_latex(name) + "(" + join(args, ", ") + ")";
    }
    return out;
  }
  return print(plain(e, order), order, latex);
}

// |t| (the sign is returned in `negative`)
std::string print_term(const Term& t, const SymbolOrder& order, bool latex, bool& negative) {
  negative = t.coef.is_negative();
  const numeric a = negative ? numeric(-t.coef) : t.coef;
  std::vector<std::string> num, den;
  for (const Sum& s : t.sums) {
    const std::string x = print(s, order, latex);
    num.push_back(latex ? "\\left(" + x + "\\right)" : "(" + x + ")");
  }
  std::sort(num.begin(), num.end());
  exvector factors = t.factors;
  if (factors.size() > 1) {
    canonical_sort(
        factors, [&](const ex& f) { return factor_key(f, order); },
        [&](const ex& f) { return print_atom(f, order, false); });
  }
  for (const ex& f : factors) {
    if (is_a<GiNaC::power>(f) && is_a<numeric>(f.op(1)) && GiNaC::ex_to<numeric>(f.op(1)).is_negative()) {
      den.push_back(print_power(f.op(0), -f.op(1), order, latex));
    } else {
      num.push_back(print_atom(f, order, latex));
    }
  }
  const std::string coef = number_of(a, false, order);
  if (!latex) {
    std::vector<std::string> parts;
    if (!a.is_equal(1) || (num.empty() && den.empty())) parts.push_back(coef);
    parts.insert(parts.end(), num.begin(), num.end());
    std::string out = parts.empty() ? "1" : join(parts, "*");
    if (!den.empty()) out += "/" + (den.size() == 1 ? den[0] : "(" + join(den, "*") + ")");
    return out;
  }
  // LaTeX: \frac{1}{2} m l^{2}; with denominators one \frac{3 g}{2 L}
  const bool fraction = is_fraction_text(coef);
  if (den.empty()) {
    std::vector<std::string> parts;
    if (fraction) {
      parts.push_back("\\frac{" + number_of(a.numer(), true, order) + "}{" + number_of(a.denom(), true, order) + "}");
    } else if (!a.is_equal(1) || num.empty()) {
      parts.push_back(coef);
    }
    parts.insert(parts.end(), num.begin(), num.end());
    return join(parts, " ");
  }
  std::vector<std::string> top, bottom;
  if (fraction) {
    if (!a.numer().is_equal(1) || num.empty()) top.push_back(number_of(a.numer(), true, order));
    bottom.push_back(number_of(a.denom(), true, order));
  } else if (!a.is_equal(1) || num.empty()) {
    top.push_back(coef);
  }
  top.insert(top.end(), num.begin(), num.end());
  bottom.insert(bottom.end(), den.begin(), den.end());
  return "\\frac{" + join(top, " ") + "}{" + join(bottom, " ") + "}";
}

// sin(x) or −sin(−x), cos(−x): the argument's first term (canonical order) positive
ex signed_sin(const ex& x, const SymbolOrder& order) {
  const ex a = x.expand();
  const Sum s = plain(a, order);
  if (!s.terms.empty() && s.terms.front().coef.is_negative()) return -GiNaC::sin(-a);
  return GiNaC::sin(a);
}
ex signed_cos(const ex& x, const SymbolOrder& order) {
  const ex a = x.expand();
  const Sum s = plain(a, order);
  if (!s.terms.empty() && s.terms.front().coef.is_negative()) return GiNaC::cos(-a);
  return GiNaC::cos(a);
}

exvector operands(const ex& e) {
  if (is_a<GiNaC::add>(e)) return exvector(e.begin(), e.end());
  if (e.is_zero()) return {};
  return {e};
}
exvector factors_of(const ex& e) {
  if (is_a<GiNaC::mul>(e)) return exvector(e.begin(), e.end());
  return {e};
}

void sort_canonically(exvector& v, const SymbolOrder& order) {
  canonical_sort(
      v, [&](const ex& e) { return term_key(term_of(e, order), order); },
      [&](const ex& e) {
        Sum one;
        one.terms.push_back(term_of(e, order));
        return print(one, order, false);
      });
}

bool is_named(const ex& e, const char* name) {
  return is_a<GiNaC::function>(e) && GiNaC::ex_to<GiNaC::function>(e).get_name() == name;
}

// cos a cos b ± sin a sin b → cos(a ∓ b), sin a cos b ± cos a sin b → sin(a ± b), for any two
// terms that differ only in these factors (the rest equal, up to sign). Terms are visited in
// canonical order and the search restarts after each merge, so the result does not depend on
// GiNaC's operand order.
void sum_to_product(exvector& terms, const SymbolOrder& order) {
  for (bool changed = true; changed;) {
    changed = false;
    sort_canonically(terms, order);
    // terms by hash (for finding a partner only; the visiting order is the canonical one)
    std::unordered_multimap<unsigned, std::size_t> by_hash;
    for (std::size_t j = 0; j < terms.size(); ++j) by_hash.emplace(terms[j].gethash(), j);
    std::vector<bool> used(terms.size(), false);
    auto find = [&](const ex& e, std::size_t self) -> std::ptrdiff_t {
      const auto [lo, hi] = by_hash.equal_range(e.gethash());
      std::ptrdiff_t best = -1;
      for (auto it = lo; it != hi; ++it) {
        const std::size_t j = it->second;
        // the first in canonical order among equal candidates
        if (j != self && !used[j] && terms[j].is_equal(e) && (best < 0 || j < static_cast<std::size_t>(best))) {
          best = static_cast<std::ptrdiff_t>(j);
        }
      }
      return best;
    };
    exvector out;
    for (std::size_t i = 0; i < terms.size(); ++i) {
      if (used[i]) continue;
      exvector trig;
      for (const ex& f : factors_of(terms[i])) {
        if (is_named(f, "sin") || is_named(f, "cos")) trig.push_back(f);
      }
      bool merged = false;
      for (std::size_t u = 0; u < trig.size() && !merged; ++u) {
        for (std::size_t v = u + 1; v < trig.size() && !merged; ++v) {
          ex X = trig[u], Y = trig[v];
          if (X.op(0).is_equal(Y.op(0))) continue;
          // order the pair as (sin, cos) when mixed
          if (is_named(X, "cos") && is_named(Y, "sin")) std::swap(X, Y);
          const ex a = X.op(0), b = Y.op(0);
          const ex rest = terms[i] / (X * Y);
          ex partner;
          int kind = 0;
          if (is_named(X, "cos") && is_named(Y, "cos")) {
            partner = rest * GiNaC::sin(a) * GiNaC::sin(b);
          } else if (is_named(X, "sin") && is_named(Y, "sin")) {
            partner = rest * GiNaC::cos(a) * GiNaC::cos(b);
            kind = 1;
          } else {
            partner = rest * GiNaC::cos(a) * GiNaC::sin(b);
            kind = 2;
          }
          std::ptrdiff_t j = find(partner, i);
          const bool plus = j >= 0;
          if (!plus) j = find(-partner, i);
          if (j < 0) continue;
          ex merged_term;
          if (kind == 0) {         // cos a cos b ± sin a sin b
            merged_term = rest * (plus ? signed_cos(a - b, order) : signed_cos(a + b, order));
          } else if (kind == 1) {  // sin a sin b ± cos a cos b
            merged_term = plus ? rest * signed_cos(a - b, order) : -rest * signed_cos(a + b, order);
          } else {                 // sin a cos b ± cos a sin b
            merged_term = rest * (plus ? signed_sin(a + b, order) : signed_sin(a - b, order));
          }
          used[i] = used[static_cast<std::size_t>(j)] = true;
          out.push_back(merged_term.expand());
          merged = changed = true;
        }
      }
      if (!merged) {
        used[i] = true;
        out.push_back(terms[i]);
      }
    }
    terms = std::move(out);
  }
}

// the arguments a of every cosⁿ(a), n ≥ 2, in e (each distinct subexpression visited once)
void squared_cosines(const ex& e, exvector& out, ExMemo<bool>& seen) {
  if (e.nops() == 0 || seen.find(e)) return;
  seen.remember(e, true);
  if (is_a<GiNaC::power>(e) && is_named(e.op(0), "cos") && is_a<numeric>(e.op(1)) &&
      GiNaC::ex_to<numeric>(e.op(1)).is_integer() && GiNaC::ex_to<numeric>(e.op(1)) >= 2) {
    const ex a = e.op(0).op(0);
    if (std::none_of(out.begin(), out.end(), [&](const ex& x) { return x.is_equal(a); })) out.push_back(a);
  }
  for (std::size_t i = 0; i < e.nops(); ++i) squared_cosines(e.op(i), out, seen);
}

// the sin² + cos² = 1 form with fewer terms, argument by argument (in canonical order)
ex fewer_terms(ex e, const SymbolOrder& order) {
  exvector args;
  ExMemo<bool> seen;
  squared_cosines(e, args, seen);
  sort_canonically(args, order);
  for (const ex& a : args) {
    const ex candidate = rewrite(e, [&](const ex& x) { return trig_power_through_pythagoras(x, "cos", &a); }).expand();
    if (operands(candidate).size() < operands(e).size()) e = candidate;
  }
  return e;
}

numeric abs_numeric(const numeric& x) { return x.is_negative() ? numeric(-x) : x; }

// Σ coef·Π bases^exps with one dynamic part: the common number (gcd of numerators over the
// lcm of denominators, negative when every coefficient is) and the common bases (present in
// every monomial with exponents of one sign) taken out
struct Monomial {
  numeric coef;
  std::vector<std::pair<ex, numeric>> powers;  // non-dynamic base, exponent
};

Term factor_group(const std::vector<Monomial>& monomials, const ex& dynamic, const SymbolOrder& order) {
  Term out;
  numeric g = 0, l = 1;
  bool all_negative = true;
  for (const Monomial& m : monomials) {
    g = GiNaC::gcd(g, abs_numeric(m.coef.numer()));
    l = GiNaC::lcm(l, m.coef.denom());
    all_negative = all_negative && m.coef.is_negative();
  }
  numeric content = g / l;
  if (all_negative) content = -content;
  if (content.is_zero()) content = 1;
  // common bases
  std::vector<std::pair<ex, numeric>> common;
  for (const auto& front_power : monomials.front().powers) {
    const ex& base = front_power.first;
    numeric lo = 0;
    bool everywhere = true, first = true;
    int sign = 0;
    for (const Monomial& m : monomials) {
      auto it = std::find_if(m.powers.begin(), m.powers.end(), [&](const auto& p) { return p.first.is_equal(base); });
      if (it == m.powers.end()) {
        everywhere = false;
        break;
      }
      const int s = it->second.is_negative() ? -1 : 1;
      if (sign != 0 && s != sign) {
        everywhere = false;
        break;
      }
      sign = s;
      if (first || (s > 0 ? it->second < lo : it->second > lo)) lo = it->second;
      first = false;
    }
    if (everywhere && !lo.is_zero()) common.push_back({base, lo});
  }
  out.coef = content;
  for (const auto& [base, e] : common) out.factors.push_back(GiNaC::pow(base, e));
  if (monomials.size() > 1) {
    Sum inner;
    for (const Monomial& m : monomials) {
      Term t;
      t.coef = m.coef / content;
      for (const auto& [base, e] : m.powers) {
        numeric rest = e;
        for (const auto& [cb, ce] : common) {
          if (cb.is_equal(base)) rest = e - ce;
        }
        if (!rest.is_zero()) t.factors.push_back(GiNaC::pow(base, rest));
      }
      inner.terms.push_back(std::move(t));
    }
    sort_sum(inner, order);
    out.sums.push_back(std::move(inner));
  } else {
    out.coef = monomials.front().coef;
  }
  for (const ex& f : factors_of(dynamic)) {
    if (!f.is_equal(1)) out.factors.push_back(f);
  }
  return out;
}

}  // namespace

std::string number_text(const numeric& x, bool latex) {
  // small integers without CLN's stream output (the common case, and the costly one)
  if (x.is_integer() && GiNaC::abs(x) < numeric(1000000000L)) return std::to_string(x.to_long());
  std::ostringstream os;
  if (x.is_integer()) {
    os << x;
    return os.str();
  }
  if (x.is_rational()) {
    const numeric p = x.numer(), q = x.denom();
    std::ostringstream ps, qs;
    ps << abs_numeric(p);
    qs << q;
    const std::string sign = p.is_negative() ? "-" : "";
    const std::string fraction = ps.str() + "/" + qs.str();
    // a terminating decimal: q = 2^a 5^b, digits = p·10^k/q with k = max(a, b). Looked for
    // while q has at most 64 digits: the decimal would have at least as many, and the search
    // divides q once per factor (a 0.07…^2000 of the fuzzer has 36,000 of them: seconds)
    constexpr std::size_t kMaxDecimalDigits = 64;
    numeric r = q;
    int twos = 0, fives = 0;
    if (qs.str().size() <= kMaxDecimalDigits) {
      while (GiNaC::mod(r, 2).is_zero()) { r = r / 2; ++twos; }
      while (GiNaC::mod(r, 5).is_zero()) { r = r / 5; ++fives; }
    }
    if (r.is_equal(1)) {
      const int k = std::max(twos, fives);
      std::ostringstream ds;
      ds << abs_numeric(p) * numeric(10).power(numeric(k)) / q;
      std::string digits = ds.str();
      if (static_cast<int>(digits.size()) <= k) digits.insert(0, static_cast<std::size_t>(k) + 1 - digits.size(), '0');
      const std::string decimal = digits.substr(0, digits.size() - static_cast<std::size_t>(k)) + "." +
                                  digits.substr(digits.size() - static_cast<std::size_t>(k));
      if (decimal.size() < fraction.size()) return sign + decimal;
    }
    if (fraction.size() <= 21) {
      return latex ? sign + "\\frac{" + ps.str() + "}{" + qs.str() + "}" : sign + fraction;
    }
  }
  return fmt::format("{}", x.to_double());
}

Sum plain(const ex& e, const SymbolOrder& order) {
  Sum s;
  for (const ex& t : operands(e)) s.terms.push_back(term_of(t, order));
  sort_sum(s, order);
  return s;
}

Sum textbook(const ex& e, const SymbolOrder& order) {
  exvector terms = operands(simplify(e));
  sum_to_product(terms, order);
  const ex sum = GiNaC::add(terms);
  ex x = fewer_terms(sum.expand(), order);
  terms = operands(x);
  // collect per dynamic part; the groups, their monomials and factors are sorted when printed,
  // so the order of `terms` (GiNaC's) does not reach the output
  std::vector<std::pair<ex, std::vector<Monomial>>> groups;
  for (const ex& term : terms) {
    Monomial m{numeric(1), {}};
    ex dynamic = 1;
    for (const ex& f : factors_of(term)) {
      if (is_a<numeric>(f)) {
        m.coef *= GiNaC::ex_to<numeric>(f);
      } else if (order.has_dynamic(f)) {
        dynamic *= f;
      } else if (is_a<GiNaC::power>(f) && is_a<numeric>(f.op(1))) {
        m.powers.push_back({f.op(0), GiNaC::ex_to<numeric>(f.op(1))});
      } else {
        m.powers.push_back({f, numeric(1)});
      }
    }
    auto it = std::find_if(groups.begin(), groups.end(), [&](const auto& g) { return g.first.is_equal(dynamic); });
    if (it == groups.end()) {
      groups.push_back({dynamic, {std::move(m)}});
    } else {
      it->second.push_back(std::move(m));
    }
  }
  Sum s;
  for (const auto& [dynamic, monomials] : groups) s.terms.push_back(factor_group(monomials, dynamic, order));
  sort_sum(s, order);
  return s;
}

Sum collected(const std::vector<ex>& coefficients, const std::vector<ex>& atoms, const SymbolOrder& order) {
  Sum s;
  s.keep_order = true;
  for (std::size_t j = 0; j < coefficients.size(); ++j) {
    Sum c = textbook(coefficients[j], order);
    if (c.terms.empty()) continue;
    Term t;
    if (c.terms.size() == 1) {
      t = std::move(c.terms.front());
    } else {
      t.sums.push_back(std::move(c));
    }
    t.factors.push_back(atoms[j]);
    s.terms.push_back(std::move(t));
  }
  return s;
}

std::string print(const Sum& s, const SymbolOrder& order, bool latex) {
  if (s.terms.empty()) return "0";
  std::string out;
  for (std::size_t i = 0; i < s.terms.size(); ++i) {
    bool negative = false;
    const std::string body = print_term(s.terms[i], order, latex, negative);
    if (i == 0) {
      out = (negative ? "-" : "") + body;
    } else {
      out += (negative ? " - " : " + ") + body;
    }
  }
  return out;
}

ex to_ex(const Sum& s) {
  ex out = 0;
  for (const Term& t : s.terms) {
    ex term = t.coef;
    for (const Sum& u : t.sums) term *= to_ex(u);
    for (const ex& f : t.factors) term *= f;
    out += term;
  }
  return out;
}

}  // namespace rigid::lagrange::detail
