#pragma once

/// Jacobi elliptic functions sn, cn, dn of one fixed modulus, by theta-function ratios
/// with a precomputed nome [DLMF, 22.2.4–22.2.6; 20.2.1–20.2.4].
///
/// The modulus is given by both k² and k'² = 1 − k² so that a body near the separatrix
/// (k' → 0) keeps k' to full relative precision. For k² ≤ ½ the nome q = exp(−πK'/K)
/// is ≤ e^{−π} ≈ 0.043 and, with v = πu/(2K),
///   sn = θ3/θ2 · θ1(v)/θ4(v),  cn = θ4/θ2 · θ2(v)/θ4(v),  dn = θ4/θ3 · θ3(v)/θ4(v)
/// (θ_j without argument: θ_j(0)). For k² > ½ Jacobi's imaginary transformation
/// [DLMF 22.6.12] sn(u, k) = −i sc(iu, k'), cn(u, k) = nc(iu, k'), dn(u, k) = dc(iu, k')
/// uses the complementary nome q' = exp(−πK/K') ≤ 0.043 and w = πu/(2K'):
///   sn = θ3/θ4 · S/C,  cn = θ2/θ4 · θ4(iw)/(2C),  dn = θ2/θ3 · θ3(iw)/(2C),
///   S = Σ (−1)ⁿ q'^{(n+½)²} sinh((2n+1)w),  C = Σ q'^{(n+½)²} cosh((2n+1)w),
///   θ3,4(iw) = 1 + 2 Σ (±1)ⁿ q'^{n²} cosh(2nw).
/// Valid for |u| ≤ K (callers reduce u by the period); there the terms fall off at
/// least like q^{n²−n}, so a few terms reach round-off: 5 are kept, fewer when the
/// nome is tiny (terms below 1e-20 relative are dropped, which also keeps e^{mw} finite).

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace rigid::body {

/// Class invariant: coefficients of a valid modulus (checked by the constructor).
class JacobiElliptic {
 public:
  JacobiElliptic() = default;
  /// k2 = k², kc2 = k'² = 1 − k² (k2 ≥ 0, kc2 > 0), each to full relative precision.
  /// @throws rigid::Error if they are not finite, out of range or k² + k'² ≠ 1 (1e-12).
  JacobiElliptic(double k2, double kc2);

  /// Complete elliptic integral of the first kind K(k) = R_F(0, k'², 1).
  [[nodiscard]] double K() const { return K_; }

  /// sn, cn, dn at u, |u| ≤ K. About 40 flops, one exp or sincos.
  void eval(double u, double& sn, double& cn, double& dn) const {
    const double x = scale_ * u;
    if (!imaginary_) {
      // Multiple angles by the Chebyshev recurrence c_{m+1} = 2c c_m − c_{m−1}.
      const double s1 = std::sin(x), c1 = std::cos(x);
      std::array<double, 2 * kTerms> cm{}, sm{};
      cm[0] = 1;
      sm[0] = 0;
      cm[1] = c1;
      sm[1] = s1;
      const int top = 2 * std::max(n_odd_, n_even_);
      for (int m = 2; m < top; ++m) {
        cm[m] = 2 * c1 * cm[m - 1] - cm[m - 2];
        sm[m] = 2 * c1 * sm[m - 1] - sm[m - 2];
      }
      double T1 = 0, T2 = 0, T3 = 1, T4 = 1;
      for (int n = 0; n < n_odd_; ++n) {
        T1 += (n % 2 ? -odd_[n] : odd_[n]) * sm[2 * n + 1];
        T2 += odd_[n] * cm[2 * n + 1];
      }
      for (int n = 1; n < n_even_; ++n) {
        T3 += 2 * even_[n] * cm[2 * n];
        T4 += (n % 2 ? -2 : 2) * even_[n] * cm[2 * n];
      }
      sn = 2 * c_sn_ * T1 / T4;
      cn = c_cn_ * 2 * T2 / T4;
      dn = c_dn_ * T3 / T4;
      return;
    }
    // Powers e^{±mw}; sinh w from expm1 keeps relative precision near u = 0.
    const double E = std::exp(x), Ei = 1.0 / E;
    double S = 0.5 * odd_[0] * (std::expm1(x) - std::expm1(-x)), C = 0.5 * odd_[0] * (E + Ei);
    double T3 = 1, T4 = 1;
    double Ep = E, Eip = Ei;  // e^{±mw}, m = 1
    for (int m = 2; m < 2 * std::max(n_odd_, n_even_); ++m) {
      Ep *= E;
      Eip *= Ei;
      if (m % 2 == 1) {
        const int n = (m - 1) / 2;
        if (n < n_odd_) {
          S += (n % 2 ? -0.5 : 0.5) * odd_[n] * (Ep - Eip);
          C += 0.5 * odd_[n] * (Ep + Eip);
        }
      } else {
        const int n = m / 2;
        if (n < n_even_) {
          T3 += even_[n] * (Ep + Eip);
          T4 += (n % 2 ? -1.0 : 1.0) * even_[n] * (Ep + Eip);
        }
      }
    }
    // n = 1 of the even sums uses e^{±2w} (m = 2), handled in the loop above.
    sn = c_sn_ * S / C;
    cn = c_cn_ * T4 / C;
    dn = c_dn_ * T3 / C;
  }

 private:
  static constexpr int kTerms = 5;
  bool imaginary_ = false;
  double K_ = std::numbers::pi / 2, Kc_ = 0, scale_ = 1;
  double c_sn_ = 1, c_cn_ = 1, c_dn_ = 1;
  int n_odd_ = 1, n_even_ = 2;
  std::array<double, kTerms> odd_{}, even_{};
};

}  // namespace rigid::body
