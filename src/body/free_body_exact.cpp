#include "rigid/body/free_body_exact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

// Double in, double out: no internal promotion to long double (x87 is slow).
#define BOOST_MATH_PROMOTE_DOUBLE_POLICY false
#include <boost/math/special_functions/ellint_rf.hpp>
#include <boost/math/special_functions/ellint_rj.hpp>

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"

namespace rigid::body {

namespace {
// Moments closer than this (relative) are treated as equal: the elliptic form
// would divide by their difference.
constexpr double kEqualMoments = 1e-14;
}  // namespace

FreeBodyExact::FreeBodyExact(const Eigen::Vector3d& I_B, const Eigen::Vector3d& w0_B) {
  if (auto report = check_rotational_moments(I_B)) RIGID_THROW("{}", *report);
  RIGID_REQUIRE(w0_B.allFinite(), "initial body angular velocity must be finite, got {}",
                rigid::to_string(w0_B.transpose()));
  // Sort ascending; an odd permutation is improper, compensated by ω → −ω
  // (Euler's equations are quadratic in ω, so −ω solves the mirrored system).
  std::array<int, 3> p{0, 1, 2};
  std::sort(p.begin(), p.end(), [&](int a, int b) { return I_B(a) < I_B(b); });
  perm_ = p;
  int inversions = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j) inversions += p[i] > p[j] ? 1 : 0;
  flip_ = inversions % 2 == 0 ? 1.0 : -1.0;
  for (int s = 0; s < 3; ++s) {
    I_sorted_(s) = I_B(p[s]);
    w0_sorted_(s) = flip_ * w0_B(p[s]);
  }
  const Eigen::Vector3d& I = I_sorted_;
  const Eigen::Vector3d& w = w0_sorted_;
  energy_ = 0.5 * (I.array() * w.array().square()).sum();
  const double L2 = (I.array().square() * w.array().square()).sum();
  L_norm_ = std::sqrt(L2);
  RIGID_REQUIRE(std::isfinite(energy_) && std::isfinite(L2),
                "initial body angular velocity {} rad/s with principal moments {} kg·m² overflows: "
                "kinetic energy {} J, |L|² = {} (kg·m²/s)²; expected a motion whose energy and "
                "|L|² are finite doubles",
                rigid::to_string(w0_B.transpose()), rigid::to_string(I_B.transpose()), energy_, L2);

