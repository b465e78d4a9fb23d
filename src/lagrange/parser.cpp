#include "detail/parser.hpp"
#include "detail/symbolic.hpp"
#include "detail/symbolic_lock.hpp"
#include "rigid/common/number_literal.hpp"
#include "rigid/lagrange/expression_names.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <new>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <vector>

#include <cln/exception.h>
#include <cln/float.h>
#include <fmt/format.h>

namespace rigid::lagrange::detail {

void throw_at(const Expression& expression, std::size_t offset, std::string_view context,
              const std::string& reason) {
  if (!expression.where.file.empty() || expression.where.line > 0) {
    SourceLocation at = expression.where;
    if (at.column > 0) {
      // a text of several lines (a scene's multi-line string): lines counted from `where`
      const std::string_view before = std::string_view(expression.text).substr(0, offset);
      const std::size_t newline = before.rfind('\n');
      if (newline == std::string_view::npos) {
        at.column += static_cast<int>(offset);
      } else {
        at.line += static_cast<int>(std::count(before.begin(), before.end(), '\n'));
        at.column = static_cast<int>(offset - newline);
      }
    }
    rigid::detail::throw_error_at(at, fmt::format("{}: {}", context, reason));
  }
  throw Error(fmt::format("{}: {} at column {} of \"{}\"", context, reason, offset + 1,
                          expression.text));
}

std::string reason_of_library_failure(const std::exception& e) {
  if (dynamic_cast<const GiNaC::pole_error*>(&e) != nullptr || dynamic_cast<const cln::division_by_0_exception*>(&e) != nullptr) {
    return "has a pole here (a division by zero, log(0), tan(pi/2), 0 to a negative power); "
           "expected a finite value";
  }
  if (dynamic_cast<const cln::floating_point_underflow_exception*>(&e) != nullptr) {
    return "underflows: a value is closer to 0 than the smallest positive double (about 1e-308)";
  }
  if (dynamic_cast<const cln::floating_point_overflow_exception*>(&e) != nullptr) {
    return "overflows: a value is larger than the largest double (about 1.8e308)";
  }
  if (dynamic_cast<const std::bad_alloc*>(&e) != nullptr) {
    return "needs more memory than is available to evaluate";
  }
  if (dynamic_cast<const std::domain_error*>(&e) != nullptr) {
    return "is undefined here (outside the domain of a function, or 0^0)";
  }
  if (dynamic_cast<const cln::runtime_exception*>(&e) != nullptr) {
    return "holds a number too large for exact arithmetic (such as an exact power whose exponent "
           "is beyond 2^31)";
  }
  return "cannot be evaluated to a number";
}

namespace {

// log10 |x| of a non-zero real number, also beyond the range of a double (a rational such as
// 10^400 has no double value; its digits are counted instead)
double log10_abs(const GiNaC::numeric& x) {
  const double v = std::abs(x.to_double());
  if (v > 0 && std::isfinite(v)) return std::log10(v);
  if (!x.is_rational()) return v > 0 ? 400.0 : -400.0;
  return (static_cast<double>(x.numer().int_length()) - static_cast<double>(x.denom().int_length())) *
         std::log10(2.0);
}

// A number as an error message shows it: exactly when short, to 6 significant digits when
// long; as an operand of ^, a fraction or a negative number in parentheses.
std::string text_of(const GiNaC::numeric& x, bool operand = false) {
  std::ostringstream out;
  out << GiNaC::ex(x);
  std::string text = out.str();
  if (text.size() > 24) text = fmt::format("{:.6g}", x.to_double());
  if (operand && text.find_first_of("/-") != std::string::npos) text = "(" + text + ")";
  return text;
}

// recursive descent over
//   sum     = product { ("+" | "-") product }
//   product = unary { ("*" | "/") unary }
//   unary   = ("-" | "+") unary | power
//   power   = primary [ ("^" | "**") unary ]
//   primary = number | name | name "(" sum ")" | "(" sum ")"
class Parser {
 public:
  Parser(const Expression& e, const std::map<std::string, GiNaC::ex>& names,
         std::string_view context)
      : e_(e), s_(e.text), names_(names), context_(context) {}

