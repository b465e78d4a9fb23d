#include "detail/parser.hpp"

#include <cctype>
#include <cmath>
#include <sstream>
#include <vector>

#include <fmt/format.h>

namespace rigid::lagrange::detail {

void throw_at(const Expression& expression, std::size_t offset, std::string_view context,
              const std::string& reason) {
  if (!expression.where.file.empty() || expression.where.line > 0) {
    SourceLocation at = expression.where;
    if (at.column > 0) at.column += static_cast<int>(offset);
    rigid::detail::throw_error_at(at, fmt::format("{}: {}", context, reason));
  }
  throw Error(fmt::format("{}: {} at column {} of \"{}\"", context, reason, offset + 1,
                          expression.text));
}

namespace {

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
  GiNaC::ex sum() {
    GiNaC::ex v = product();
    for (;;) {
      if (accept('+')) {
        v += product();
      } else if (accept('-')) {
        v -= product();
      } else {
        return v;
      }
    }
  }
  GiNaC::ex product() {
    GiNaC::ex v = unary();
    for (;;) {
      skip();
      if (pos_ + 1 < s_.size() && s_[pos_] == '*' && s_[pos_ + 1] == '*') return v;
      if (accept('*')) {
        v *= unary();
      } else if (accept('/')) {
        const std::size_t at = pos_;
        GiNaC::ex d = unary();
        if (d.is_zero()) fail(at, "division by zero");
        v /= d;
      } else {
        return v;
      }
    }
  }
  GiNaC::ex unary() {
    if (accept('-')) return -unary();
    if (accept('+')) return unary();
    return power();
  }
  GiNaC::ex power() {
    GiNaC::ex base = primary();
    skip();
    if (accept('^')) return GiNaC::pow(base, unary());
    if (pos_ + 1 < s_.size() && s_[pos_] == '*' && s_[pos_ + 1] == '*') {
      pos_ += 2;
      return GiNaC::pow(base, unary());
    }
    return base;
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
        ++pos_;
        const GiNaC::ex arg = sum();
        if (!accept(')')) fail(pos_, fmt::format("missing ')' after the argument of {}", name));
        return apply(name, arg, start);
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
    if (f == "asin") return GiNaC::asin(x);
    if (f == "acos") return GiNaC::acos(x);
    if (f == "atan") return GiNaC::atan(x);
    if (f == "exp") return GiNaC::exp(x);
    if (f == "log") return GiNaC::log(x);
    if (f == "sqrt") return GiNaC::sqrt(x);
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
};

}  // namespace

GiNaC::ex parse_expression(const Expression& expression,
                           const std::map<std::string, GiNaC::ex>& names,
                           std::string_view context) {
  return Parser(expression, names, context).parse();
}

}  // namespace rigid::lagrange::detail

namespace rigid::lagrange {

double evaluate_constant(const Expression& expression, const std::vector<Parameter>& parameters,
                         std::string_view context) {
  if (expression.text.find_first_not_of(" \t") == std::string::npos) {
    detail::throw_at(expression, 0, context, "empty expression; expected a number, a name or '('");
  }
  std::map<std::string, GiNaC::ex> names;
  for (const Parameter& p : parameters) names[p.name] = GiNaC::numeric(p.value);
  const GiNaC::ex value = detail::parse_expression(expression, names, context).evalf();
  if (GiNaC::is_a<GiNaC::numeric>(value)) {
    const auto& n = GiNaC::ex_to<GiNaC::numeric>(value);
    if (n.is_real()) {
      const double v = n.to_double();
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