  const bool eq12 = I(1) - I(0) <= kEqualMoments * I(2);
  const bool eq23 = I(2) - I(1) <= kEqualMoments * I(2);
  if ((eq12 && eq23) || L2 == 0.0) {
    case_ = FreeBodyCase::kSphere;
    return;
  }
  if (eq12 || eq23) {
    case_ = FreeBodyCase::kSymmetric;
    // Axis 3 symmetric (I1 = I2): (ω1, ω2) turns at c = (I3 − I1) ω3 / I1.
    // Axis 1 symmetric (I2 = I3): (ω2, ω3) turns at c = (I1 − I3) ω1 / I3.
    if (eq12) {
      sym_axis_ = 2;
      Omega_ = (I(2) - I(0)) * w(2) / I(0);
    } else {
      sym_axis_ = 0;
      Omega_ = (I(0) - I(2)) * w(0) / I(2);
    }
    phase_rate_ = std::abs(Omega_);
    return;
  }
  case_ = FreeBodyCase::kAsymmetric;
  // A permanent rotation (ω ∥ L exactly, e.g. ω along one principal axis): ω is
  // constant. Caught here because on the unstable middle axis the elliptic form with
  // a rounded k < 1 would start a flip that the given data do not contain.
  if (w.cross(I.cwiseProduct(w)).isZero(0.0)) {
    steady_ = true;
    return;
  }
  // [Landau1976, §37, eq. 37.10]: for L² > 2E I2, ω1 ∝ cn, ω2 ∝ sn, ω3 ∝ dn;
  // for L² < 2E I2 the roles of axes 1 and 3 swap.
  // The differences below are sums of terms of one sign, free of cancellation:
  //   A = 2E I_d − L² = Σ I_i (I_d − I_i) ω_i²,  B = L² − 2E I_c = Σ I_i (I_i − I_c) ω_i²,
  //   D = L² − 2E I2 = Σ I_i (I_i − I2) ω_i²   (D = 0 on the separatrix).
  const auto quad = [&](double Iref) {
    double acc = 0;
    for (int i = 0; i < 3; ++i) acc += I(i) * (I(i) - Iref) * w(i) * w(i);
    return acc;
  };
  const double D = quad(I(1));
  const bool about3 = D >= 0.0;
  axis_cn_ = about3 ? 0 : 2;
  axis_dn_ = about3 ? 2 : 0;
  const double Ic = I(axis_cn_), I2 = I(1), Id = I(axis_dn_);
  const double A = -quad(Id);  // same sign as (Id − Ic)
  const double B = quad(Ic);   // same sign as (Id − Ic)
  a_cn_ = std::sqrt(std::max(0.0, A / (Ic * (Id - Ic))));
  a_sn_ = std::sqrt(std::max(0.0, A / (I2 * (Id - I2))));
  a_dn_ = std::sqrt(std::max(0.0, B / (Id * (Id - Ic))));
  lambda_ = std::sqrt(std::max(0.0, (Id - I2) * B / (Ic * I2 * Id)));
  phase_rate_ = lambda_;
  // k² = (I2 − Ic) A / ((Id − I2) B) and, by the identity (Id − I2)B − (I2 − Ic)A
  // = (Id − Ic) D, k'² = 1 − k² = (Id − Ic) D / ((Id − I2) B): k' keeps full relative
  // precision near the separatrix.
  k2_ = std::clamp((I2 - Ic) * A / ((Id - I2) * B), 0.0, 1.0);
  kc2_ = std::clamp((Id - Ic) * D / ((Id - I2) * B), 0.0, 1.0);
  k_ = k2_ < 0.5 ? std::sqrt(k2_) : std::sqrt(1.0 - kc2_);
  // Signs from Euler's equations (substitute the ansatz into I_c ω̇_c and I_2 ω̇_2):
  // ω2 and ω_d carry the same sign s = sign(ω_d(0)) in both cases.
  sign_ = w(axis_dn_) >= 0.0 ? 1.0 : -1.0;
  // Initial amplitude φ0: cos φ0 = ω_c/a_c, sin φ0 = ω2/(s a_2), normalised.
  double cn0 = a_cn_ > 0 ? w(axis_cn_) / a_cn_ : 1.0;
  double sn0 = a_sn_ > 0 ? w(1) / (sign_ * a_sn_) : 0.0;
  const double rho = std::hypot(sn0, cn0);
  cn0 /= rho;
  sn0 /= rho;
  // Below k'² ≈ 1e-290 the nome underflows: the orbit is the separatrix to within
  // a phase error that appears only after λt ≈ 330.
  if (kc2_ > 1e-290) {
    jacobi_ = JacobiElliptic(k2_, kc2_);
    K_ = jacobi_.K();
    // F(φ, k) = sin φ · R_F(cos²φ, 1 − k² sin²φ, 1) for |φ| ≤ π/2 [DLMF 19.25.5], with
    // 1 − k² sin²φ = cos²φ + k'² sin²φ; beyond, F(π − φ) = 2K − F(φ).
    const double F = sn0 * boost::math::ellint_rf(cn0 * cn0, cn0 * cn0 + kc2_ * sn0 * sn0, 1.0);
    u0_ = cn0 >= 0.0 ? F : std::copysign(2.0 * K_, sn0) - F;
    if (cn0 < 0.0 && sn0 == 0.0) u0_ = 2.0 * K_;
  } else {
    // Separatrix: cn u = sech u > 0, so ω_c keeps its sign; the mirror image
    // (ω_c, ω2, ω_d) → (−ω_c, −ω2, ω_d) (a half turn about axis d) covers ω_c < 0.
    // u0 = F(φ0, 1) = asinh(tan φ0), clamped where sech u underflows anyway.
    K_ = 0.0;
    k_ = 1.0;
    if (cn0 < 0.0) {
      sep_sign_ = -1.0;
      sn0 = -sn0;
      cn0 = -cn0;
    }
    u0_ = std::clamp(std::asinh(sn0 / cn0), -700.0, 700.0);
  }
}