  GiNaC::ex parse() {
    if (s_.size() > kMaxExpressionLength) {
      fail(0, fmt::format("the expression is {} characters long, more than the {} an expression "
                          "may have; split it into parameters",
                          s_.size(), kMaxExpressionLength));
    }
    skip();
    if (pos_ >= s_.size()) fail(pos_, "empty expression; expected a number, a name or '('");
    GiNaC::ex value = sum();
    skip();
    if (pos_ < s_.size()) {
      fail(pos_, fmt::format("unexpected '{}'; expected an operator or the end", s_[pos_]));
    }
    return value;
  }

 private:
  [[noreturn]] void fail(std::size_t at, const std::string& reason) const {
    throw_at(e_, at, context_, reason);
  }
  // One level of nesting (parentheses, a function's argument, a sign, an exponent) for the
  // lifetime of the guard; the recursion (and GiNaC's own, on the tree it builds) stays far
  // from the end of the stack.
  class Nest {
   public:
    Nest(Parser& p, std::size_t at) : p_(p) {
      if (++p_.depth_ > kMaxExpressionDepth) {
        p_.fail(at, fmt::format("the expression nests deeper than {} levels (parentheses, "
                                "function arguments, signs and exponents); simplify it or "
                                "split it into parameters",
                                kMaxExpressionDepth));
      }
    }
    ~Nest() { --p_.depth_; }
    Nest(const Nest&) = delete;
    Nest& operator=(const Nest&) = delete;

