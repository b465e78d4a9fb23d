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

}  // namespace rigid::body