FreeBodyExact::Phase FreeBodyExact::phase(double u, const JacobiElliptic::ThetaShift* shift) const {
  Phase ph;
  if (K_ == 0.0) {
    // Separatrix (k = 1): sn = tanh, cn = dn = sech, no period to reduce by.
    ph.u_r = u;
    ph.dn = 1.0 / std::cosh(u);
    ph.sn = sep_sign_ * std::tanh(u);
    ph.cn = sep_sign_ * ph.dn;
    return ph;
  }
  // u = u_r + 2K j with |u_r| ≤ K; fma rounds u − 2K j once.
  ph.half_periods = std::nearbyint(u / (2.0 * K_));
  ph.u_r = std::fma(-2.0 * K_, ph.half_periods, u);
  if (shift != nullptr) {
    jacobi_.eval(ph.u_r, *shift, ph.sn, ph.cn, ph.dn, ph.theta_arg);
  } else {
    jacobi_.eval(ph.u_r, ph.sn, ph.cn, ph.dn);
  }
  // sn(u + 2K) = −sn u, cn(u + 2K) = −cn u, dn(u + 2K) = dn u [DLMF 22.4.3].
  // j odd ⇔ j/2 is not an integer (j/2 is exact: j is an integer-valued double; cheaper
  // than fmod, which loops on x87 fprem).
  const double half = 0.5 * ph.half_periods;
  if (half != std::floor(half)) {
    ph.sn = -ph.sn;
    ph.cn = -ph.cn;
  }
  return ph;
}

Eigen::Vector3d FreeBodyExact::omega_sorted_at(const Phase& ph) const {
  Eigen::Vector3d out;
  out(axis_cn_) = a_cn_ * ph.cn;
  out(1) = sign_ * a_sn_ * ph.sn;
  out(axis_dn_) = sign_ * a_dn_ * ph.dn;
  return out;
}

Eigen::Vector3d FreeBodyExact::omega_sorted(double t) const {
  const Eigen::Vector3d& w = w0_sorted_;
  switch (case_) {
    case FreeBodyCase::kSphere:
      return w;
    case FreeBodyCase::kSymmetric: {
      const double c = std::cos(Omega_ * t), s = std::sin(Omega_ * t);
      Eigen::Vector3d out = w;
      if (sym_axis_ == 2) {
        out(0) = c * w(0) - s * w(1);
        out(1) = s * w(0) + c * w(1);
      } else {
        out(1) = c * w(1) - s * w(2);
        out(2) = s * w(1) + c * w(2);
      }
      return out;
    }
    case FreeBodyCase::kAsymmetric:
      break;
  }
  if (steady_) return w;
  return omega_sorted_at(phase(lambda_ * t + u0_));
}

void FreeBodyExact::require_time(const char* function, double t) const {
  RIGID_REQUIRE_AS(function, std::isfinite(t), "time t = {} s is not finite, expected a finite time",
                   t);
  RIGID_REQUIRE_AS(function, std::abs(phase_rate_ * t) <= kMaxAngle,
                   "time t = {} s is too far: the phase of ω(t) there is {:.6g} rad, expected at "
                   "most kMaxAngle = {:.0e} rad (beyond, rounding has lost the fraction of a "
                   "period), i.e. |t| <= {:.6g} s",
                   t, phase_rate_ * t, kMaxAngle, max_time());
}

double FreeBodyExact::max_time() const {
  return phase_rate_ > 0.0 ? kMaxAngle / phase_rate_ : std::numeric_limits<double>::infinity();
}

Eigen::Vector3d FreeBodyExact::omega_body(double t) const {
  require_time("omega_body", t);
  const Eigen::Vector3d ws = omega_sorted(t);
  Eigen::Vector3d out;
  for (int s = 0; s < 3; ++s) out(perm_[s]) = flip_ * ws(s);
  return out;
}

double FreeBodyExact::period() const {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  switch (case_) {
    case FreeBodyCase::kSphere:
      return kInf;
    case FreeBodyCase::kSymmetric:
      return Omega_ == 0.0 ? kInf : 2.0 * std::numbers::pi / std::abs(Omega_);
    case FreeBodyCase::kAsymmetric:
      if (steady_ || K_ == 0.0 || lambda_ == 0.0) return kInf;
      return 4.0 * K_ / lambda_;
  }
  return kInf;
}

}  // namespace rigid::body

// ---------------------------------------------------------------------------
// FreeBodyMotion