   private:
    Parser& p_;
  };
  void skip() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  bool accept(char c) {
    skip();
    if (pos_ < s_.size() && s_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  // Terms and factors are collected and handed to GiNaC once: adding them one by one
  // would copy the growing sum each time (quadratic in the number of terms).
  GiNaC::ex sum() {
    GiNaC::exvector terms{product()};
    for (;;) {
      if (accept('+')) {
        terms.push_back(product());
      } else if (accept('-')) {
        terms.push_back(-product());
      } else {
        return terms.size() == 1 ? terms.front() : GiNaC::ex(GiNaC::add(terms));
      }
    }
  }
  GiNaC::ex product() {
    GiNaC::exvector factors{unary()};
    auto done = [&] { return factors.size() == 1 ? factors.front() : GiNaC::ex(GiNaC::mul(factors)); };
    for (;;) {
      skip();
      if (pos_ + 1 < s_.size() && s_[pos_] == '*' && s_[pos_ + 1] == '*') return done();
      if (accept('*')) {
        factors.push_back(unary());
      } else if (accept('/')) {
        const std::size_t at = pos_;
        GiNaC::ex d = unary();
        if (d.is_zero()) fail(at, "division by zero");
        factors.push_back(guarded(at, [&] { return GiNaC::pow(d, -1); }));
      } else {
        return done();
      }
    }
  }
  GiNaC::ex unary() {
    skip();
    const std::size_t at = pos_;
    if (accept('-')) {
      const Nest nest(*this, at);
      return -unary();
    }
    if (accept('+')) {
      const Nest nest(*this, at);
      return unary();
    }
    return power();
  }
  GiNaC::ex power() {
    GiNaC::ex base = primary();
    skip();
    const std::size_t at = pos_;
    if (accept('^')) {
    } else if (pos_ + 1 < s_.size() && s_[pos_] == '*' && s_[pos_ + 1] == '*') {
      pos_ += 2;
    } else {
      return base;
    }
    const Nest nest(*this, at);
    const GiNaC::ex exponent = unary();
    return raise(base, exponent, at);
  }
  // base^exponent. GiNaC evaluates a power of two numbers at once, exactly for rationals:
  // 9^9^9 would be an integer of 370 million digits (minutes and gigabytes). So the size of
  // the result is estimated first: a magnitude beyond 10^±kMaxPowerDigits is refused (no finite
  // double comes out of it), and an exact result longer than kMaxExactPowerBits is computed in
  // floating point instead (GiNaC's Digits, at least 17 significant digits).
  // An irrational power of numbers other than a square root (2^(1/3), 77777^0.1787) is also
  // computed in floating point here: GiNaC keeps it unevaluated and, each time a product
  // holding it is rebuilt (every derivative, expansion and printing step), tries the exact
  // result again through CLN's exp and log at 17 digits; one such number in a sum to the 8th
  // took seconds to derive and print. A square root stays exact (CLN's exact square-root test
  // is cheap), as does a root with a rational value (8^(1/3) = 2).
  GiNaC::ex raise(const GiNaC::ex& base, const GiNaC::ex& exponent, std::size_t at) const {
    if (GiNaC::is_a<GiNaC::numeric>(base) && GiNaC::is_a<GiNaC::numeric>(exponent)) {
      const auto& b = GiNaC::ex_to<GiNaC::numeric>(base);
      const auto& e = GiNaC::ex_to<GiNaC::numeric>(exponent);
      if (b.is_zero()) {
        if (e.is_zero()) fail(at, "0^0 is undefined; expected a base or an exponent other than 0");
        if (!e.is_real() || !e.is_positive()) fail(at, "0 to a negative power is a division by zero");
        return 0;
      }
      if (b.is_real() && b.is_negative() && e.is_real() && !e.is_integer()) {
        // GiNaC's principal value is complex ((-8)^(1/3) = 1 + 1.732i), and a double NaN
        fail(at, fmt::format("{}^{} is not real: a negative number to a non-integer power; "
                             "expected a positive base or an integer exponent",
                             text_of(b, true), text_of(e, true)));
      }
      if (b.is_real() && e.is_real() && !e.is_zero()) {
        // the result is about 10^(e·log10|b|): compared through logarithms, so nothing overflows
        const double lb = log10_abs(b);
        const double digits = std::log10(std::abs(lb)) + log10_abs(e);
        if (lb != 0 && digits > std::log10(kMaxPowerDigits)) {
          const bool large = (lb > 0) == e.is_positive();
          fail(at, fmt::format("the power is about 10^{}{:.4g}, far beyond any finite double (a "
                               "power may reach 10^±{}); check the exponent",
                               large ? "" : "-", std::pow(10.0, digits), kMaxPowerDigits));
        }
        if (b.is_rational() && e.is_rational() && lb != 0) {
          const double bits = (static_cast<double>(b.numer().int_length()) +
                               static_cast<double>(b.denom().int_length())) *
                              std::abs(e.to_double());
          if (!(bits <= kMaxExactPowerBits)) {
            return guarded(at, [&] { return GiNaC::pow(b.evalf(), e); });
          }
          if (!e.is_integer() && e.denom() != 2) {
            const GiNaC::ex exact = guarded(at, [&] { return GiNaC::pow(base, exponent); });
            if (GiNaC::is_a<GiNaC::numeric>(exact)) return exact;
            return guarded(at, [&] { return GiNaC::pow(b.evalf(), e); });
          }
        }
      }
    }
    return guarded(at, [&] { return GiNaC::pow(base, exponent); });
  }
  // Runs a GiNaC construction that may evaluate (a pole, an overflow) and reports its failure
  // at `at`.
  template <typename F>
  GiNaC::ex guarded(std::size_t at, F&& f) const {
    try {
      return f();
    } catch (const Error&) {
      throw;  // the parser's own refusal (an unknown function), already located
    } catch (const std::exception& e) {
      fail(at, "the expression " + reason_of_library_failure(e));
    }
  }
  GiNaC::ex number() {
    // digits [. digits] [e|E [+-] digits] as an exact rational
    const std::size_t start = pos_;
    std::string digits;
    long scale = 0;
    while (pos_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[pos_]))) {
      digits += s_[pos_++];
    }
    if (pos_ < s_.size() && s_[pos_] == '.') {
      ++pos_;
      while (pos_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[pos_]))) {
        digits += s_[pos_++];
        --scale;
      }
    }
    if (digits.empty()) fail(start, "malformed number");
    if (pos_ < s_.size() && (s_[pos_] == 'e' || s_[pos_] == 'E')) {
      std::size_t p = pos_ + 1;
      bool negative = false;
      if (p < s_.size() && (s_[p] == '+' || s_[p] == '-')) negative = s_[p++] == '-';
      if (p >= s_.size() || !std::isdigit(static_cast<unsigned char>(s_[p]))) {
        fail(pos_, "malformed exponent of a number; expected digits after 'e'");
      }
      long exponent = 0;
      while (p < s_.size() && std::isdigit(static_cast<unsigned char>(s_[p]))) {
        exponent = std::min(10 * exponent + (s_[p++] - '0'), 100000L);
      }
      scale += negative ? -exponent : exponent;
      pos_ = p;
    }
    // a literal is exact here, but every value leaves as a double: one that no double holds
    // (1e-400 would become 0, 1e-310 a subnormal, 1e400 infinity) is refused as written
    if (auto problem = literal_range_problem(std::string_view(s_).substr(start, pos_ - start))) {
      fail(start, *problem);
    }
    if (std::abs(scale) > 400) fail(start, "number out of range");
    const GiNaC::numeric mantissa(digits.c_str());
    return mantissa * GiNaC::numeric(10).power(GiNaC::numeric(scale));
  }
  GiNaC::ex primary() {
    skip();
    if (pos_ >= s_.size()) fail(pos_, "unexpected end; expected a number, a name or '('");
    const char c = s_[pos_];
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return number();
    if (c == '(') {
      const std::size_t open = pos_++;
      const Nest nest(*this, open);
      GiNaC::ex v = sum();
      if (!accept(')')) fail(pos_ < s_.size() ? pos_ : open, "missing ')' closing the '(' here");
      return v;
    }
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      const std::size_t start = pos_;
      while (pos_ < s_.size() &&
             (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '_')) {
        ++pos_;
      }
      const std::string name = s_.substr(start, pos_ - start);
      skip();
      if (pos_ < s_.size() && s_[pos_] == '(') {
        const Nest nest(*this, pos_);
        ++pos_;
        const GiNaC::ex arg = sum();
        if (!accept(')')) fail(pos_, fmt::format("missing ')' after the argument of {}", name));
        return guarded(start, [&] { return apply(name, arg, start); });
      }
      if (name == "pi") return GiNaC::Pi;
      auto it = names_.find(name);
      if (it == names_.end()) {
        std::string known;
        for (const auto& [n, _] : names_) known += n + ", ";
        fail(start, fmt::format("undefined symbol '{}'; known names: {}pi", name, known));
      }
      return it->second;
    }
    fail(pos_, fmt::format("unexpected '{}'; expected a number, a name or '('", c));
  }
  GiNaC::ex apply(const std::string& f, const GiNaC::ex& x, std::size_t at) const {
    if (f == "sin") return GiNaC::sin(x);
    if (f == "cos") return GiNaC::cos(x);
    if (f == "tan") return GiNaC::tan(x);
    if (f == "asin" || f == "acos") {
      // of a number outside [-1, 1] it is complex: refused here rather than as a NaN at run time
      if (GiNaC::is_a<GiNaC::numeric>(x) && GiNaC::ex_to<GiNaC::numeric>(x).is_real() &&
          abs(GiNaC::ex_to<GiNaC::numeric>(x)) > 1) {
        fail(at, fmt::format("{}({}) is not real; expected an argument in [-1, 1]", f,
                             text_of(GiNaC::ex_to<GiNaC::numeric>(x))));
      }
      return f == "asin" ? GiNaC::asin(x) : GiNaC::acos(x);
    }
    if (f == "atan") return GiNaC::atan(x);
    if (f == "exp") return GiNaC::exp(x);
    if (f == "log") return GiNaC::log(x);
    if (f == "sqrt") {
      if (GiNaC::is_a<GiNaC::numeric>(x) && GiNaC::ex_to<GiNaC::numeric>(x).is_real() &&
          GiNaC::ex_to<GiNaC::numeric>(x).is_negative()) {
        fail(at, fmt::format("sqrt({}) is not real; expected a non-negative argument",
                             text_of(GiNaC::ex_to<GiNaC::numeric>(x))));
      }
      return raise(x, GiNaC::numeric(1, 2), at);
    }
    if (f == "abs") return GiNaC::abs(x);
    if (f == "sinh") return GiNaC::sinh(x);
    if (f == "cosh") return GiNaC::cosh(x);
    if (f == "tanh") return GiNaC::tanh(x);
    fail(at, fmt::format("unknown function '{}'; expected one of sin cos tan asin acos atan exp "
                         "log sqrt abs sinh cosh tanh", f));
  }

  const Expression& e_;
  const std::string& s_;
  const std::map<std::string, GiNaC::ex>& names_;
  std::string_view context_;
  std::size_t pos_ = 0;
  std::size_t depth_ = 0;
};

}  // namespace

