#include "lagrange/detail/canonical.hpp"

#include <cmath>
#include <optional>
#include <random>

#include <gtest/gtest.h>

#include "lagrange/detail/symbolic.hpp"

namespace rigid::lagrange::detail {
namespace {

using GiNaC::cos;
using GiNaC::is_a;
using GiNaC::ex;
using GiNaC::pow;
using GiNaC::sin;
using GiNaC::symbol;

// A double pendulum's symbols: coordinates theta1, theta2 (with velocities) and the
// parameters g, m1, m2, l1, l2 in this declaration order.
struct Symbols {
  symbol th1{"theta1", "\\theta_{1}"}, th2{"theta2", "\\theta_{2}"};
  symbol th1d{"theta1_dot", "\\dot{\\theta}_{1}"}, th2d{"theta2_dot", "\\dot{\\theta}_{2}"};
  symbol th1dd{"theta1_ddot", "\\ddot{\\theta}_{1}"}, th2dd{"theta2_ddot", "\\ddot{\\theta}_{2}"};
  symbol g{"g"}, m1{"m1", "m_{1}"}, m2{"m2", "m_{2}"}, l1{"l1", "l_{1}"}, l2{"l2", "l_{2}"};
  SymbolOrder order;
  Symbols() {
    order.add(th1, SymbolOrder::kCoordinate, 0, 0);
    order.add(th1d, SymbolOrder::kCoordinate, 0, 1);
    order.add(th1dd, SymbolOrder::kCoordinate, 0, 2);
    order.add(th2, SymbolOrder::kCoordinate, 1, 0);
    order.add(th2d, SymbolOrder::kCoordinate, 1, 1);
    order.add(th2dd, SymbolOrder::kCoordinate, 1, 2);
    int k = 0;
    for (const symbol* p : {&g, &m1, &m2, &l1, &l2}) order.add(*p, SymbolOrder::kParameter, k++);
  }
  [[nodiscard]] std::string text(const ex& e) const { return print(textbook(e, order), order, false); }
  [[nodiscard]] std::string latex(const ex& e) const { return print(textbook(e, order), order, true); }
  [[nodiscard]] std::string as_is(const ex& e) const { return print(plain(e, order), order, false); }
};

// e1 − e2 at random points: the simplified form equals the input identically. Values of
// order 1 whose sums and products stay below 100: round-off ≤ 1e-12.
double largest_difference(const ex& a, const ex& b, const std::vector<symbol>& vars) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  double worst = 0.0;
  for (int trial = 0; trial < 20; ++trial) {
    GiNaC::exmap at;
    for (const symbol& v : vars) at[v] = u(rng);
    const ex diff = GiNaC::evalf((a - b).subs(at));
    worst = std::max(worst, std::abs(GiNaC::ex_to<GiNaC::numeric>(diff).to_double()));
  }
  return worst;
}

TEST(CanonicalPrinter, FactorsInNaturalOrderNumbersFirst) {
  const Symbols s;
  // GiNaC may hold this product as l2*l1*sin(theta2)*sin(theta1)
  EXPECT_EQ(s.as_is(s.l2 * s.l1 * sin(s.th2) * sin(s.th1)), "l1*l2*sin(theta1)*sin(theta2)");
  EXPECT_EQ(s.as_is(s.th2dd * s.m2 * 3 * s.l2), "3*m2*l2*theta2_ddot");
  EXPECT_EQ(s.as_is(GiNaC::numeric(1, 2) * s.m1 * pow(s.l1, 2) * pow(s.th1d, 2)),
            "1/2*m1*l1^2*theta1_dot^2");
  EXPECT_EQ(s.as_is(-3 * s.g * sin(s.th1) / (2 * s.l1)), "-3/2*g*sin(theta1)/l1");
}

TEST(CanonicalPrinter, TermsByCoordinateThenDerivativeOrderThenParameters) {
  const Symbols s;
  const ex e = s.l2 * s.th2d + s.m1 * s.th1d + 7 + s.l1 * s.th1 + s.m2;
  // θ1 before θ̇1 before θ̇2; terms without coordinates after, parameters before numbers
  EXPECT_EQ(s.as_is(e), "l1*theta1 + m1*theta1_dot + l2*theta2_dot + m2 + 7");
}

TEST(CanonicalPrinter, SameBytesWhateverTheConstructionOrder) {
  // the same sum built in two orders, with the symbols made in two orders: GiNaC's operand
  // order may differ, the printout may not
  const Symbols s;
  const ex a = s.m1 * sin(s.th1) + s.m2 * cos(s.th2) * s.th2d - s.l1 * s.l2 * s.th1dd;
  const ex b = -s.th1dd * s.l2 * s.l1 + s.th2d * cos(s.th2) * s.m2 + sin(s.th1) * s.m1;
  EXPECT_EQ(s.as_is(a), s.as_is(b));
  EXPECT_EQ(print(plain(a, s.order), s.order, true), print(plain(b, s.order), s.order, true));
}

TEST(CanonicalPrinter, FactorOrderDoesNotFollowGiNaCsOperandOrder) {
  // the symbols made in the opposite order: GiNaC then holds theta1 + theta2 as theta2 +
  // theta1, and a factor's key spelled its symbols in that order (cos(theta1) came before
  // sin(theta1 + theta2) with one order of creation and after it with the other)
  struct Reversed {
    symbol l1{"l1"}, th2{"theta2"}, th1{"theta1"};
    SymbolOrder order;
    Reversed() {
      order.add(th1, SymbolOrder::kCoordinate, 0, 0);
      order.add(th2, SymbolOrder::kCoordinate, 1, 0);
      order.add(l1, SymbolOrder::kParameter, 3);
    }
  };
  const Symbols s;
  const Reversed r;
  const std::string forward = s.as_is(s.l1 * cos(s.th1) * sin(s.th1 + s.th2));
  EXPECT_EQ(r.order.code(r.th1), s.order.code(s.th1));
  EXPECT_EQ(print(plain(r.l1 * cos(r.th1) * sin(r.th1 + r.th2), r.order), r.order, false), forward);
  EXPECT_EQ(print(plain(r.l1 * sin(r.th2 + r.th1) * cos(r.th1), r.order), r.order, false), forward);
}

TEST(CanonicalPrinter, SharedSubexpressionsPrintOnceAndAsATree) {
  // X shared 2^12 times over (each level uses the one below twice): GiNaC holds 13 nodes; the
  // text holds X's tree written out, and the printer visits each distinct node once
  const Symbols s;
  ex x = s.th1 + s.l1;
  for (int level = 0; level < 12; ++level) x = sin(x) + pow(x, 3);
  const std::string text = s.as_is(x);
  std::size_t thetas = 0;
  for (std::size_t at = text.find("theta1"); at != std::string::npos; at = text.find("theta1", at + 1)) ++thetas;
  EXPECT_EQ(thetas, std::size_t{1} << 12);
  std::size_t cubes = 0;
  for (std::size_t at = text.find(")^3"); at != std::string::npos; at = text.find(")^3", at + 1)) ++cubes;
  EXPECT_EQ(cubes, (std::size_t{1} << 12) - 1);
}

TEST(TextbookSimplification, SumToProduct) {
  const Symbols s;
  const ex a = s.th1, b = s.th2;
  EXPECT_EQ(s.text(cos(a) * cos(b) + sin(a) * sin(b)), "cos(theta1 - theta2)");
  EXPECT_EQ(s.text(cos(a) * cos(b) - sin(a) * sin(b)), "cos(theta1 + theta2)");
  EXPECT_EQ(s.text(sin(a) * cos(b) + cos(a) * sin(b)), "sin(theta1 + theta2)");
  EXPECT_EQ(s.text(sin(a) * cos(b) - cos(a) * sin(b)), "sin(theta1 - theta2)");
  // the argument's first term is positive: sin(θ2 − θ1) is written −sin(θ1 − θ2)
  EXPECT_EQ(s.text(cos(a) * sin(b) - sin(a) * cos(b)), "-sin(theta1 - theta2)");
  // with a common factor, as the double pendulum's mass matrix has it
  EXPECT_EQ(s.text(s.m2 * s.l1 * s.l2 * (cos(a) * cos(b) + sin(a) * sin(b))),
            "m2*l1*l2*cos(theta1 - theta2)");
  EXPECT_EQ(s.latex(s.m2 * s.l1 * s.l2 * (cos(a) * cos(b) + sin(a) * sin(b))),
            "m_{2} l_{1} l_{2} \\cos(\\theta_{1} - \\theta_{2})");
}

TEST(TextbookSimplification, PythagorasTakesTheShorterForm) {
  const Symbols s;
  const ex m = s.m1, l = s.l1, th = s.th1;
  EXPECT_EQ(s.text(m * l * l * (pow(sin(th), 2) + pow(cos(th), 2)) * pow(s.th1d, 2)),
            "m1*l1^2*theta1_dot^2");
  // m l² − m l² cos²θ is one term as m l² sin²θ
  EXPECT_EQ(s.text(m * l * l * (1 - pow(cos(th), 2))), "m1*l1^2*sin(theta1)^2");
  EXPECT_EQ(s.latex(m * l * l * (1 - pow(cos(th), 2))), "m_{1} l_{1}^{2} \\sin^{2}(\\theta_{1})");
}

TEST(TextbookSimplification, CommonParametersFactoredOutPerDynamicPart) {
  const Symbols s;
  EXPECT_EQ(s.text(s.m1 * pow(s.l1, 2) + s.m2 * pow(s.l1, 2)), "(m1 + m2)*l1^2");
  EXPECT_EQ(s.text(-s.g * s.m1 * s.l1 * sin(s.th1) - s.g * s.m2 * s.l1 * sin(s.th1)),
            "-(m1 + m2)*g*l1*sin(theta1)");
  EXPECT_EQ(s.text(GiNaC::numeric(1, 2) * s.m1 + s.m2), "1/2*(m1 + 2*m2)");
  // collected per acceleration, in the order of the coordinates
  const Sum lhs = collected({(s.m1 + s.m2) * pow(s.l1, 2), s.m2 * s.l1 * s.l2 * (cos(s.th1) * cos(s.th2) + sin(s.th1) * sin(s.th2))},
                            {s.th1dd, s.th2dd}, s.order);
  EXPECT_EQ(print(lhs, s.order, false),
            "(m1 + m2)*l1^2*theta1_ddot + m2*l1*l2*cos(theta1 - theta2)*theta2_ddot");
}

TEST(TextbookSimplification, EqualsTheInputIdentically) {
  const Symbols s;
  const std::vector<ex> inputs = {
      s.m2 * s.l1 * s.l2 * pow(s.th2d, 2) * (cos(s.th1) * sin(s.th2) - sin(s.th1) * cos(s.th2)) -
          (s.m1 + s.m2) * s.g * s.l1 * sin(s.th1),
      pow(sin(s.th1), 3) * s.m1 + pow(cos(s.th1), 2) * s.m2 * sin(s.th1) + s.l1 / s.l2,
      sin(s.th1) * cos(s.th2) * cos(s.th1 + s.th2) + cos(s.th1) * sin(s.th2) * cos(s.th1 + s.th2),
      // powers of sines and cosines inside a shared, nested power of a sum: the rewrites of
      // sin² and cos² visit each distinct subexpression once and must reach every use
      pow(pow(sin(s.th1), 2) * s.m1 + s.l1, 3) * pow(cos(s.th2), 2) +
          pow(pow(pow(sin(s.th1), 2) * s.m1 + s.l1, 3) + pow(cos(s.th2), 3), 2) * s.th1d};
  const std::vector<symbol> vars = {s.th1, s.th2, s.th1d, s.th2d, s.g, s.m1, s.m2, s.l1, s.l2};
  for (const ex& e : inputs) {
    const ex back = to_ex(textbook(e, s.order));
    // values of order 1 (|x| ≤ 2, about ten terms): round-off below 1e-12
    EXPECT_LT(largest_difference(e, back, vars), 1e-12) << s.text(e);
  }
}

TEST(Rewrite, VisitsEachSubexpressionOnceAndReachesEveryUse) {
  const Symbols s;
  const ex shared = pow(sin(s.th1), 2) + s.l1;
  const ex e = pow(shared, 5) * s.m1 + sin(shared) * cos(s.th2) + GiNaC::exp(shared);
  int calls = 0;
  const auto rule = [&](const ex& x) -> std::optional<ex> {
    ++calls;
    if (is_a<GiNaC::power>(x) && x.op(0).is_equal(sin(s.th1))) return 1 - pow(cos(s.th1), 2);
    return std::nullopt;
  };
  const ex out = rewrite(e, rule);
  // GiNaC's own subs() as the reference: the same replacement everywhere
  EXPECT_TRUE((out - e.subs(pow(sin(s.th1), 2) == 1 - pow(cos(s.th1), 2))).expand().is_zero()) << out;
  EXPECT_FALSE(out.has(pow(sin(s.th1), 2)));
  // e's distinct nodes: the sum, three products or functions, the shared sum and its parts, …
  // well below the 3 uses × the shared part's nodes a tree walk would visit at least
  const int first = calls;
  calls = 0;
  (void)rewrite(pow(e, 2) + e * s.th1d + GiNaC::exp(e), rule);
  EXPECT_LE(calls, first + 12) << first;
  // nothing to replace: the expression itself comes back (no rebuilding)
  const ex unchanged = rewrite(e, [](const ex&) -> std::optional<ex> { return std::nullopt; });
  EXPECT_TRUE(GiNaC::are_ex_trivially_equal(unchanged, e));
}

TEST(NumberText, ShortRationalsOrDecimals) {
  using GiNaC::numeric;
  EXPECT_EQ(number_text(numeric(3), false), "3");
  EXPECT_EQ(number_text(numeric(7, 10), false), "0.7");
  EXPECT_EQ(number_text(numeric(1, 2), false), "1/2");
  EXPECT_EQ(number_text(numeric(1, 3), false), "1/3");
  EXPECT_EQ(number_text(numeric(1, 3), true), "\\frac{1}{3}");
  EXPECT_EQ(number_text(numeric(-3, 100), false), "-0.03");
  EXPECT_EQ(number_text(numeric(123456789, 1000), false), "123456.789");
  // a long non-terminating rational, (10²⁵ + 3)/21: the shortest decimal of the nearest
  // double (Python: repr(float(Fraction(10**25 + 3, 21))))
  EXPECT_EQ(number_text(numeric("10000000000000000000000003") / numeric(21), false),
            "4.761904761904762e+23");
}

}  // namespace
}  // namespace rigid::lagrange::detail
