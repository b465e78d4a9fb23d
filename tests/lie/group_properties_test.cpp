// Typed property suite over the fixed-size groups: identities that hold exactly, checked on
// 10,000 random elements per group with a fixed seed.

#include <random>

#include <gtest/gtest.h>

#include "rigid/lie.hpp"
#include "support/lie_properties.hpp"
#include "support/tolerance.hpp"

namespace rigid {
namespace {

using test::matrix_distance;
using test::random_tangent;

// Each family gives the group for a scalar, so that the AutoDiffXd instance can be checked
// against the double one.
struct SO2Family {
  template <typename S>
  using G = SO2<S>;
};
struct SE2Family {
  template <typename S>
  using G = SE2<S>;
};
struct SO3Family {
  template <typename S>
  using G = SO3<S>;
};
struct SE3Family {
  template <typename S>
  using G = SE3<S>;
};

template <typename F>
class GroupProperties : public ::testing::Test {};
using Families = ::testing::Types<SO2Family, SE2Family, SO3Family, SE3Family>;

// Random tangent vector of G: rotation angle uniform in [0, max_angle) (SO2: in
// (−max_angle, max_angle)), translation part (if any) uniform in [−1, 1].
template <typename G>
typename G::Tangent tangent(std::mt19937_64& rng, double max_angle) {
  using T = typename G::Tangent;
  if constexpr (G::Point::RowsAtCompileTime == 2) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    T xi;
    for (Eigen::Index i = 0; i < xi.size(); ++i) xi(i) = u(rng);
    xi(xi.size() - 1) *= max_angle;
    return xi;
  } else {
    return random_tangent<T>(rng, max_angle);
  }
}
TYPED_TEST_SUITE(GroupProperties, Families);

constexpr int kSamples = 10000;
// Entries of R and t are O(1); a dozen roundings per operation chain, so 1e-12 (≈ 4500 ulps)
// is a generous bound that still catches any wrong term.
constexpr double kTol = 1e-12;

TYPED_TEST(GroupProperties, ExpOfLogIsIdentityOnRandomElements) {
  using G = typename TypeParam::template G<double>;
  std::mt19937_64 rng(20261123);
  for (int i = 0; i < kSamples; ++i) {
    const G g = G::sample(rng);
    ASSERT_LE(matrix_distance(G::exp(g.log()), g), kTol) << "sample " << i;
  }
}

TYPED_TEST(GroupProperties, LogOfExpIsIdentityBelowPi) {
  using G = typename TypeParam::template G<double>;
  using T = typename G::Tangent;
  std::mt19937_64 rng(7);
  for (int i = 0; i < kSamples; ++i) {
    const T xi = tangent<G>(rng, 3.1);
    ASSERT_LE((G::exp(xi).log() - xi).cwiseAbs().maxCoeff(), kTol) << "xi " << xi.transpose();
  }
}

TYPED_TEST(GroupProperties, InverseAndAssociativity) {
  using G = typename TypeParam::template G<double>;
  std::mt19937_64 rng(11);
  for (int i = 0; i < kSamples; ++i) {
    const G a = G::sample(rng), b = G::sample(rng), c = G::sample(rng);
    ASSERT_LE(matrix_distance(a * a.inverse(), G::identity()), kTol);
    ASSERT_LE(matrix_distance(a.inverse() * a, G::identity()), kTol);
    ASSERT_LE(matrix_distance((a * b) * c, a * (b * c)), kTol);
    ASSERT_LE((a.matrix() * b.matrix() - (a * b).matrix()).cwiseAbs().maxCoeff(), kTol);
  }
}

TYPED_TEST(GroupProperties, ActionMatchesHomogeneousMatrix) {
  using G = typename TypeParam::template G<double>;
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < kSamples; ++i) {
    const G g = G::sample(rng);
    using P = typename G::Point;
    constexpr int d = P::RowsAtCompileTime;
    P p;
    for (int k = 0; k < d; ++k) p(k) = u(rng);
    Eigen::Matrix<double, d + 1, 1> ph;
    ph << p, 1.0;
    ph = g.homogeneous() * ph;
    ASSERT_LE(((g * p) - ph.template head<d>()).cwiseAbs().maxCoeff(), kTol);
  }
}

TYPED_TEST(GroupProperties, AdjointConjugatesExp) {
  using G = typename TypeParam::template G<double>;
  using T = typename G::Tangent;
  std::mt19937_64 rng(17);
  for (int i = 0; i < kSamples; ++i) {
    const G g = G::sample(rng);
    const T xi = tangent<G>(rng, 3.0);
    const T ad_xi = g.adjoint() * xi;
    ASSERT_LE(matrix_distance(g * G::exp(xi) * g.inverse(), G::exp(ad_xi)), kTol);
    // Same identity at the Lie-algebra level: g hat(ξ) g⁻¹ = hat(Ad ξ).
    ASSERT_LE((g.matrix() * G::hat(xi) * g.inverse().matrix() - G::hat(ad_xi)).cwiseAbs().maxCoeff(),
              kTol);
    ASSERT_EQ(G::vee(G::hat(xi)), xi);  // exact: vee reads back the stored entries
  }
}