namespace {

// What expand() makes of an expression, estimated from the parsed expression before anything is
// expanded, as log10 of counts: `result`, its number of terms; `worst`, the largest count that
// multiplying out creates among its parts (a product of two or more sums, a sum to a power;
// expand works from the leaves up; a sum as written is not counted: its terms are the text's
// own); `size`, its number of nodes written as a tree (what the derivation, the printer and the
// tape builder walk), and `worst_size`, the largest size that multiplying out creates. Upper
// estimates: no cancellation is assumed, a sum of t terms to the n is counted as
// C(n + t − 1, n) terms, each a product of min(n, t) powers of the base's terms of average size.
struct ExpandedTerms {
  double result = 0;
  double worst = 0;
  double size = 0;
  double worst_size = 0;
};

// log10(10^x + 10^y), without overflow
double log_sum(double x, double y) {
  const double top = std::max(x, y);
  return top + std::log10(std::pow(10.0, x - top) + std::pow(10.0, y - top));
}

using ExpandedMemo = std::map<GiNaC::ex, ExpandedTerms, GiNaC::ex_is_less>;

// Memoized on the expression's graph: a subexpression GiNaC shares (a power whose exponent is a
// sum used in many places) is estimated once, whatever its number of uses.
ExpandedTerms expanded_terms(const GiNaC::ex& e, ExpandedMemo& memo) {
  if (const auto found = memo.find(e); found != memo.end()) return found->second;
  ExpandedTerms out;
  auto part = [&](const ExpandedTerms& t) {
    out.worst = std::max(out.worst, t.worst);
    out.worst_size = std::max(out.worst_size, t.worst_size);
  };
  if (GiNaC::is_a<GiNaC::add>(e)) {
    bool first = true;
    for (const GiNaC::ex& op : e) {
      const ExpandedTerms t = expanded_terms(op, memo);
      part(t);
      out.result = first ? t.result : log_sum(out.result, t.result);
      out.size = first ? t.size : log_sum(out.size, t.size);
      first = false;
    }
  } else if (GiNaC::is_a<GiNaC::mul>(e)) {
    int sums = 0;
    double term_size = 0;  // log10 of a product term's size: Σ of each factor's average term
    double written = 0;    // log10 of the factors' own sizes, side by side
    bool first = true;
    for (const GiNaC::ex& op : e) {
      const ExpandedTerms t = expanded_terms(op, memo);
      part(t);
      out.result += t.result;
      term_size = first ? t.size - t.result : log_sum(term_size, t.size - t.result);
      written = first ? t.size : log_sum(written, t.size);
      first = false;
      if (t.result > 0) ++sums;
    }
    out.size = out.result + term_size;
    if (sums >= 2) {
      out.worst = std::max(out.worst, out.result);
      out.worst_size = std::max(out.worst_size, out.size);
    } else if (sums == 1 && out.size > written + 1) {
      // one sum times a long product: each term holds the product (a derivative's chain rule
      // makes these); counted where it multiplies the written size by ten or more, so that a
      // long sum times a short factor still counts as written
      out.worst_size = std::max(out.worst_size, out.size);
    }
  } else if (GiNaC::is_a<GiNaC::power>(e)) {
    const ExpandedTerms base = expanded_terms(e.op(0), memo);
    const ExpandedTerms exponent = expanded_terms(e.op(1), memo);
    part(base);
    part(exponent);
    const GiNaC::ex& p = e.op(1);
    out.size = log_sum(base.size, exponent.size);
    if (base.result > 0 && GiNaC::is_a<GiNaC::numeric>(p) && GiNaC::ex_to<GiNaC::numeric>(p).is_pos_integer()) {
      // C(N, k) with N = n + t − 1 and k = min(n, t − 1) ≤ N/2: a product of k ratios while k
      // is small (a difference of lgamma values would cancel to 0 for n = 2^708), else at
      // least 2^k, already far beyond the limit
      const double n = GiNaC::ex_to<GiNaC::numeric>(p).to_double();
      const double t = std::round(std::pow(10.0, std::min(base.result, 300.0)));
      const double N = n + t - 1, k = std::min(n, t - 1);
      if (k > 64) {
        out.result = k * std::log10(2.0);
      } else {
        for (double i = 1; i <= k; ++i) out.result += std::log10((N - k + i) / i);
      }
      out.size = out.result + std::log10(std::min(n, t)) + (base.size - base.result);
      out.worst = std::max(out.worst, out.result);
      out.worst_size = std::max(out.worst_size, out.size);
    } else if (exponent.result > 0 && !GiNaC::is_a<GiNaC::numeric>(p)) {
      // b^(x + y + …) = b^x · b^y · …: a product of as many powers as the exponent has terms,
      // each holding the base
      out.size = exponent.result + log_sum(base.size, exponent.size - exponent.result);
      out.worst_size = std::max(out.worst_size, out.size);
    }
  } else {
    for (const GiNaC::ex& op : e) {
      const ExpandedTerms t = expanded_terms(op, memo);
      part(t);
      out.size = log_sum(out.size, t.size);
    }
  }
  memo.emplace(e, out);
  return out;
}

}  // namespace

