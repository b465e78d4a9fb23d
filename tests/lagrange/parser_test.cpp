// The expression parser at its limits: nesting, length, powers of numbers, and the failures of
// GiNaC/CLN, each refused with its position and without the library's own text.
#include <chrono>
#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/tolerance.hpp"

#include "rigid/lagrange/expression_names.hpp"
#include "rigid/lagrange/symbolic_core.hpp"
#include "rigid/lagrange/system.hpp"
#include "support/expect_error.hpp"

namespace rigid::lagrange {
namespace {

using Clock = std::chrono::steady_clock;

double eval(const std::string& text, const std::vector<Parameter>& params = {}) {
  return evaluate_constant(Expression(text, {"e.toml", 3, 10}), params, "value");
}

std::string error_of(const std::string& text, const std::vector<Parameter>& params = {}) {
  try {
    (void)eval(text, params);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

// Library texts that must never reach a user.
void expect_no_raw_text(const std::string& message) {
  for (const char* raw : {"log_eval", "floating point", "bad_alloc", "bad optional", "power::eval",
                          "domain_error", "(): "}) {
    EXPECT_EQ(message.find(raw), std::string::npos) << raw << " in: " << message;
  }
}

// 20,000 nested parentheses crashed the recursive descent (stack overflow, also in Python);
// they are refused at the parenthesis that goes one level too deep.
TEST(Parser, DeepNestingIsRefusedAtItsPosition) {
  const std::size_t n = 20'000;
  const std::string deep = std::string(n, '(') + "1" + std::string(n, ')');
  const std::string msg = error_of(deep);
  // file:line:col with col = 10 + 200 (the 201st '(' is at offset 200)
  EXPECT_NE(msg.find("e.toml:3:210: value: the expression nests deeper than 200 levels"), std::string::npos) << msg;
  // signs, function arguments and exponents count as well
  EXPECT_NE(error_of(std::string(n, '-') + "1").find("nests deeper than 200"), std::string::npos);
  std::string calls;
  for (std::size_t i = 0; i < n; ++i) calls += "sin(";
  EXPECT_NE(error_of(calls + "1" + std::string(n, ')')).find("nests deeper than 200"), std::string::npos);
  std::string tower = "1";
  for (std::size_t i = 0; i < n; ++i) tower += "^1";
  EXPECT_NE(error_of(tower).find("nests deeper than 200"), std::string::npos);
  // 200 levels are fine: ((…(2)…)) is 2
  EXPECT_EQ(eval(std::string(199, '(') + "2" + std::string(199, ')')), 2.0);
}

TEST(Parser, OverlongExpressionsAreRefused) {
  std::string text = "1";
  while (text.size() <= kMaxExpressionLength) text += "+1";
  EXPECT_NE(error_of(text).find("characters long, more than the 1000000"), std::string::npos);
}

// A long flat sum is built in one go (GiNaC's += copied the growing sum: quadratic time).
// Σ_{k=1..n} 0.5^k is summed exactly in rationals; its closed form is 1 − 2^−n; tolerance:
// the one final conversion to double, 1 ulp.
TEST(Parser, LongSumsAreLinear) {
  std::string text;
  const int n = 2000;  // distinct rational terms: exact, and 2000 of them stay cheap
  for (int k = 1; k <= n; ++k) {
    if (k > 1) text += '+';
    text += "0.5^";
    text += std::to_string(k);
  }
  EXPECT_NEAR(eval(text), 1.0 - std::pow(2.0, -n), 1.2e-16);
  // 200,000 terms of a parameter: seconds when quadratic, milliseconds now (generous bound 2 s)
  std::string many = "a";
  for (int k = 0; k < 200'000; ++k) many += "+a";
  const auto start = Clock::now();
  EXPECT_EQ(eval(many, {{"a", 0.5}}), 100'000.5);
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - start).count(),
            rigid::test::hang_bound(2.0));
}

// 9^9^9 = 9^387420489 was computed exactly (13 s, 791 MB) before being found not finite. The
// size of a power of two numbers is estimated first.
TEST(Parser, HugePowersAreRefusedBeforeTheyAreComputed) {
  const auto start = Clock::now();
  const std::string msg = error_of("9^9^9");
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - start).count(),
            rigid::test::hang_bound(1.0));
  // at the second '^' (offset 1 + 10 = col 11): 9^(9^9) is refused as a whole
  EXPECT_NE(msg.find("e.toml:3:11: value: the power is about 10^3.697e+08"), std::string::npos) << msg;
  EXPECT_NE(error_of("0.5^(10^6)").find("the power is about 10^-3.01e+05"), std::string::npos);
  EXPECT_NE(error_of("a^(10^6)", {{"a", 9.0}}).find("the power is about 10^9.542e+05"), std::string::npos);
  // powers within the margin stay exact: 10^400/10^399 = 10
  EXPECT_EQ(eval("10^400/10^399"), 10.0);
  // an exact result too long to compute (1.0001^10^5 has 1.4 million-bit numerator and
  // denominator) is computed in floating point: (1 + 1e-4)^1e5 = exp(1e5·log1p(1e-4));
  // tolerance 1e-12 relative: GiNaC's 17+ digit floats and the reference's libm rounding
  const double reference = std::exp(1e5 * std::log1p(1e-4));
  EXPECT_NEAR(eval("1.0001^(10^5)"), reference, 1e-12 * reference);
  EXPECT_NEAR(eval("1.0001^(10^6)") / std::exp(1e6 * std::log1p(1e-4)), 1.0, 1e-11);
}

TEST(Parser, LibraryFailuresAreWordedWithTheirPosition) {
  // GiNaC threw "log_eval(): log(0)", "power::eval(): division by zero"; CLN "floating point
  // underflow."; 0^0 escaped as std::domain_error
  const std::string log0 = error_of("1 + log(0)");
  EXPECT_NE(log0.find("e.toml:3:14: value: the expression has a pole here"), std::string::npos) << log0;
  EXPECT_NE(error_of("tan(pi/2)").find("has a pole"), std::string::npos);
  EXPECT_NE(error_of("2*0^0").find("e.toml:3:13: value: 0^0 is undefined"), std::string::npos);
  EXPECT_NE(error_of("0^(-1)").find("0 to a negative power is a division by zero"), std::string::npos);
  const std::string under = error_of("exp(-a*1e300)", {{"a", 1e-200}});
  EXPECT_NE(under.find("underflows"), std::string::npos) << under;
  for (const std::string& m : {log0, under, error_of("0^0"), error_of("9^9^9"), error_of("asin(2)")}) {
    expect_no_raw_text(m);
  }
}

// A power of two numbers is exact when its value is rational or a square root; any other
// irrational root is computed in floating point as it is parsed (GiNaC would otherwise try the
// exact result again through exp and log each time a product holding it is rebuilt: a sum to
// the 8th holding 77777^0.1787 took 1.6 s to derive and print, and 20 s under the sanitizers).
// A negative base to a non-integer power, sqrt, asin and acos of numbers outside their real
// domain are refused where they are written, not found as a NaN at run time.
TEST(Parser, PowersOfNumbersAreExactOnlyWhenRationalOrASquareRoot) {
  EXPECT_EQ(eval("8^(1/3)"), 2.0);
  EXPECT_EQ(eval("(27/8)^(2/3)"), 2.25);
  EXPECT_EQ(eval("(-8)^2"), 64.0);
  EXPECT_EQ(eval("(-8)^(6/3)"), 64.0);  // the exponent is the integer 2
  // GiNaC's 17+ digits rounded to a double: within 1 ulp of the libm value, which is itself
  // within 1 ulp of the exact root (2^-52 relative each)
  EXPECT_NEAR(eval("2^(1/3)"), std::cbrt(2.0), 2 * 0x1p-52 * std::cbrt(2.0));
  // 0.1787387777 as a double differs from the decimal by at most half an ulp (1.4e-17); times
  // ln 77777 = 11.26 that moves the power by 1.6e-16 relative, plus each side's rounding
  const double p = std::pow(77777.0, 0.1787387777);
  EXPECT_NEAR(eval("77777^.1787387777"), p, 1e-15 * p);
  EXPECT_NEAR(eval("2^0.5"), std::sqrt(2.0), 0x1p-52 * std::sqrt(2.0));

  // printed: a square root stays exact, another root is its value
  auto equations_of = [](const std::string& coefficient) {
    SystemSpec spec;
    spec.coordinates = {{"q", 1.0, 0.0}};
    spec.lagrangian = Expression("q_dot^2/2 - " + coefficient + "*q^2/2");
    std::string text;
    for (const auto& line : System(spec).equations().text) text += line + "\n";
    return text;
  };
  EXPECT_NE(equations_of("2^0.5").find("q_ddot = -sqrt(2)*q"), std::string::npos) << equations_of("2^0.5");
  const std::string cube = equations_of("2^(1/3)");
  EXPECT_NE(cube.find("q_ddot = -1.25992104989487"), std::string::npos) << cube;
  EXPECT_EQ(cube.find("1/3"), std::string::npos) << cube;

  const std::string negative = error_of("1 + (-8)^(1/3)");
  EXPECT_NE(negative.find("e.toml:3:18: value: (-8)^(1/3) is not real: a negative number to a "
                          "non-integer power; expected a positive base or an integer exponent"),
            std::string::npos)
      << negative;
  EXPECT_NE(error_of("(-1)^0.25").find("(-1)^(1/4) is not real"), std::string::npos);
  EXPECT_NE(error_of("(-a)^(1/3)", {{"a", 8.0}}).find("(-8.0)^(1/3) is not real"), std::string::npos)
      << error_of("(-a)^(1/3)", {{"a", 8.0}});
  const std::string root = error_of("2*sqrt(-2)");
  EXPECT_NE(root.find("e.toml:3:12: value: sqrt(-2) is not real; expected a non-negative argument"),
            std::string::npos)
      << root;
  EXPECT_NE(error_of("asin(2)").find("e.toml:3:10: value: asin(2) is not real; expected an argument in [-1, 1]"),
            std::string::npos)
      << error_of("asin(2)");
  EXPECT_NE(error_of("acos(-1.5)").find("acos(-3/2) is not real"), std::string::npos);
  EXPECT_EQ(eval("asin(1)"), std::asin(1.0));
  for (const std::string& m : {negative, root, error_of("asin(2)")}) expect_no_raw_text(m);
}

// A name alone or negated is read without the symbolic core (what a sweep's run evaluates
// most); it must give the very bits of the general path, which "(x)" and "-(x)" still take.
TEST(EvaluateConstant, NamesAreReadWithoutTheSymbolicCoreAndExactlyAsParsed) {
  for (double v : {1.0, -2.5, 0.1, 9.81, 2.3e-308, -1e308, 3.0e-5, 123456789.123}) {
    const std::vector<Parameter> params{{"x", 7.0}, {"x", v}};  // the last of a name counts
    const SymbolicCoreUsage before = symbolic_core_usage();
    const double by_name = eval(" x ", params), negated = eval("-x", params);
    EXPECT_EQ(symbolic_core_usage().entries, before.entries) << v;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(by_name), std::bit_cast<std::uint64_t>(eval("(x)", params))) << v;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(by_name), std::bit_cast<std::uint64_t>(v));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(negated), std::bit_cast<std::uint64_t>(eval("-(x)", params))) << v;
    (void)eval("x", params);
    EXPECT_EQ(symbolic_core_usage().entries, before.entries + 2) << "only the two parenthesised forms";
  }
  // what is not a known, finite, nonzero name goes the general way, with its messages
  EXPECT_DOUBLE_EQ(eval("pi"), M_PI);
  EXPECT_EQ(eval("-x", {{"x", 0.0}}), 0.0);
  EXPECT_EQ(error_of("x", {{"x", 1e-310}}), error_of("(x)", {{"x", 1e-310}}));  // a subnormal alike
  EXPECT_NE(error_of("y", {{"x", 1.0}}).find("y"), std::string::npos);
  EXPECT_NE(error_of("x", {{"x", INFINITY}}).find("parameter 'x' = inf overflows"), std::string::npos);
}