TYPED_TEST(GroupProperties, JacobiansMatchCentralDifferences) {
  using G = typename TypeParam::template G<double>;
  using T = typename G::Tangent;
  constexpr int n = T::RowsAtCompileTime;
  std::mt19937_64 rng(19);
  for (int i = 0; i < 500; ++i) {
    const T xi = tangent<G>(rng, 3.0);
    const auto Jr = G::right_jacobian(xi);
    const auto Jl = G::left_jacobian(xi);
    const G X = G::exp(xi);
    // Central difference with h = 1e-5: truncation O(h²) ≈ 1e-10 times third derivatives of
    // order 1, rounding ≈ 1e-16/1e-5 = 1e-11; 1e-8 bounds both with margin.
    const double h = 1e-5;
    for (int j = 0; j < n; ++j) {
      const T e = T::Unit(j) * h;
      const T right = ((X.inverse() * G::exp(xi + e)).log() - (X.inverse() * G::exp(xi - e)).log()) / (2 * h);
      const T left = ((G::exp(xi + e) * X.inverse()).log() - (G::exp(xi - e) * X.inverse()).log()) / (2 * h);
      ASSERT_LE((right - Jr.col(j)).cwiseAbs().maxCoeff(), 1e-8) << "xi " << xi.transpose();
      ASSERT_LE((left - Jl.col(j)).cwiseAbs().maxCoeff(), 1e-8) << "xi " << xi.transpose();
    }
    // Exact identities: Jl = Ad_exp(ξ) Jr, and the inverses.
    using M = Eigen::Matrix<double, n, n>;
    ASSERT_LE((Jl - X.adjoint() * Jr).cwiseAbs().maxCoeff(), 1e-12);
    ASSERT_LE((G::right_jacobian_inverse(xi) * Jr - M::Identity()).cwiseAbs().maxCoeff(), 1e-11);
    ASSERT_LE((G::left_jacobian_inverse(xi) * Jl - M::Identity()).cwiseAbs().maxCoeff(), 1e-11);
  }
}

TYPED_TEST(GroupProperties, RightJacobianMatchesAutoDiff) {
  using G = typename TypeParam::template G<double>;
  using Gad = typename TypeParam::template G<AutoDiffXd>;
  using T = typename G::Tangent;
  using Tad = typename Gad::Tangent;
  constexpr int n = T::RowsAtCompileTime;
  std::mt19937_64 rng(23);
  for (int i = 0; i < 200; ++i) {
    const T xi = tangent<G>(rng, 3.0);
    Tad xi_const, xi_var;
    for (int k = 0; k < n; ++k) {
      xi_const(k) = AutoDiffXd(xi(k), Eigen::VectorXd::Zero(n));
      xi_var(k) = AutoDiffXd(xi(k), n, k);
    }
    // d/dδ log(exp(ξ)⁻¹ exp(ξ + δ)) at δ = 0 is Jr(ξ) by definition.
    const Tad d = (Gad::exp(xi_const).inverse() * Gad::exp(xi_var)).log();
    const auto Jr = G::right_jacobian(xi);
    for (int r = 0; r < n; ++r) {
      ASSERT_EQ(d(r).derivatives().size(), n);
      // Both sides are closed forms of the same derivative; 1e-12 allows for ~100 roundings.
      ASSERT_LE((d(r).derivatives().transpose() - Jr.row(r)).cwiseAbs().maxCoeff(), 1e-12);
    }
  }
}

TYPED_TEST(GroupProperties, InterpolationEndsAndMidpoint) {
  using G = typename TypeParam::template G<double>;
  std::mt19937_64 rng(29);
  for (int i = 0; i < 1000; ++i) {
    const G a = G::sample(rng), b = G::sample(rng);
    ASSERT_LE(matrix_distance(a.interpolate(b, 0.0), a), kTol);
    ASSERT_LE(matrix_distance(a.interpolate(b, 1.0), b), 1e-11);
    // The midpoint m satisfies (a⁻¹ m)² = a⁻¹ b.
    const G m = a.interpolate(b, 0.5);
    const G half = a.inverse() * m;
    ASSERT_LE(matrix_distance(half * half, a.inverse() * b), 1e-11);
  }
}

TEST(GroupDimensions, MatchFormulas) {
  EXPECT_EQ(SO2d::kDim, 2 * 1 / 2);  // n(n−1)/2
  EXPECT_EQ(SE2d::kDim, 2 * 3 / 2);  // n(n+1)/2
  EXPECT_EQ(SO3d::kDim, 3 * 2 / 2);
  EXPECT_EQ(SE3d::kDim, 3 * 4 / 2);
  for (int n = 2; n <= 8; ++n) {
    EXPECT_EQ(SOn::identity(n).dimension(), n * (n - 1) / 2);
    EXPECT_EQ(SEn::identity(n).dimension(), n * (n + 1) / 2);
    EXPECT_EQ(SOn::n_from_dimension(n * (n - 1) / 2), n);
    EXPECT_EQ(SEn::n_from_dimension(n * (n + 1) / 2), n);
  }
}

}  // namespace
}  // namespace rigid