double expanded_size_log10(const GiNaC::ex& e) {
  ExpandedMemo memo;
  const ExpandedTerms expanded = expanded_terms(e, memo);
  return std::max(expanded.worst_size, expanded.size);
}

GiNaC::ex parse_expression(const Expression& expression,
                           const std::map<std::string, GiNaC::ex>& names,
                           std::string_view context) {
  const GiNaC::ex value = Parser(expression, names, context).parse();
  ExpandedMemo memo;
  const ExpandedTerms expanded = expanded_terms(value, memo);
  if (const double terms = expanded.worst; !(terms <= std::log10(kMaxExpandedTerms))) {
    throw_at(expression, 0, context,
             fmt::format("the expression multiplies out to about 10^{:.3g} terms (products and "
                         "integer powers of sums); at most {:.0f} are allowed, since the equations of motion are "
                         "derived from the expanded expression",
                         terms, kMaxExpandedTerms));
  }
  if (const double nodes = expanded.worst_size; !(nodes <= std::log10(kMaxExpandedNodes))) {
    throw_at(expression, 0, context,
             fmt::format("the expression multiplies out to about 10^{:.3g} symbols and operations "
                         "(products and integer powers of sums whose terms are long); at most {:.0f} "
                         "are allowed, since the equations of motion are derived from the expanded "
                         "expression",
                         nodes, kMaxExpandedNodes));
  }
  // a complex number inside (sqrt(-1) is I) has no place in the real model
  for (auto it = value.preorder_begin(); it != value.preorder_end(); ++it) {
    if (GiNaC::is_a<GiNaC::numeric>(*it) && !GiNaC::ex_to<GiNaC::numeric>(*it).is_real()) {
      std::ostringstream text;
      text << *it;
      throw_at(expression, 0, context,
               fmt::format("'{}' holds the complex number {}; expected a real expression", expression.text,
                           text.str()));
    }
  }
  return value;
}

}  // namespace rigid::lagrange::detail

