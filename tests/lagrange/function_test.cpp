// lagrange::compile_function: an expression of named variables evaluated from its tape equals
// the expression evaluated by hand, for interleaved functions in one thread and from several
// threads; bad input is refused at its column.
#include "rigid/lagrange/function.hpp"

#include <array>
#include <cmath>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "support/expect_error.hpp"

namespace rigid::lagrange {
namespace {

TEST(CompiledFunction, EqualsTheExpressionByHand) {
  const CompiledFunction f = compile_function(Expression("rho0*(1 + x^2) + sin(y)*z/2"),
                                              {"x", "y", "z"}, {{"rho0", 7.5}}, "test");
  const CompiledFunction g = compile_function(Expression("exp(-x) - y"), {"x", "y"}, {}, "test");
  for (int k = 0; k < 5; ++k) {
    const double x = 0.3 * k - 0.7, y = 1.1 - 0.2 * k, z = 0.05 * k;
    const std::array<double, 3> p{x, y, z};
    const std::array<double, 2> q{x, y};
    // the two alternate in one thread: each keeps its constants (7.5, 1, 1/2) apart
    EXPECT_NEAR(f(p), 7.5 * (1 + x * x) + std::sin(y) * z / 2, 1e-14);
    EXPECT_NEAR(g(q), std::exp(-x) - y, 1e-15);
  }
  EXPECT_EQ(f.variables(), (std::vector<std::string>{"x", "y", "z"}));
}

TEST(CompiledFunction, ManyThreadsEvaluateOneFunction) {
  const CompiledFunction f = compile_function(Expression("x*x*y + 3"), {"x", "y"}, {}, "test");
  std::vector<double> worst(4, 0.0);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (int k = 0; k < 2000; ++k) {
        const double x = 0.001 * k + t, y = 0.5 - 0.0003 * k;
        const std::array<double, 2> p{x, y};
        worst[static_cast<std::size_t>(t)] =
            std::max(worst[static_cast<std::size_t>(t)], std::abs(f(p) - (x * x * y + 3)));
      }
    });
  }
  for (auto& th : threads) th.join();
  for (const double w : worst) EXPECT_LE(w, 1e-13);
}

TEST(CompiledFunction, RefusesWhatItCannotCompile) {
  EXPECT_RIGID_ERROR((void)compile_function(Expression("x + w"), {"x"}, {}, "field"),
                     "field: undefined symbol 'w'");
  EXPECT_RIGID_ERROR((void)compile_function(Expression("   "), {"x"}, {}, "field"),
                     "empty expression");
  EXPECT_RIGID_ERROR((void)compile_function(Expression("x"), {"sin"}, {}, "field"),
                     "variable 'sin'");
  EXPECT_RIGID_ERROR((void)compile_function(Expression("x"), {"x"}, {{"x", 1.0}}, "field"),
                     "variable 'x' is also a parameter's name");
  const CompiledFunction f = compile_function(Expression("x"), {"x"}, {}, "field");
  const std::array<double, 2> two{1.0, 2.0};
  EXPECT_RIGID_ERROR((void)f(two), "'x' takes 1 value (x), got 2");
}

}  // namespace
}  // namespace rigid::lagrange
