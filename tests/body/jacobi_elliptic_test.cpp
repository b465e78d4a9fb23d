#include "rigid/body/jacobi_elliptic.hpp"

#include <cmath>
#include <numbers>

#include <boost/math/special_functions/ellint_1.hpp>
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

TEST(JacobiElliptic, RejectsBadModulus) {
  EXPECT_RIGID_ERROR(JacobiElliptic(0.5, 0.6), "k² + k'² = 1");
  EXPECT_RIGID_ERROR(JacobiElliptic(1.0, 0.0), "k'² > 0");
}

}  // namespace
}  // namespace rigid::body