// The names of an expression as the parser reads them: numbers (with exponents, a leading or
// trailing point) are none of them, `e` inside a number is no name, functions and pi are names.
// Checked against the parser itself: every name of a text it accepts with parameters a, b_2, c
// and nothing else is one of those or a function, and a text naming another is refused.
TEST(NamesIn, AreTheNamesTheParserReads) {
  EXPECT_EQ(names_in("a*sin(b_2) + 1e-3*c - 2.5E+4 + .5/a + 3.*pi"),
            (std::vector<std::string>{"a", "sin", "b_2", "c", "a", "pi"}));
  EXPECT_EQ(names_in("2e5 + 1E3 + 7"), std::vector<std::string>{});
  EXPECT_EQ(names_in("_x1^2"), std::vector<std::string>{"_x1"});
  const std::vector<Parameter> params{{"a", 1.5}, {"b_2", -0.25}, {"c", 2.0}};
  for (const char* text : {"a*sin(b_2) + 1e-3*c - 2.5E+4", "(a + c)^2 / 3e+1", "-b_2 * exp(a*1E-2)"}) {
    (void)evaluate_constant(Expression(text), params, "names");  // the parser accepts it
    for (const std::string& n : names_in(text)) {
      EXPECT_TRUE(n == "a" || n == "b_2" || n == "c" || n == "sin" || n == "exp") << text << ": " << n;
    }
  }
  EXPECT_EQ(names_in("a*d"), (std::vector<std::string>{"a", "d"}));
  EXPECT_RIGID_ERROR((void)evaluate_constant(Expression("a*d"), params, "names"), "undefined symbol 'd'");
}

}  // namespace
}  // namespace rigid::lagrange
