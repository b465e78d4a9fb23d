#include "rigid/body/free_body_batch.hpp"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "support/expect_error.hpp"

namespace rigid::body {
namespace {

// random bodies: moments of boxes with sides in [0.1, 1] m and unit mass (so the triangle
// inequality holds), ω ∈ [−2, 2]³ rad/s, random orientation
void random_bodies(int n, std::vector<Eigen::Vector3d>& I, std::vector<FreeBodyState>& s) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> side(0.1, 1.0), omega(-2.0, 2.0);
  for (int b = 0; b < n; ++b) {
    const double x = side(rng), y = side(rng), z = side(rng);
    I.emplace_back((y * y + z * z) / 12, (x * x + z * z) / 12, (x * x + y * y) / 12);
    FreeBodyState st;
    st.R_WB = SO3d::sample(rng);
    st.w_B = Eigen::Vector3d(omega(rng), omega(rng), omega(rng));
    s.push_back(st);
  }
}

TEST(FreeBodyBatch, EqualsSingleBodyStepperBitwise) {
  std::vector<Eigen::Vector3d> I;
  std::vector<FreeBodyState> batch;
  random_bodies(50, I, batch);
  for (const FreeBodyMethod m : {FreeBodyMethod::kSplitting2, FreeBodyMethod::kSplitting4,
                                 FreeBodyMethod::kSplitting6, FreeBodyMethod::kRk4,
                                 FreeBodyMethod::kLiePoissonMidpoint}) {
    SCOPED_TRACE(std::string(name_of(m)));
    std::vector<FreeBodyState> b = batch, single = batch;
    const double h = 0.01;
    for (int k = 0; k < 200; ++k) {
      step_free_bodies(m, I, b, h);
      for (std::size_t i = 0; i < single.size(); ++i) single[i] = step_free_body(m, I[i], single[i], h);
    }
    // one kernel serves both entry points, so the results must be bitwise equal (an
    // independent check of that kernel against the unmerged textbook composition is in
    // free_body_integrators_test.cpp)
    double max_w = 0, max_q = 0;
    for (std::size_t i = 0; i < b.size(); ++i) {
      max_w = std::max(max_w, (b[i].w_B - single[i].w_B).lpNorm<Eigen::Infinity>());
      max_q = std::max(max_q, (b[i].R_WB.quaternion() - single[i].R_WB.quaternion()).lpNorm<Eigen::Infinity>());
    }
    EXPECT_EQ(max_w, 0.0);
    EXPECT_EQ(max_q, 0.0);
  }
}

TEST(FreeBodyBatch, RejectsMismatchedSpansAndBadStep) {
  std::vector<Eigen::Vector3d> I(3, Eigen::Vector3d(1, 2, 3));
  std::vector<FreeBodyState> s(2);
  EXPECT_RIGID_ERROR(step_free_bodies(FreeBodyMethod::kSplitting4, I, s, 0.1),
                     "3 principal-moment vectors for 2 states; expected one per body");
  s.resize(3);
  EXPECT_RIGID_ERROR(step_free_bodies(FreeBodyMethod::kSplitting4, I, s, -0.1),
                     "step h must be positive and finite, got -0.1 s");
}

TEST(FreeBodyBatch, NamesTheBodyWhoseImplicitStepDoesNotConverge) {
  // body 1 is the racket spun at 3 rad/s with h = 1 s (h |ω| max(I)/min(I) = 9): its midpoint
  // step does not converge and is refused naming the body; body 0 (ω ten times smaller, 0.9)
  // converges and was stepped, body 2 was not
  const std::vector<Eigen::Vector3d> I(3, Eigen::Vector3d(1, 2, 3));
  std::vector<FreeBodyState> s(3);
  s[0].w_B = Eigen::Vector3d(0.001, 0.3, 0.001);
  s[1].w_B = Eigen::Vector3d(0.01, 3, 0.01);
  s[2].w_B = s[0].w_B;
  const std::vector<FreeBodyState> before = s;
  EXPECT_RIGID_ERROR(step_free_bodies(FreeBodyMethod::kLiePoissonMidpoint, I, s, 1.0),
                     "step_free_bodies(): body 1: step_free_body(): the Lie–Poisson midpoint step "
                     "(midpoint) did not converge: h = 1 s");
  EXPECT_NE(s[0].w_B, before[0].w_B);
  EXPECT_EQ(s[1].w_B, before[1].w_B);
  EXPECT_EQ(s[2].w_B, before[2].w_B);
}

TEST(StepFreeBodies, RefusesBadInputNamingTheBody) {
  const std::vector<Eigen::Vector3d> I{{1, 2, 3}, {1, 2, 3}};
  std::vector<FreeBodyState> s(2);
  s[0].w_B = Eigen::Vector3d(0.1, 0.2, 0.3);
  s[1].w_B = Eigen::Vector3d(0, std::nan(""), 0);
  const std::vector<FreeBodyState> before = s;
  EXPECT_RIGID_ERROR(step_free_bodies(FreeBodyMethod::kSplitting2, I, s, 0.01),
                     "step_free_bodies(): body 1: the state is not finite: w_B.y = nan");
  EXPECT_NE(s[0].w_B, before[0].w_B);  // the bodies before the refused one have been stepped
  EXPECT_TRUE(std::isnan(s[1].w_B(1)));  // the refused body is left as it was
  s[1].w_B = Eigen::Vector3d(0, 0, 1);
  const std::vector<Eigen::Vector3d> bad_I{{1, 2, 3}, {1, -2, 3}};
  EXPECT_RIGID_ERROR(step_free_bodies(FreeBodyMethod::kRk4, bad_I, s, 0.01),
                     "body 1: principal moments [1, -2, 3] kg·m² must be positive and finite");
  const std::vector<Eigen::Vector3d> nan_I{{std::nan(""), 2, 3}, {1, 2, 3}};
  EXPECT_RIGID_ERROR(step_free_bodies(FreeBodyMethod::kRk4, nan_I, s, 0.01),
                     "body 0: principal moments [nan, 2, 3] kg·m² must be positive and finite");
}

TEST(StepFreeBodies, RefusesAStepThatDiverges) {
  // RK4 with h |ω| = 1e200: the stages overflow (ω̇ ~ ω² = 1e200, then 1e600), the state is NaN
  const std::vector<Eigen::Vector3d> I{{1, 2, 3}};
  std::vector<FreeBodyState> s(1);
  s[0].w_B = Eigen::Vector3d(1e100, 1e100, 1e100);
  EXPECT_RIGID_ERROR(step_free_bodies(FreeBodyMethod::kRk4, I, s, 1e100),
                     "step_free_bodies(): body 0: the step of h = 1e+100 s diverged");
}

}  // namespace
}  // namespace rigid::body
