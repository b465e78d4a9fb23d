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
///
/// The same multiple angles give the phase of Jacobi's theta function
/// Θ(u) = θ4(πu/(2K)) at a shifted argument u + iβ (β fixed, 0 < β < K'), from which
/// the incomplete elliptic integral of the third kind follows for n < 0
/// (`ThetaShift`, `eval` with a shift; [DLMF, §22.16(iii)], [Celledoni2008, §2]).

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

  /// Complete elliptic integral of the first kind of the complementary modulus,
  /// K' = K(k') = R_F(0, k², 1) (infinite for k = 0).
  [[nodiscard]] double Kc() const { return Kc_; }

  static constexpr int kTerms = 5;

  /// Coefficients of arg Θ(u + iβ) for one fixed β ∈ (0, K'), from `theta_shift(β)`.
  /// k² ≤ ½: Θ(u + iβ) = θ4(v + iw), v = πu/(2K), w = πβ/(2K), and with
  ///   cos(2n(v + iw)) = cos 2nv cosh 2nw − i sin 2nv sinh 2nw [DLMF 20.2.4]
  ///   Re = 1 + Σ re_n cos 2nv, Im = Σ im_n sin 2nv,
  ///   re_n = 2(−1)ⁿ qⁿ² cosh 2nw, im_n = −2(−1)ⁿ qⁿ² sinh 2nw (n ≥ 1).
  /// k² > ½: Jacobi's imaginary transformation θ4(z|τ) = (−iτ)^{−½} e^{−iz²/(πτ)} θ2(z/τ|−1/τ)
  /// [DLMF 20.7.32], τ = iK'/K, z = π(u + iβ)/(2K): the prefactor is real and positive, the
  /// exponential has phase −πuβ/(2KK') (= lin·u) and z/τ = x − iy, x = πβ/(2K'), y = πu/(2K'):
  ///   Re = Σ re_n cosh((2n+1)y), Im = Σ im_n sinh((2n+1)y),
  ///   re_n = q'^{n²+n} cos((2n+1)x), im_n = q'^{n²+n} sin((2n+1)x) (common q'^{¼} dropped).
  /// The strip 0 ≤ Im(·) ≤ β < K' holds no zero of Θ (they are at iK' + 2jK), Θ is real and
  /// positive on the real axis, and Im = 0 only at u ∈ {0, ±K}, where Re > 0: so
  /// atan2(Im, Re) is the continuous branch of the phase on |u| ≤ K, zero at u = 0.
  struct ThetaShift {
    std::array<double, kTerms> re{}, im{};
    double lin = 0;  // rad per unit u (imaginary transformation only)
  };
  /// Coefficients for the shift β (0 < β < K').
  /// @throws rigid::Error if β is not in (0, K').
  [[nodiscard]] ThetaShift theta_shift(double beta) const;

  /// sn, cn, dn at u, |u| ≤ K. About 40 flops, one expm1 or sincos.
  void eval(double u, double& sn, double& cn, double& dn) const {
    eval_impl<false>(u, sn, cn, dn, nullptr, nullptr);
  }
  /// sn, cn, dn at u, |u| ≤ K, and the continuous phase arg Θ(u + iβ) (rad, 0 at u = 0)
  /// for the shift `sh` = theta_shift(β): the same multiple angles, one atan2 more.
  void eval(double u, const ThetaShift& sh, double& sn, double& cn, double& dn, double& arg) const {
    eval_impl<true>(u, sn, cn, dn, &sh, &arg);
  }

 private:
  template <bool kArg>
  void eval_impl(double u, double& sn, double& cn, double& dn, const ThetaShift* sh,
                 double* arg) const {
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
      if constexpr (kArg) {
        double re = 1, im = 0;
        for (int n = 1; n < n_even_; ++n) {
          re += sh->re[n] * cm[2 * n];
          im += sh->im[n] * sm[2 * n];
        }
        *arg = std::atan2(im, re);
      }
      return;
    }
    // Powers e^{±mw} from one expm1 of |w|: with g = e^|w| − 1 ≥ 0, e^|w| = 1 + g,
    // e^{−|w|} = 1/(1 + g) and 2 sinh |w| = g + g/(1 + g) = g (2 + g)/(1 + g), a product of
    // positive factors: relative precision near u = 0 (no e^w − e^{−w} cancellation), and
    // no 1 + g cancellation for w < 0 (g would be near −1 there).
    const double g = std::expm1(std::abs(x));
    const double Eabs = 1.0 + g, Eabs_inv = 1.0 / Eabs;
    const double E = x >= 0.0 ? Eabs : Eabs_inv, Ei = x >= 0.0 ? Eabs_inv : Eabs;
    const double sinh1 = std::copysign(0.5 * g * (2.0 + g) * Eabs_inv, x), cosh1 = 0.5 * (E + Ei);
    double S = odd_[0] * sinh1, C = odd_[0] * cosh1;
    double T3 = 1, T4 = 1;
    [[maybe_unused]] double re = 0, im = 0;
    if constexpr (kArg) {
      re = sh->re[0] * cosh1;
      im = sh->im[0] * sinh1;
    }
    double Ep = E, Eip = Ei;  // e^{±mw}, m = 1
    for (int m = 2; m < 2 * std::max(n_odd_, n_even_); ++m) {
      Ep *= E;
      Eip *= Ei;
      if (m % 2 == 1) {
        const int n = (m - 1) / 2;
        if (n < n_odd_) {
          S += (n % 2 ? -0.5 : 0.5) * odd_[n] * (Ep - Eip);
          C += 0.5 * odd_[n] * (Ep + Eip);
          if constexpr (kArg) {
            re += 0.5 * sh->re[n] * (Ep + Eip);
            im += 0.5 * sh->im[n] * (Ep - Eip);
          }
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
    if constexpr (kArg) *arg = std::atan2(im, re) + sh->lin * u;
  }

  bool imaginary_ = false;
  double K_ = std::numbers::pi / 2, Kc_ = 0, scale_ = 1;
  double c_sn_ = 1, c_cn_ = 1, c_dn_ = 1;
  int n_odd_ = 1, n_even_ = 2;
  std::array<double, kTerms> odd_{}, even_{};
};

}  // namespace rigid::body
