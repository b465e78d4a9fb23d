#include "lagrange/detail/tape.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "support/tolerance.hpp"

namespace rigid::lagrange::detail {
namespace {

using GiNaC::ex;
using GiNaC::symbol;

TEST(Tape, EvaluatesEveryOperationLikeTheStandardLibrary) {
  const symbol x("x"), y("y");
  const std::vector<ex> exprs = {
      x + 2 * y - 3,
      x * y / (1 + x * x),
      GiNaC::pow(x, 7) - GiNaC::pow(y, -3) + GiNaC::pow(x, GiNaC::numeric(3, 2)),
      GiNaC::sqrt(x + y) + 1 / GiNaC::sqrt(x) + GiNaC::pow(x, y),
      GiNaC::sin(x) * GiNaC::cos(y) + GiNaC::tan(x / 3) + GiNaC::asin(y / 4) +
          GiNaC::acos(y / 5) + GiNaC::atan(x),
      GiNaC::exp(-y) + GiNaC::log(x) + GiNaC::abs(y - 2) + GiNaC::sinh(x) + GiNaC::cosh(y) +
          GiNaC::tanh(x - y) + GiNaC::Pi * x};
  TapeBuilder b({x, y});
  for (const ex& e : exprs) b.add_output(e);
  const Tape tape = b.build();
  const double X = 1.3, Y = 0.7;
  const double expected[] = {
      X + 2 * Y - 3,
      X * Y / (1 + X * X),
      std::pow(X, 7) - std::pow(Y, -3) + std::pow(X, 1.5),
      std::sqrt(X + Y) + 1 / std::sqrt(X) + std::pow(X, Y),
      std::sin(X) * std::cos(Y) + std::tan(X / 3) + std::asin(Y / 4) + std::acos(Y / 5) +
          std::atan(X),
      std::exp(-Y) + std::log(X) + std::abs(Y - 2) + std::sinh(X) + std::cosh(Y) +
          std::tanh(X - Y) + M_PI * X};
  const double in[] = {X, Y};
  double out[6];
  tape.evaluate(in, out);
  for (int k = 0; k < 6; ++k) {
    // a few roundings in a different order than the reference: ≤ 64 ulps of the magnitude
    EXPECT_NEAR(out[k], expected[k], test::ulps(64, 1 + std::abs(expected[k]))) << k;
  }
}

TEST(Tape, RepeatedSubexpressionsAreComputedOnce) {
  // sin(x) and cos(x) appear in all three outputs; each is computed once
  const symbol x("x"), y("y");
  TapeBuilder b({x, y});
  b.add_output(GiNaC::sin(x) * GiNaC::cos(x) + x * y);
  b.add_output(GiNaC::pow(GiNaC::sin(x), 2) * x * y);
  b.add_output(GiNaC::cos(x) - GiNaC::sin(x));
  const Tape tape = b.build();
  EXPECT_EQ(tape.count(Op::kSin), 1u);
  EXPECT_EQ(tape.count(Op::kCos), 1u);
  double out[3];
  const double in[] = {0.4, 2.0};
  tape.evaluate(in, out);
  EXPECT_NEAR(out[2], std::cos(0.4) - std::sin(0.4), test::ulps(4));
}

TEST(Tape, OutputsMayBeInputsOrConstants) {
  const symbol x("x");
  TapeBuilder b({x});
  b.add_output(x);
  b.add_output(GiNaC::numeric(5, 2));
  const Tape tape = b.build();
  EXPECT_EQ(tape.size(), 0u);
  double out[2];
  const double in[] = {-3.0};
  tape.evaluate(in, out);
  EXPECT_EQ(out[0], -3.0);
  EXPECT_EQ(out[1], 2.5);
}

}  // namespace
}  // namespace rigid::lagrange::detail
