#include "lagrange/detail/tape.hpp"
#include "lagrange/detail/symbolic.hpp"

#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>
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

// Tape::tangent (forward mode) against the symbolic derivatives (detail::d, GiNaC) compiled to
// a tape of their own, for every operation: two independent ways to the same numbers. The
// derivative programs differ (the chain rule per instruction against rewritten expressions), so
// a few roundings apart: 256 ulps of 1 + |∂f/∂v|. Also the tangent along a seed that mixes the
// inputs (a directional derivative) and the defined names of TapeBuilder::define.
TEST(Tape, TangentIsTheDerivativeOfEveryOperation) {
  const symbol x("x"), y("y"), w("w");
  const std::vector<ex> exprs = {
      x + 2 * y - 3,
      x * y / (1 + x * x),
      GiNaC::pow(x, 7) - GiNaC::pow(y, -3) + GiNaC::pow(x, GiNaC::numeric(3, 2)),
      GiNaC::sqrt(x + y) + 1 / GiNaC::sqrt(x) + GiNaC::pow(x, y) + GiNaC::pow(x, -2),
      GiNaC::sin(x) * GiNaC::cos(y) + GiNaC::tan(x / 3) + GiNaC::asin(y / 4) +
          GiNaC::acos(y / 5) + GiNaC::atan(x),
      GiNaC::exp(-y) + GiNaC::log(x) + GiNaC::abs(y - 2) + GiNaC::sinh(x) + GiNaC::cosh(y) +
          GiNaC::tanh(x - y) + GiNaC::Pi * x,
      w * w * x - GiNaC::sin(w)};  // w = x·y², a defined name
  const ex w_value = x * GiNaC::pow(y, 2);
  TapeBuilder b({x, y});
  b.define(w, w_value);
  for (const ex& e : exprs) b.add_output(e);
  const Tape tape = b.build();
  // the symbolic derivatives, w substituted first; |y − 2| is 2 − y at the point (y = 0.7), as
  // GiNaC differentiates abs() of a complex symbol by conjugates
  TapeBuilder db({x, y});
  for (const ex& e : exprs) {
    const ex full = e.subs(w == w_value).subs(GiNaC::abs(y - 2) == 2 - y);
    db.add_output(d(full, x));
    db.add_output(d(full, y));
  }
  const Tape derivatives = db.build();
  const double in[] = {1.3, 0.7};
  std::vector<double> out(tape.num_outputs()), scratch = tape.make_scratch();
  std::vector<double> dscratch = tape.make_scratch();
  tape.evaluate(in, out.data(), scratch);
  std::vector<double> expected(derivatives.num_outputs());
  derivatives.evaluate(in, expected.data());
  const double seeds[3][2] = {{1, 0}, {0, 1}, {0.6, -0.8}};
  for (const auto& seed : seeds) {
    std::vector<double> tangent(tape.num_outputs());
    tape.tangent(seed, tangent.data(), scratch, dscratch);
    for (std::size_t k = 0; k < exprs.size(); ++k) {
      const double want = seed[0] * expected[2 * k] + seed[1] * expected[2 * k + 1];
      EXPECT_NEAR(tangent[k], want, test::ulps(256, 1 + std::abs(want)))
          << "expression " << k << ", seed (" << seed[0] << ", " << seed[1] << ")";
    }
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

TEST(Tape, ProductsWithACommonPrefixShareIt) {
  // a·b·c and a·b·d: the factors are multiplied in one (sorted) order, so a·b is one
  // instruction for both (value numbering): 3 products, not 4
  const symbol a("a"), bb("b"), c("c"), d("d");
  TapeBuilder b({d, a, bb, c});
  b.add_output(a * bb * c);
  b.add_output(a * bb * d);
  const Tape tape = b.build();
  EXPECT_EQ(tape.count(Op::kMul), 3u);
  double out[2];
  const double in[] = {0.5, 3.0, 7.0, 11.0};
  tape.evaluate(in, out);
  // small integers and halves: every product is exact
  EXPECT_EQ(out[0], 3.0 * 7.0 * 11.0);
  EXPECT_EQ(out[1], 3.0 * 7.0 * 0.5);
}

TEST(Tape, DispatchesOncePerGroupOfIndependentInstructions) {
  // Σ_k sin(x_k)·cos(x_k) over 16 inputs: 16 sin, 16 cos, 16 products, 15 sums; by level that
  // is sin | cos (level 1), the products (level 2) and the balanced sum (levels 3–6): 7
  // groups for 63 instructions (one dispatch per instruction before)
  std::vector<symbol> x;
  for (int k = 0; k < 16; ++k) x.emplace_back(fmt::format("x{}", k));
  ex sum = 0;
  for (const symbol& s : x) sum += GiNaC::sin(s) * GiNaC::cos(s);
  TapeBuilder b(x);
  b.add_output(sum);
  const Tape tape = b.build();
  EXPECT_EQ(tape.size(), 63u);
  EXPECT_EQ(tape.num_groups(), 7u);
  std::vector<double> in(16);
  double expected = 0;
  for (int k = 0; k < 16; ++k) {
    in[static_cast<std::size_t>(k)] = 0.1 * k - 0.7;
    expected += std::sin(in[static_cast<std::size_t>(k)]) * std::cos(in[static_cast<std::size_t>(k)]);
  }
  double out = 0;
  tape.evaluate(in.data(), &out);
  // 16 terms of magnitude ≤ ½ summed in another order: ≤ 16 roundings of ≤ 8
  EXPECT_NEAR(out, expected, test::ulps(16, 8.0));
}

TEST(Tape, InstructionsReadOnlyEarlierSlots) {
  // the execution order is a valid straight-line program (what the code export prints)
  const symbol x("x"), y("y");
  TapeBuilder b({x, y});
  b.add_output(GiNaC::sin(x * y) + GiNaC::pow(x, 5) - y / (x + 1));
  b.add_output(GiNaC::cos(x * y) * GiNaC::sqrt(y));
  const Tape tape = b.build();
  const std::size_t base = tape.num_inputs() + tape.constants().size();
  for (std::size_t k = 0; k < tape.instructions().size(); ++k) {
    const Instruction& in = tape.instructions()[k];
    EXPECT_LT(static_cast<std::size_t>(in.a), base + k) << k;
    const bool binary = in.op == Op::kAdd || in.op == Op::kSub || in.op == Op::kMul ||
                        in.op == Op::kDiv || in.op == Op::kPow;
    if (binary) {
      EXPECT_LT(static_cast<std::size_t>(in.b), base + k) << k;
    }
  }
}

}  // namespace
}  // namespace rigid::lagrange::detail