namespace rigid::body {

namespace {
// R_C(1, 1 + e) = atan(√e)/√e (e > 0), atanh(√−e)/√−e (−1 < e < 0) [DLMF, §19.2(iv)];
// for |e| < 1e-3 its Maclaurin series Σ (−e)^j/(2j + 1), first dropped term e⁶/13 < 1e-19.
double carlson_rc1p(double e) {
  if (std::abs(e) < 1e-3)
    return 1.0 + e * (-1.0 / 3.0 + e * (1.0 / 5.0 + e * (-1.0 / 7.0 + e * (1.0 / 9.0 - e / 11.0))));
  if (e > 0.0) {
    const double r = std::sqrt(e);
    return std::atan(r) / r;
  }
  const double r = std::sqrt(-e);
  return std::atanh(r) / r;
}

// R_F(x, y, z) and R_J(x, y, z, p) (x, y, z ≥ 0, at most one 0; p > 0) from one shared
// duplication loop (Carlson's algorithm) [DLMF, §19.36(i)]: both integrals move x, y, z to
//   x ← (x + λ)/4, …,  λ = √x√y + √y√z + √z√x,  and R_J also p ← (p + λ)/4,
// so the square roots of x, y, z serve both. R_J collects 6 Σ 4⁻ᵐ R_C(1, 1 + e_m)/d_m with
// d_m = (√p + √x)(√p + √y)(√p + √z), e_m = 4^{−3m} δ/d_m², δ = (p − x)(p − y)(p − z).
// The loop stops once 4⁻ᵐ·max|A0 − ·| ≤ 3e-3 |A_m| (A = the mean of the arguments): the
// 5th-order series that ends both is then exact to (3e-3)⁶ ≈ 1e-15 relative; ≈ 4–5
// iterations of 4 square roots here, where Boost runs two separate loops with an R_C
// (atan or log) in every iteration of R_J.
void carlson_rf_rj(double x, double y, double z, double p, double& rf, double& rj) {
  double AF = (x + y + z) / 3.0;
  double AJ = (x + y + z + 2.0 * p) / 5.0;
  const double delta = (p - x) * (p - y) * (p - z);
  const double dev = std::max({std::abs(AJ - x), std::abs(AJ - y), std::abs(AJ - z), std::abs(AJ - p),
                               std::abs(AF - x), std::abs(AF - y), std::abs(AF - z)}) /
                     3e-3;
  double fac = 1.0, sum = 0.0, q = dev;
  while (q > std::min(AF, AJ)) {
    const double sx = std::sqrt(x), sy = std::sqrt(y), sz = std::sqrt(z), sp = std::sqrt(p);
    const double lambda = sx * sy + sy * sz + sz * sx;
    const double d = (sp + sx) * (sp + sy) * (sp + sz);
    sum += fac / d * carlson_rc1p(fac * fac * fac * delta / (d * d));
    x = 0.25 * (x + lambda);
    y = 0.25 * (y + lambda);
    z = 0.25 * (z + lambda);
    p = 0.25 * (p + lambda);
    AF = 0.25 * (AF + lambda);
    AJ = 0.25 * (AJ + lambda);
    fac *= 0.25;
    q *= 0.25;
  }
  {
    // R_F = A^{−1/2} (1 − E2/10 + E3/14 + E2²/24 − 3 E2 E3/44), X = (A − x)/A, Y, Z = −X − Y,
    // E2 = XY − Z², E3 = XYZ [DLMF, §19.36(i)]
    const double X = (AF - x) / AF, Y = (AF - y) / AF, Z = -(X + Y);
    const double E2 = X * Y - Z * Z, E3 = X * Y * Z;
    rf = (1.0 - E2 / 10.0 + E3 / 14.0 + E2 * E2 / 24.0 - 3.0 * E2 * E3 / 44.0) / std::sqrt(AF);
  }
  {
    // R_J = 4⁻ᴹ A^{−3/2} (1 − 3E2/14 + E3/6 + 9E2²/88 − 3E4/22 − 9E2E3/52 + 3E5/26) + 6 Σ,
    // X, Y, Z = (A − ·)/A, P = −(X + Y + Z)/2, E2 = XY + XZ + YZ − 3P², E3 = XYZ + 2E2 P + 4P³,
    // E4 = (2XYZ + E2 P + 3P³) P, E5 = XYZ P² [DLMF, §19.36(i)]
    const double X = (AJ - x) / AJ, Y = (AJ - y) / AJ, Z = (AJ - z) / AJ, P = -0.5 * (X + Y + Z);
    const double xyz = X * Y * Z, P2 = P * P;
    const double E2 = X * Y + X * Z + Y * Z - 3.0 * P2;
    const double E3 = xyz + 2.0 * E2 * P + 4.0 * P * P2;
    const double E4 = (2.0 * xyz + E2 * P + 3.0 * P * P2) * P;
    const double E5 = xyz * P2;
    const double series = 1.0 - 3.0 * E2 / 14.0 + E3 / 6.0 + 9.0 * E2 * E2 / 88.0 - 3.0 * E4 / 22.0 -
                          9.0 * E2 * E3 / 52.0 + 3.0 * E5 / 26.0;
    rj = fac * series / (AJ * std::sqrt(AJ)) + 6.0 * sum;
  }
}

// The principal axes R_BP of a body's inertia about its COM (rigid::MassProperties).
SO3d principal_rotation(const MassProperties& mass_B) {
  return SO3d::from_matrix(mass_B.principal_axes().R_BP);
}
}  // namespace

FreeBodyMotion::FreeBodyMotion(const Eigen::Vector3d& I_B, const SO3d& R0_WB, const Eigen::Vector3d& w0_B)
    : FreeBodyMotion(I_B, R0_WB, w0_B, SO3d::identity()) {}

FreeBodyMotion::FreeBodyMotion(const MassProperties& mass_B, const SO3d& R0_WB, const Eigen::Vector3d& w0_B)
    : FreeBodyMotion(mass_B.principal_axes().moments, R0_WB * principal_rotation(mass_B),
                     principal_rotation(mass_B).inverse() * w0_B, principal_rotation(mass_B)) {}

FreeBodyMotion::FreeBodyMotion(const Eigen::Vector3d& I_B, const SO3d& R0_WB, const Eigen::Vector3d& w0_B,
                               const SO3d& R_BP)
    : R_BP_(R_BP), omega_(I_B, w0_B) {
  // (in this constructor B is the principal frame; R_BP_ turns the results back into the
  // user's body frame for the MassProperties form)
  q0_WB_ = R0_WB;
  L_W_ = q0_WB_ * I_B.cwiseProduct(w0_B);
  inv_L_ = omega_.L_norm_ > 0.0 ? 1.0 / omega_.L_norm_ : 0.0;

  // Sorted axes from the user's: v_S(s) = flip · v_B(perm[s]), a proper rotation
  // (an odd permutation has det −1 and flip = −1 restores det +1 in 3D).
  Eigen::Matrix3d R_SB = Eigen::Matrix3d::Zero();
  for (int s = 0; s < 3; ++s) R_SB(s, omega_.perm_[s]) = omega_.flip_;
  RIGID_ASSERT(std::abs(R_SB.determinant() - 1.0) < 1e-12);
  q_SB_ = SO3d::from_matrix(R_SB);

  const FreeBodyExact& e = omega_;
  const Eigen::Vector3d& I = e.I_sorted_;
  const Eigen::Vector3d& w = e.w0_sorted_;
  const double L = e.L_norm_;
  switch (e.case_) {
    case FreeBodyCase::kSphere:
      uniform_ = true;
      return;
    case FreeBodyCase::kSymmetric: {
      // (a, b, d) cyclic with d the symmetry axis; ψ̇ = |L|/I_t [Landau1976, §33].
      abd_ = e.sym_axis_ == 2 ? std::array<int, 3>{0, 1, 2} : std::array<int, 3>{1, 2, 0};
      const double Lt2 = std::pow(I(abd_[0]) * w(abd_[0]), 2) + std::pow(I(abd_[1]) * w(abd_[1]), 2);
      if (Lt2 == 0.0) {  // spin about the symmetry axis: permanent rotation
        uniform_ = true;
        return;
      }
      psi_rate_ = L / I(abd_[0]);
      break;
    }
    case FreeBodyCase::kAsymmetric: {
      if (e.steady_) {
        uniform_ = true;
        return;
      }
      abd_ = e.axis_dn_ == 2 ? std::array<int, 3>{0, 1, 2} : std::array<int, 3>{1, 2, 0};
      const double Ic = I(e.axis_cn_), I2 = I(1), Id = I(e.axis_dn_);
      // ψ̇ = |L|(2E − L_d²/I_d)/(|L|² − L_d²) with L_d² = I_d² a_d² (1 − k² sn²) is
      // |L|/I_d + |L|(I_d − I_c)/(I_c I_d) / (1 − n sn²) after partial fractions
      // [Landau1976, eq. 37.16; Celledoni2008, eq. 2.14]; ∫ du/(1 − n sn²u) = Π(n; am u, k).
      psi_rate_ = L / Id;
      pi_coef_ = L * (Id - Ic) / (Ic * Id * e.lambda_);
      n_ = -Id * (I2 - Ic) / (Ic * (Id - I2));
      // Π(n, k) = K + (n/3) R_J(0, k'², 1, 1 − n) [DLMF 19.25.2].
      Pi_complete_ =
          e.K_ > 0.0 ? e.K_ + n_ / 3.0 * boost::math::ellint_rj(0.0, e.kc2_, 1.0, 1.0 - n_) : 0.0;
      if (e.K_ > 0.0) {
        // Theta form of Π for n = −m < 0 [DLMF, §22.16(iii); Celledoni2008, §2]. Jacobi's
        // Zeta Z(u) = d/du ln Θ(u), Θ(u) = θ4(πu/(2K)) [DLMF 22.16.32], obeys the addition
        // formula Z(u − a) − Z(u + a) + 2Z(a) = 2k² sn a cn a dn a sn²u / (1 − k² sn²a sn²u);
        // integrating over [0, u] (Θ is even),
        //   ∫₀ᵘ sn²v dv / (1 − k² sn²a sn²v) = [u Z(a) + ½ ln(Θ(u − a)/Θ(u + a))] / (k² sn a cn a dn a).
        // Choose a with k² sn²a = n: since n < 0, a = iβ with sn(iβ, k) = i sc(β, k'),
        // cn = nc(β, k'), dn = dc(β, k') [DLMF 22.6.12], i.e. tan am(β, k') = √m/k. Then
        //   Π(n; am u, k) = u + n ∫₀ᵘ sn²/(1 − n sn²) = u (1 − c Z_i) + c · arg Θ(u + iβ),
        // Z(iβ) = i Z_i, c = sn cn/dn (β, k'), as Θ(u − iβ) is the conjugate of Θ(u + iβ).
        // arg Θ(K + iβ) = 0 (JacobiElliptic::ThetaShift), so the slope 1 − c Z_i is
        // Π(n, k)/K and no Zeta function is needed. With tan φ = √m/k:
        //   c = sin φ cos φ / √(1 − k'² sin²φ) = √(m / ((k² + m)(1 + m))),
        //   β = F(φ, k') = sin φ R_F(cos²φ, 1 − k'² sin²φ, 1) = √m R_F(k², k²(1 + m), k² + m)
        // [DLMF 19.25.5] (R_F homogeneous of degree −½; every argument a sum of positives).
        const double m = -n_, k2 = e.k2_;
        theta_coef_ = std::sqrt(m / ((k2 + m) * (1.0 + m)));
        const double beta = std::sqrt(m) * boost::math::ellint_rf(k2, k2 * (1.0 + m), k2 + m);
        theta_shift_ = e.jacobi_.theta_shift(beta);
        Pi_slope_ = Pi_complete_ / e.K_;
      }
      Pi_u0_ = elliptic_pi(e.phase(e.u0_, &theta_shift_));
      Pi_u0_carlson_ = elliptic_pi_carlson(e.phase(e.u0_));
      break;
    }
  }
  // M = R_WS(0) Q(0): world from the frame whose e3 is L.
  q_M_ = q0_WB_ * q_SB_.inverse() * q_Q(w);
  Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
  for (int c = 0; c < 3; ++c) P(abd_[c], c) = 1.0;
  q_PS_SB_ = SO3d::from_matrix(P.transpose()) * q_SB_;
}

namespace {
// Separatrix: with s = sin θ, Π(n; φ, 1) = ∫ ds / ((1 + m s²)(1 − s²))
//   = (atanh s + √m atan(√m s)) / (1 + m), and s = tanh u, atanh s = u.
double elliptic_pi_separatrix(double m, double u) {
  const double rm = std::sqrt(m);
  return (u + rm * std::atan(rm * std::tanh(u))) / (1.0 + m);
}
}  // namespace

double FreeBodyMotion::elliptic_pi(const FreeBodyExact::Phase& ph) const {
  if (omega_.K_ == 0.0) return elliptic_pi_separatrix(-n_, ph.u_r);
  // Π(n; am u, k) = 2j Π(n, k) + u_r Π(n, k)/K + c arg Θ(u_r + iβ), u = u_r + 2jK (the
  // derivation is in the constructor): one atan2 on the multiple angles of sn, cn, dn.
  return 2.0 * ph.half_periods * Pi_complete_ + Pi_slope_ * ph.u_r + theta_coef_ * ph.theta_arg;
}

double FreeBodyMotion::elliptic_pi_carlson(const FreeBodyExact::Phase& ph) const {
  if (omega_.K_ == 0.0) return elliptic_pi_separatrix(-n_, ph.u_r);
  // Reduced u_r ∈ [−K, K] has φ_r = am u_r ∈ [−π/2, π/2], sin φ_r = sn u_r,
  // cos φ_r = cn u_r ≥ 0, √(1 − k² sin²φ_r) = dn u_r, and [DLMF 19.25.14]
  //   Π(n; φ, k) = s R_F(c², Δ², 1) + (n/3) s³ R_J(c², Δ², 1, 1 − n s²).
  // Π gains 2Π(n, k) per half period (am(u + 2K) = am u + π).
  const bool odd = std::fmod(ph.half_periods, 2.0) != 0.0;
  const double s = odd ? -ph.sn : ph.sn;
  const double c2 = ph.cn * ph.cn, d2 = ph.dn * ph.dn;
  double rf = 0, rj = 0;
  carlson_rf_rj(c2, d2, 1.0, 1.0 - n_ * s * s, rf, rj);
  const double incomplete = s * rf + n_ / 3.0 * s * s * s * rj;
  return 2.0 * ph.half_periods * Pi_complete_ + incomplete;
}

SO3d FreeBodyMotion::q_Q(const Eigen::Vector3d& w_S) const {
  // Columns in sorted coordinates: (l_b/s, −l_a/s, 0), (l_a l_d/s, l_b l_d/s, −s), l
  // in the (a, b, d) components; s = √(l_a² + l_b²) > 0 off permanent rotations.
  const Eigen::Vector3d l = omega_.I_sorted_.cwiseProduct(w_S) / omega_.L_norm_;
  const int a = abd_[0], b = abd_[1], d = abd_[2];
  const double s = std::hypot(l(a), l(b));
  Eigen::Matrix3d Q = Eigen::Matrix3d::Zero();
  Q(a, 0) = l(b) / s;
  Q(b, 0) = -l(a) / s;
  Q(a, 1) = l(a) * l(d) / s;
  Q(b, 1) = l(b) * l(d) / s;
  Q(d, 1) = -s;
  Q.col(2) = l;
  // orthonormal to round-off (unit columns built from the unit l); the tolerance of from_matrix
  // is ample
  return SO3d::from_matrix(Q);
}

SO3d FreeBodyMotion::orientation(double t) const {
  omega_.require_time("orientation", t);
  const SO3d R_WP = orientation_impl(t, false);
  return R_BP_is_identity() ? R_WP : R_WP * R_BP_.inverse();
}

SO3d FreeBodyMotion::orientation_impl(double t, bool carlson) const {
  const FreeBodyExact& e = omega_;
  if (uniform_) {
    // ω constant: R_WB(t) = R_WB(0) exp(t ω̂).
    const double turn = std::abs(t) * e.w0_sorted_.norm();
    RIGID_REQUIRE_AS("orientation", turn <= kMaxAngle,
                     "time t = {} s is too far: the body has turned by {:.6g} rad there, expected "
                     "at most kMaxAngle = {:.0e} rad (beyond, rounding has lost the fraction of a "
                     "turn), i.e. |t| <= {:.6g} s",
                     t, turn, kMaxAngle, kMaxAngle / e.w0_sorted_.norm());
    return q0_WB_ * SO3d::exp(t * (q_SB_.inverse() * e.w0_sorted_));
  }
  Eigen::Vector3d w_S;
  double psi = psi_rate_ * t;
  if (e.case_ == FreeBodyCase::kSymmetric) {
    w_S = e.omega_sorted(t);
  } else {
    const double u = e.lambda_ * t + e.u0_;
    if (carlson) {
      const FreeBodyExact::Phase ph = e.phase(u);
      w_S = e.omega_sorted_at(ph);
      psi += pi_coef_ * (elliptic_pi_carlson(ph) - Pi_u0_carlson_);
    } else {
      const FreeBodyExact::Phase ph = e.phase(u, &theta_shift_);
      w_S = e.omega_sorted_at(ph);
      psi += pi_coef_ * (elliptic_pi(ph) - Pi_u0_);
    }
  }
  RIGID_REQUIRE_AS("orientation", std::abs(psi) <= kMaxAngle,
                   "time t = {} s is too far: the precession angle ψ there is {:.6g} rad, expected "
                   "at most kMaxAngle = {:.0e} rad (beyond, rounding has lost the fraction of a "
                   "turn)",
                   t, psi, kMaxAngle);
  // R_WB = M R_e3(ψ) Q(t)ᵀ R_SB, with Q = R_z(α) R_x(−θ) in the (a, b, d) axes (cos θ = l_d,
  // sin θ = s = √(l_a² + l_b²), cos α = l_b/s, sin α = −l_a/s: the columns of q_Q below), so
  // R_e3(ψ) Qᵀ = R_z(ψ) R_x(θ) R_z(−α), whose quaternion (z-x-z Euler angles) is
  //   (cos θ/2 cos((ψ − α)/2), sin θ/2 cos((ψ + α)/2), sin θ/2 sin((ψ + α)/2), cos θ/2 sin((ψ − α)/2))
  // in (a, b, d) components. The half angles come from the cosines without cancellation:
  // (cos θ/2, sin θ/2) ∝ (1 + l_d, s) for l_d ≥ 0 and ∝ (s, 1 − l_d) otherwise; the same for
  // α/2 with (s + l_b, −l_a) or (−l_a, s − l_b). This replaces building Q, converting the
  // matrix to a quaternion and one quaternion product.
  // (products with reciprocals: one division each instead of two or three; each adds at
  // most ½ ulp, and q is renormalised at the end)
  const Eigen::Vector3d l = e.I_sorted_.cwiseProduct(w_S) * inv_L_;
  const int a = abd_[0], b = abd_[1], d = abd_[2];
  // (sqrt, not hypot: the components are ≤ 2 in magnitude, nothing can overflow)
  const double s = std::sqrt(l(a) * l(a) + l(b) * l(b));
  double ct = l(d) >= 0.0 ? 1.0 + l(d) : s, st = l(d) >= 0.0 ? s : 1.0 - l(d);
  const double nt = 1.0 / std::sqrt(ct * ct + st * st);
  ct *= nt;
  st *= nt;
  double ca = l(b) >= 0.0 ? s + l(b) : -l(a), sa = l(b) >= 0.0 ? -l(a) : s - l(b);
  const double na = 1.0 / std::sqrt(ca * ca + sa * sa);
  ca *= na;
  sa *= na;
  const double cp = std::cos(0.5 * psi), sp = std::sin(0.5 * psi);
  const double c_minus = cp * ca + sp * sa, s_minus = sp * ca - cp * sa;  // (ψ − α)/2
  const double c_plus = cp * ca - sp * sa, s_plus = sp * ca + cp * sa;    // (ψ + α)/2
  // (ct, st) and (ca, sa) are unit pairs and (cp, sp) a cosine and sine: r is unit to round-off
  const SO3d r = SO3d::from_unit_quaternion(ct * c_minus, st * c_plus, st * s_plus, ct * s_minus);
  // r acts in the frame whose x, y, z are the sorted axes a, b, d: q_PS_SB_ = Pᵀ R_SB takes
  // the user's body axes there (P: x, y, z ↦ a, b, d, a cyclic relabelling).
  return (q_M_ * r * q_PS_SB_).renormalized();
}

FreeBodyState FreeBodyMotion::state(double t) const { return {orientation(t), omega_body(t)}; }

}  // namespace rigid::body