namespace rigid::lagrange {

namespace {

// The value of an expression that is a parameter's name alone or negated (`L`, ` -g `), without
// a parse and without the symbolic core: what a sweep's run evaluates most, lock-free. GiNaC
// gives the same double: a parameter enters it as the floating-point number it holds, and
// negating a double is exact (zeros and subnormals are left to GiNaC: the sign of a zero, the
// underflow CLN reports). The last parameter of a name is the one a parse sees. Anything else
// (an unknown name, a non-finite value, any other expression) returns nothing and takes the
// general path, with its messages.
std::optional<double> value_of_name(std::string_view text, const std::vector<Parameter>& parameters) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return std::nullopt;
  const auto last = text.find_last_not_of(" \t");
  text = text.substr(first, last - first + 1);
  const bool negated = text.front() == '-';
  if (negated) text.remove_prefix(1);
  const std::string name(text);
  if (!detail::is_identifier(name) || detail::reserved_names().count(name) > 0) {
    return std::nullopt;  // not a name, or pi, sin, …
  }
  for (auto p = parameters.rbegin(); p != parameters.rend(); ++p) {
    if (p->name != name) continue;
    if (!std::isnormal(p->value)) return std::nullopt;  // 0, subnormal, inf, NaN: GiNaC's way
    return negated ? -p->value : p->value;
  }
  return std::nullopt;
}

}  // namespace

