#include "rigid/body/jacobi_elliptic.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/ellint_3.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>
#include <gtest/gtest.h>

#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid::body {
namespace {

using test::ulps;

// Moduli exactly representable as doubles, with k'² = (1 − k)(1 + k): 1 − k is exact
// for k ≥ ½ (Sterbenz), so k'² has full relative precision and both implementations
// see the same modulus.
JacobiElliptic make(double k) {
  return JacobiElliptic(k * k, k >= 0.5 ? (1.0 - k) * (1.0 + k) : 1.0 - k * k);
}

TEST(JacobiElliptic, MatchesBoostLandenImplementation) {
  // Boost.Math evaluates sn, cn, dn by the descending Landen (AGM) transformation, an
  // independent algorithm; both are accurate to a few ulps of the O(1) values, so
  // 1e-14 leaves margin for the ε-level rounding of the argument scaling.
  for (double k : {0.0, 0.1, 0.5, 0.7071067811865476, 0.75, 0.9, 0.9999, 1.0 - 0x1p-30}) {
    const JacobiElliptic jac = make(k);
    const double K = boost::math::ellint_1(k);
    EXPECT_NEAR(jac.K(), K, ulps(16, K)) << "k = " << k;
    // Quarter period in closed form [DLMF 22.5.1]: sn K = 1, cn K = 0, dn K = k'.
    double sn, cn, dn;
    jac.eval(K, sn, cn, dn);
    EXPECT_NEAR(sn, 1.0, ulps(8));
    EXPECT_NEAR(cn, 0.0, ulps(8));
    EXPECT_NEAR(dn, std::sqrt((1.0 - k) * (1.0 + k)), ulps(8));
    for (double f = -0.9375; f < 1.0; f += 0.0625) {
      const double u = f * K;
      double bcn, bdn;
      jac.eval(u, sn, cn, dn);
      const double bsn = boost::math::jacobi_elliptic(k, u, &bcn, &bdn);
      EXPECT_NEAR(sn, bsn, 1e-14) << "k = " << k << " u = " << u;
      EXPECT_NEAR(cn, bcn, 1e-14) << "k = " << k << " u = " << u;
      EXPECT_NEAR(dn, bdn, 1e-14) << "k = " << k << " u = " << u;
      // Exact identities [DLMF 22.6.1]: sn² + cn² = 1, dn² + k² sn² = 1.
      EXPECT_NEAR(sn * sn + cn * cn, 1.0, ulps(8));
      EXPECT_NEAR(dn * dn + k * k * sn * sn, 1.0, ulps(8));
    }
  }
}

TEST(JacobiElliptic, KeepsQuarterPeriodValuesNearTheSeparatrix) {
  // k'² = 1e-20 is below what k can carry in double (k rounds to 1), yet sn(K) = 1,
  // cn(K) = 0, dn(K) = k' [DLMF 22.5.1] still hold; K ≈ ln(4/k') = ln 4 + 10 ln 10.
  const double kc2 = 1e-20;
  const JacobiElliptic jac(1.0 - kc2, kc2);
  EXPECT_NEAR(jac.K(), std::log(4.0) + 10.0 * std::log(10.0), 1e-12);  // + O(k'² K)
  double sn, cn, dn;
  jac.eval(jac.K(), sn, cn, dn);
  EXPECT_NEAR(sn, 1.0, ulps(8));
  EXPECT_NEAR(cn, 0.0, ulps(8));
  EXPECT_NEAR(dn, 1e-10, 1e-10 * 1e-12);
  // Small u: sn ≈ tanh u, the separatrix limit, to O(k'²).
  jac.eval(0.5, sn, cn, dn);
  EXPECT_NEAR(sn, std::tanh(0.5), ulps(8));
  EXPECT_NEAR(cn, 1.0 / std::cosh(0.5), ulps(8));
}

// Π(n; am u, k) = u Π(n, k)/K + c arg Θ(u + iβ) (JacobiElliptic::ThetaShift), with
// k² sn²(iβ, k) = n < 0: tan am(β, k') = √m/k, c = sn cn/dn (β, k'), m = −n. β and c come
// from Boost's F and sn, cn, dn (not from the code under test).
struct ShiftedTheta {
  JacobiElliptic::ThetaShift shift;
  double c, slope;
};
ShiftedTheta shifted_theta(const JacobiElliptic& jac, double k, double n) {
  const double kc = std::sqrt((1.0 - k) * (1.0 + k));
  const double beta = boost::math::ellint_1(kc, std::atan(std::sqrt(-n) / k));
  double cn, dn;
  const double sn = boost::math::jacobi_elliptic(kc, beta, &cn, &dn);
  return {jac.theta_shift(beta), sn * cn / dn, boost::math::ellint_3(k, n) / jac.K()};
}

TEST(JacobiElliptic, ThetaPhaseGivesTheThirdKindIntegral) {
  // Reference: Boost's ellint_3(k, n, φ) (Carlson R_F, R_J), φ = am u = atan2(sn, cn) from
  // Boost's own sn, cn. Both sides are O(1) to O(K) sums of a few rounded terms; the
  // reference φ carries ≈ ε/k' of rounding that Π turns into ≈ ε/k' (dΠ/dφ ≤ 1/dn ≤ 1/k'):
  // 64 ε · max(1, |Π|) / k' covers both (measured worst about a tenth of that).
  for (double k : {0.1, 0.5, 0.7071067811865476, 0.75, 0.9, 0.9999}) {
    const JacobiElliptic jac = make(k);
    const double kc = std::sqrt((1.0 - k) * (1.0 + k));
    for (double n : {-1e-3, -0.5, -3.0, -1e3, -1e8}) {
      const ShiftedTheta st = shifted_theta(jac, k, n);
      for (double f = -1.0; f <= 1.0; f += 0.03125) {
        const double u = f * jac.K();
        double sn, cn, dn, arg, bcn, bdn;
        jac.eval(u, st.shift, sn, cn, dn, arg);
        const double bsn = boost::math::jacobi_elliptic(k, u, &bcn, &bdn);
        const double expected = boost::math::ellint_3(k, n, std::atan2(bsn, bcn));
        const double got = u * st.slope + st.c * arg;
        EXPECT_NEAR(got, expected, ulps(64, std::max(1.0, std::abs(expected)) / kc))
            << "k = " << k << " n = " << n << " u = " << u;
        // The shifted evaluation returns the same sn, cn, dn bit for bit.
        double sn0, cn0, dn0;
        jac.eval(u, sn0, cn0, dn0);
        EXPECT_EQ(sn, sn0);
        EXPECT_EQ(cn, cn0);
        EXPECT_EQ(dn, dn0);
      }
    }
  }
}

TEST(JacobiElliptic, ThetaPhaseVanishesAtZeroAndAtTheQuarterPeriod) {
  // Θ is real and positive on the real axis and Θ(±K + iβ) = θ3(iw) (or its transform) > 0,
  // so arg Θ(u + iβ) is 0 at u = 0 and u = ±K: Π(n; am K, k) = Π(n, k) = K · slope exactly.
  // Only the rounding of a few O(1) terms remains: 16 ε.
  for (double k : {0.1, 0.7071067811865476, 0.75, 0.9999, 1.0 - 0x1p-30}) {
    const JacobiElliptic jac = make(k);
    for (double beta_frac : {1e-6, 0.3, 0.9, 0.999999}) {
      const JacobiElliptic::ThetaShift sh = jac.theta_shift(beta_frac * jac.Kc());
      double sn, cn, dn, arg;
      for (double u : {0.0, jac.K(), -jac.K()}) {
        jac.eval(u, sh, sn, cn, dn, arg);
        EXPECT_NEAR(arg, 0.0, ulps(16, std::max(1.0, jac.K()))) << "k = " << k << " β/K' = " << beta_frac;
      }
      // odd in u: Θ(−u + iβ) is the conjugate of Θ(u + iβ)
      double arg_minus;
      jac.eval(0.4 * jac.K(), sh, sn, cn, dn, arg);
      jac.eval(-0.4 * jac.K(), sh, sn, cn, dn, arg_minus);
      EXPECT_NEAR(arg, -arg_minus, ulps(4, std::abs(arg)));
    }
  }
}

TEST(JacobiElliptic, RejectsBadModulus) {
  EXPECT_RIGID_ERROR(JacobiElliptic(0.5, 0.6), "k² + k'² = 1");
  EXPECT_RIGID_ERROR(JacobiElliptic(1.0, 0.0), "k'² > 0");
  const JacobiElliptic jac = make(0.5);
  EXPECT_RIGID_ERROR(static_cast<void>(jac.theta_shift(0.0)), "imaginary shift must lie in (0, K')");
  EXPECT_RIGID_ERROR(static_cast<void>(jac.theta_shift(jac.Kc())), "imaginary shift must lie in (0, K')");
}

}  // namespace
}  // namespace rigid::body
