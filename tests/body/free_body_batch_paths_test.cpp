// The code paths of step_free_bodies (scalar, four bodies in baseline vectors, four bodies in
// AVX2) give the same bits as step_free_body body by body, for every splitting, step size and
// kind of body, including the lanes that leave the series for std::sin/std::cos, the last
// partial block, a step that diverges and an input that is refused.
#include <bit>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "body/detail/free_body_batch_paths.hpp"
#include "rigid/body/free_body_batch.hpp"
#include "support/expect_error.hpp"

namespace rigid::body {
namespace {

using detail::BatchPath;

constexpr FreeBodyMethod kSplittings[] = {FreeBodyMethod::kSplitting2, FreeBodyMethod::kSplitting4,
                                          FreeBodyMethod::kSplitting6};

// Bodies of every kind the kernel meets: boxes (sides in [0.05, 1] m, unit mass), axially
// symmetric ones (I1 = I2), thin rods (I3 ≪ I1), spins from rest to 400 rad/s (at h = 0.01 a
// sub-flow's half angle c h ω reaches 1, past the series' bound 0.5) and random orientations.
// 1003 bodies: the last block of four holds three.
void mixed_bodies(std::vector<Eigen::Vector3d>& I, std::vector<FreeBodyState>& s) {
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> side(0.05, 1.0), unit(-1.0, 1.0);
  for (int b = 0; b < 1003; ++b) {
    double x = side(rng), y = side(rng), z = side(rng);
    if (b % 7 == 0) y = x;          // symmetric about the body's z axis
    if (b % 11 == 0) x = y = 1e-3;  // a thin rod along z
    I.emplace_back((y * y + z * z) / 12, (x * x + z * z) / 12, (x * x + y * y) / 12);
    const double spin = b % 13 == 0 ? 400.0 : (b % 5 == 0 ? 0.0 : 3.0);
    FreeBodyState st;
    st.R_WB = SO3d::sample(rng);
    st.w_B = spin * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    s.push_back(st);
  }
}

std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }

// The first component where two batches differ in any bit, or "" when all are equal.
std::string first_difference(const std::vector<FreeBodyState>& a,
                             const std::vector<FreeBodyState>& b) {
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Eigen::Vector4d qa = a[i].R_WB.quaternion(), qb = b[i].R_WB.quaternion();
    for (int k = 0; k < 4; ++k)
      if (bits(qa(k)) != bits(qb(k)))
        return fmt::format("body {} q[{}]: {:.17g} vs {:.17g}", i, k, qa(k), qb(k));
    for (int k = 0; k < 3; ++k) {
      if (bits(a[i].w_B(k)) != bits(b[i].w_B(k)))
        return fmt::format("body {} w[{}]: {:.17g} vs {:.17g}", i, k, a[i].w_B(k), b[i].w_B(k));
    }
  }
  return "";
}

std::vector<BatchPath> lane_paths() {
  std::vector<BatchPath> paths{BatchPath::kLanes};
  if (detail::batch_path_available(BatchPath::kLanesAvx2)) paths.push_back(BatchPath::kLanesAvx2);
  return paths;
}

TEST(FreeBodyBatchPaths, EveryPathEqualsTheSingleBodyStepBitwise) {
  std::vector<Eigen::Vector3d> I;
  std::vector<FreeBodyState> start;
  mixed_bodies(I, start);
  for (const FreeBodyMethod m : kSplittings) {
    for (const double h : {1e-3, 1e-2, 5e-2}) {
      std::vector<FreeBodyState> single = start;
      for (int k = 0; k < 20; ++k)
        for (std::size_t b = 0; b < single.size(); ++b)
          single[b] = step_free_body(m, I[b], single[b], h);
      for (const BatchPath path : lane_paths()) {
        SCOPED_TRACE(fmt::format("{} h = {} path {}", name_of(m), h, static_cast<int>(path)));
        std::vector<FreeBodyState> batch = start;
        for (int k = 0; k < 20; ++k) detail::step_free_bodies_on(path, m, I, batch, h);
        EXPECT_EQ(first_difference(batch, single), "");
      }
    }
  }
}

// The public entry point takes a four-body path for the splittings and the scalar one for the
// other methods (their steps are not the splitting kernel).
TEST(FreeBodyBatchPaths, TheSplittingsTakeAFourBodyPath) {
  for (const FreeBodyMethod m : kSplittings)
    EXPECT_NE(detail::batch_path_of(m), BatchPath::kScalar);
  EXPECT_EQ(detail::batch_path_of(FreeBodyMethod::kRk4), BatchPath::kScalar);
  EXPECT_EQ(detail::batch_path_of(FreeBodyMethod::kLiePoissonMidpoint), BatchPath::kScalar);
  std::vector<Eigen::Vector3d> I{{1, 2, 3}};
  std::vector<FreeBodyState> s(1);
  EXPECT_RIGID_ERROR(
      detail::step_free_bodies_on(BatchPath::kLanes, FreeBodyMethod::kRk4, I, s, 0.01),
      "the four-body path takes the splittings only, not rk4");
}

// A body whose step overflows (L = I ω beyond the largest double) diverges on every path with
// the same refusal, naming it, and every body holds the same bits afterwards.
TEST(FreeBodyBatchPaths, ADivergedStepIsRefusedAlikeOnEveryPath) {
  std::vector<Eigen::Vector3d> I;
  std::vector<FreeBodyState> start;
  mixed_bodies(I, start);
  start[6].w_B = Eigen::Vector3d(1e308, 1e308, 0.0);
  I[6] = Eigen::Vector3d(10.0, 10.0, 15.0);
  std::vector<FreeBodyState> scalar = start;
  std::string expected;
  try {
    detail::step_free_bodies_on(BatchPath::kScalar, FreeBodyMethod::kSplitting2, I, scalar, 0.01);
  } catch (const Error& e) {
    expected = e.what();
  }
  ASSERT_NE(expected.find("body 6: the step of h = 0.01 s diverged"), std::string::npos)
      << expected;
  for (const BatchPath path : lane_paths()) {
    std::vector<FreeBodyState> batch = start;
    EXPECT_RIGID_ERROR(
        detail::step_free_bodies_on(path, FreeBodyMethod::kSplitting2, I, batch, 0.01), expected);
    EXPECT_EQ(first_difference(batch, scalar), "");
  }
}

// A refused input in the middle of a block of four: the bodies before it are stepped (the same
// bits as the scalar path), it and those after it are not.
TEST(FreeBodyBatchPaths, ARefusedBodyLeavesTheBodiesAfterItUnstepped) {
  std::vector<Eigen::Vector3d> I;
  std::vector<FreeBodyState> start;
  mixed_bodies(I, start);
  I[9] = Eigen::Vector3d(1.0, -1.0, 1.0);
  for (const BatchPath path : lane_paths()) {
    std::vector<FreeBodyState> batch = start, scalar = start;
    EXPECT_RIGID_ERROR(
        detail::step_free_bodies_on(path, FreeBodyMethod::kSplitting4, I, batch, 0.01),
        "body 9: principal moments");
    for (std::size_t b = 0; b < 9; ++b)
      scalar[b] = step_free_body(FreeBodyMethod::kSplitting4, I[b], start[b], 0.01);
    EXPECT_EQ(first_difference(batch, scalar), "");
  }
}

}  // namespace
}  // namespace rigid::body