std::vector<std::string> names_in(std::string_view text) {
  auto digit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
  auto word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; };
  std::vector<std::string> out;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (digit(c) || c == '.') {
      // a number as Parser::number reads it: digits [. digits] [e|E [+-] digits]
      while (i < text.size() && (digit(text[i]) || text[i] == '.')) ++i;
      if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
        std::size_t p = i + 1;
        if (p < text.size() && (text[p] == '+' || text[p] == '-')) ++p;
        if (p < text.size() && digit(text[p])) {
          while (p < text.size() && digit(text[p])) ++p;
          i = p;
        }
      }
    } else if (std::isalpha(static_cast<unsigned char>(c)) != 0 || c == '_') {
      const std::size_t start = i;
      while (i < text.size() && word(text[i])) ++i;
      out.emplace_back(text.substr(start, i - start));
    } else {
      ++i;
    }
  }
  return out;
}

double evaluate_constant(const Expression& expression, const std::vector<Parameter>& parameters,
                         std::string_view context) {
  if (const auto v = value_of_name(expression.text, parameters)) return *v;
  detail::SymbolicLock lock;
  if (expression.text.find_first_not_of(" \t") == std::string::npos) {
    detail::throw_at(expression, 0, context, "empty expression; expected a number, a name or '('");
  }
  std::map<std::string, GiNaC::ex> names;
  for (const Parameter& p : parameters) {
    try {
      names[p.name] = GiNaC::numeric(p.value);
    } catch (const std::exception& e) {  // inf, NaN or a subnormal: outside CLN's double-floats
      detail::throw_at(expression, 0, context,
                       fmt::format("parameter '{}' = {:.17g} {}", p.name, p.value, detail::reason_of_library_failure(e)));
    }
  }
  const GiNaC::ex parsed = detail::parse_expression(expression, names, context);
  GiNaC::ex value;
  try {
    value = parsed.evalf();
  } catch (const std::exception& e) {
    detail::throw_at(expression, 0, context,
                     fmt::format("'{}' {}", expression.text, detail::reason_of_library_failure(e)));
  }
  if (GiNaC::is_a<GiNaC::numeric>(value)) {
    const auto& n = GiNaC::ex_to<GiNaC::numeric>(value);
    if (n.is_real()) {
      const double v = n.to_double();
      // a non-zero value closer to 0 than the smallest normal double (1e-300/1e10, exp(-1000))
      // would be used as 0 or a subnormal: refused, as its literal would be
      if (!n.is_zero() && !(std::abs(v) >= kSmallestLiteral) && std::isfinite(v)) {
        std::ostringstream exact;
        exact << value;
        detail::throw_at(expression, 0, context,
                         fmt::format("'{}' evaluates to {}, which underflows: a double would hold "
                                     "{:.17g}; expected 0 or a magnitude from {:.17g} to {:.17g}",
                                     expression.text, exact.str(), v, kSmallestLiteral,
                                     kLargestLiteral));
      }
      if (std::isfinite(v)) return v;
    }
  }
  std::ostringstream text;
  text << value;
  detail::throw_at(expression, 0, context,
                   fmt::format("'{}' evaluates to {}; expected a finite real number",
                               expression.text, text.str()));
}

}  // namespace rigid::lagrange
