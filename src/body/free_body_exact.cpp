#include "rigid/body/free_body_exact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

// Double in, double out: no internal promotion to long double (x87 is slow).
#define BOOST_MATH_PROMOTE_DOUBLE_POLICY false
#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"

namespace rigid::body {

namespace {
// Moments closer than this (relative) are treated as equal: the elliptic form
// would divide by their difference.
constexpr double kEqualMoments = 1e-14;
}  // namespace

FreeBodyExact::FreeBodyExact(const Eigen::Vector3d& I_B, const Eigen::Vector3d& w0_B) {
  RIGID_REQUIRE(I_B.allFinite() && (I_B.array() > 0).all(),
                "principal moments must be finite and > 0 kg·m², got {}", rigid::to_string(I_B.transpose()));
  RIGID_REQUIRE(w0_B.allFinite(), "initial body angular velocity must be finite, got {}",
                rigid::to_string(w0_B.transpose()));
  const double tol = 1e-12 * I_B.maxCoeff();
  for (int i = 0; i < 3; ++i) {
    RIGID_REQUIRE(I_B(i) <= I_B((i + 1) % 3) + I_B((i + 2) % 3) + tol,
                  "principal moments {} violate the triangle inequality at axis {} "
                  "(I{} = {} > {}); not a physical body",
                  rigid::to_string(I_B.transpose()), i + 1, i + 1, I_B(i),
                  I_B((i + 1) % 3) + I_B((i + 2) % 3));
  }
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
  const double E2 = 2.0 * energy_;

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
    return;
  }
  case_ = FreeBodyCase::kAsymmetric;
  // [Landau1976, §37, eq. 37.10]: for L² > 2E I2, ω1 ∝ cn, ω2 ∝ sn, ω3 ∝ dn;
  // for L² < 2E I2 the roles of axes 1 and 3 swap.
  const bool about3 = L2 >= E2 * I(1);
  axis_cn_ = about3 ? 0 : 2;
  axis_dn_ = about3 ? 2 : 0;
  const double Ic = I(axis_cn_), I2 = I(1), Id = I(axis_dn_);
  const double A = E2 * Id - L2;  // same sign as (Id − Ic)
  const double B = L2 - E2 * Ic;  // same sign as (Id − Ic)
  a_cn_ = std::sqrt(std::max(0.0, A / (Ic * (Id - Ic))));
  a_sn_ = std::sqrt(std::max(0.0, A / (I2 * (Id - I2))));
  a_dn_ = std::sqrt(std::max(0.0, B / (Id * (Id - Ic))));
  lambda_ = std::sqrt(std::max(0.0, (Id - I2) * B / (Ic * I2 * Id)));
  const double k2 = (I2 - Ic) * A / ((Id - I2) * B);
  k_ = std::sqrt(std::clamp(k2, 0.0, 1.0));
  // Signs from Euler's equations (substitute the ansatz into I_c ω̇_c and I_2 ω̇_2):
  // ω2 and ω_d carry the same sign s = sign(ω_d(0)) in both cases.
  const double sd = w(axis_dn_) >= 0.0 ? 1.0 : -1.0;
  sign_ = sd;
  const double s2 = sd;
  // Initial phase: amplitude φ0 with cn u0 = ω_c/a_c, sn u0 = ω2/(s2 a_2).
  const double cn0 = a_cn_ > 0 ? w(axis_cn_) / a_cn_ : 1.0;
  const double sn0 = a_sn_ > 0 ? w(1) / (s2 * a_sn_) : 0.0;
  const double phi0 = std::atan2(sn0, cn0);
  if (k_ < 1.0) {
    u0_ = boost::math::ellint_1(k_, phi0);
  } else {
    // Separatrix: F(φ, 1) = atanh(sin φ) = asinh(tan φ), finite for |φ| < π/2.
    u0_ = std::asinh(std::tan(phi0));
  }
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
  const double u = lambda_ * t + u0_;
  double cn = 0, dn = 0;
  const double sn = boost::math::jacobi_elliptic(k_, u, &cn, &dn);
  const double s2 = sign_;
  Eigen::Vector3d out;
  out(axis_cn_) = a_cn_ * cn;
  out(1) = s2 * a_sn_ * sn;
  out(axis_dn_) = sign_ * a_dn_ * dn;
  return out;
}

Eigen::Vector3d FreeBodyExact::omega_body(double t) const {
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
      if (k_ >= 1.0 || lambda_ == 0.0) return kInf;
      return 4.0 * boost::math::ellint_1(k_) / lambda_;
  }
  return kInf;
}

}  // namespace rigid::body
