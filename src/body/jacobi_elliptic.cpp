#include "rigid/body/jacobi_elliptic.hpp"

#include <cmath>
#include <limits>
#include <numbers>

// Double in, double out: no internal promotion to long double.
#define BOOST_MATH_PROMOTE_DOUBLE_POLICY false
#include <boost/math/special_functions/ellint_rf.hpp>

#include "rigid/common/error.hpp"

namespace rigid::body {

JacobiElliptic::JacobiElliptic(double k2, double kc2) {
  RIGID_REQUIRE(std::isfinite(k2) && std::isfinite(kc2) && k2 >= 0 && kc2 > 0 && std::abs(k2 + kc2 - 1.0) < 1e-12,
                "need k² ≥ 0 and k'² > 0 with k² + k'² = 1, got k² = {}, k'² = {}", k2, kc2);
  // K = R_F(0, k'², 1), K' = R_F(0, k², 1) [DLMF 19.25.1].
  K_ = boost::math::ellint_rf(0.0, kc2, 1.0);
  Kc_ = k2 > 0.0 ? boost::math::ellint_rf(0.0, k2, 1.0) : std::numeric_limits<double>::infinity();
  imaginary_ = k2 > 0.5;
  // k = 0 gives q = 0 (K' infinite): sn = sin, cn = cos, dn = 1.
  const double q = imaginary_ ? std::exp(-std::numbers::pi * K_ / Kc_)
                              : std::exp(-std::numbers::pi * Kc_ / K_);
  scale_ = 0.5 * std::numbers::pi / (imaginary_ ? Kc_ : K_);
  // Coefficients q^{(n+½)²} (odd, divided by the common factor q^{1/4}, which cancels
  // in every ratio and would make 0/0 at k = 0) and q^{n²} (even), n = 0..4.
  for (int n = 0; n < kTerms; ++n) {
    odd_[n] = std::pow(q, static_cast<double>(n * n + n));
    even_[n] = std::pow(q, static_cast<double>(n * n));
  }
  // Drop terms that cannot matter for |u| ≤ K: their size relative to the leading
  // one is ≤ q^{n²} (odd) or q^{n²−n} (even).
  n_odd_ = 1;
  while (n_odd_ < kTerms && std::pow(q, n_odd_ * n_odd_) > 1e-20) ++n_odd_;
  n_even_ = 2;
  while (n_even_ < kTerms && std::pow(q, n_even_ * (n_even_ - 1.0)) > 1e-20) ++n_even_;
  double t2 = 0, t3 = 1, t4 = 1;
  for (int n = 0; n < n_odd_; ++n) t2 += 2 * odd_[n];
  for (int n = 1; n < n_even_; ++n) {
    t3 += 2 * even_[n];
    t4 += (n % 2 ? -2 : 2) * even_[n];
  }
  if (imaginary_) {
    c_sn_ = t3 / t4;
    c_cn_ = 0.5 * t2 / t4;
    c_dn_ = 0.5 * t2 / t3;
  } else {
    c_sn_ = t3 / t2;
    c_cn_ = t4 / t2;
    c_dn_ = t4 / t3;
  }
}

JacobiElliptic::ThetaShift JacobiElliptic::theta_shift(double beta) const {
  RIGID_REQUIRE(std::isfinite(beta) && beta > 0.0 && beta < Kc_,
                "the imaginary shift must lie in (0, K') = (0, {}), got β = {}", Kc_, beta);
  ThetaShift sh;
  // x = πβ/(2K) (real nome) or πβ/(2K') (imaginary transformation): scale_ β either way.
  const double x = scale_ * beta;
  if (!imaginary_) {
    // re_n = 2(−1)ⁿ qⁿ² cosh 2nx, im_n = −2(−1)ⁿ qⁿ² sinh 2nx; qⁿ² e^{2nx} ≤ q^{n²−n}
    // (x < πK'/(2K)), so these terms are no larger than those of θ4(v) itself. A
    // zero qⁿ² (underflow) gives a zero term (not 0 · ∞).
    for (int n = 1; n < n_even_; ++n) {
      if (even_[n] == 0.0) continue;
      const double sgn = n % 2 ? -2.0 : 2.0;
      sh.re[n] = sgn * even_[n] * std::cosh(2.0 * n * x);
      sh.im[n] = -sgn * even_[n] * std::sinh(2.0 * n * x);
    }
  } else {
    for (int n = 0; n < n_odd_; ++n) {
      sh.re[n] = odd_[n] * std::cos((2.0 * n + 1.0) * x);
      sh.im[n] = odd_[n] * std::sin((2.0 * n + 1.0) * x);
    }
    sh.lin = -0.5 * std::numbers::pi * beta / (K_ * Kc_);
  }
  return sh;
}

}  // namespace rigid::body
