#pragma once

#include <cmath>
#include <limits>
#include <random>
#include <type_traits>

#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross

#include "rigid/common/scalars.hpp"
#include "rigid/lie/angle_limit.hpp"

namespace rigid {

/// Rotation group SO(3), stored as a unit quaternion q = (w, x, y, z).
///
/// Class invariant: |q| = 1 within a few ulps, or every component NaN for the marker of a
/// diverged computation (invalid(): a time step whose state blew up returns it, so that the
/// finiteness check of rigid::integrate::march names the rotation). q and −q are the same
/// rotation; the stored sign is whatever construction produced. Tangent vectors ω ∈ R³ are rotation
/// vectors (axis · angle, radians); hat(ω) is the skew matrix with hat(ω) v = ω × v.
/// Jacobians follow [Sola2018]: exp(ω + δ) ≈ exp(ω) · exp(Jr(ω) δ) ≈ exp(Jl(ω) δ) · exp(ω).
template <typename Scalar>
class SO3 {
 public:
  using Vector3 = Eigen::Matrix<Scalar, 3, 1>;
  using Vector4 = Eigen::Matrix<Scalar, 4, 1>;
  using Matrix3 = Eigen::Matrix<Scalar, 3, 3>;
  static constexpr int kDim = 3;   ///< n(n−1)/2 with n = 3
  static constexpr int kDof = 3;
  using Tangent = Vector3;
  using Point = Vector3;

  /// The identity rotation.
  [[nodiscard]] static SO3 identity() { return SO3(Scalar(1), Scalar(0), Scalar(0), Scalar(0)); }
  /// All components NaN: the result of a step that diverged (see the class invariant).
  [[nodiscard]] static SO3 invalid() {
    const Scalar nan(std::numeric_limits<double>::quiet_NaN());
    return SO3(nan, nan, nan, nan);
  }
  /// Unit quaternion (w, x, y, z); a non-unit input is normalised.
  /// @throws rigid::Error if a component is not finite or the norm is below 1e-12.
  [[nodiscard]] static SO3 from_quaternion(const Scalar& w, const Scalar& x, const Scalar& y,
                                           const Scalar& z);
  /// The rotation of quaternion coefficients q that a time integrator carried (Runge–Kutta
  /// stages and steps: |q|² = 1 + δ drifts by the truncation error). For |δ| ≤ 1e-8 (the end
  /// of a step) one Newton step q (3 − |q|²)/2 leaves O(δ²) ≤ 1e-16, round-off, with no square
  /// root or division; a larger drift (a stage, δ = O(h²)) is normalised exactly; a
  /// non-finite or vanishing q gives invalid() (a diverged step, for the finiteness check to
  /// report).
  [[nodiscard]] static SO3 from_integrated_quaternion(const Vector4& q) {
    using std::sqrt;
    const Scalar n2 = q.squaredNorm();
    double v = 0;  // |q|² as a double (the value of an AutoDiff scalar)
    if constexpr (std::is_same_v<Scalar, double>) {
      v = n2;
    } else {
      v = n2.value();
    }
    SO3 r;
    if (std::abs(v - 1.0) <= 1e-8) {
      r.q_ = (1.5 - 0.5 * n2) * q;
    } else if (std::isfinite(v) && v > 1e-24) {
      r.q_ = q * (1.0 / sqrt(n2));
    } else {
      return invalid();
    }
    return r;
  }
  /// Unit quaternion (w, x, y, z) from input that claims to be unit: refused unless its norm is
  /// within `tolerance` of 1 (a scene's initial_quaternion, a Python argument), then normalised.
  /// @throws rigid::Error giving the norm and the tolerance.
  [[nodiscard]] static SO3 from_unit_quaternion(const Scalar& w, const Scalar& x, const Scalar& y,
                                                const Scalar& z, double tolerance);
  /// Unit quaternion (w, x, y, z) whose norm the caller guarantees to be 1 within a few ulps
  /// (built from unit factors, or from cosines and sines of the same angle); not normalised.
  /// The guarantee is checked by RIGID_ASSERT (1e-12). Use from_quaternion for other input.
  [[nodiscard]] static SO3 from_unit_quaternion(const Scalar& w, const Scalar& x, const Scalar& y,
                                                const Scalar& z);
  /// Rotation matrix R_AB. @throws rigid::Error if R is not finite, |RᵀR − I|_max > tol or
  /// det R < 0 (the message gives the defect and the determinant). Use nearest_rotation first
  /// for a matrix that is only roughly orthonormal.
  [[nodiscard]] static SO3 from_matrix(const Matrix3& R, double tol = 1e-9);
  /// Rotation of `angle` radians about `axis` (normalised). @throws rigid::Error on a zero
  /// or non-finite axis, or an angle that is not finite or exceeds kMaxAngle in magnitude.
  [[nodiscard]] static SO3 from_axis_angle(const Vector3& axis, const Scalar& angle);

  /// Exponential map: rotation vector ω → rotation (accurate for small |ω|).
  /// @throws rigid::Error if ω is not finite or |ω| > kMaxAngle (the check costs one
  /// comparison of |ω|², computed anyway).
  [[nodiscard]] static SO3 exp(const Vector3& omega);
  /// Skew matrix hat(ω), hat(ω) v = ω × v.
  [[nodiscard]] static Matrix3 hat(const Vector3& w) {
    Matrix3 m;
    m << Scalar(0), -w(2), w(1), w(2), Scalar(0), -w(0), -w(1), w(0), Scalar(0);
    return m;
  }
  /// Inverse of hat (reads the lower-triangle entries).
  [[nodiscard]] static Vector3 vee(const Matrix3& m) { return Vector3(m(2, 1), m(0, 2), m(1, 0)); }
  /// Right Jacobian Jr(ω) and its inverse [Sola2018].
  [[nodiscard]] static Matrix3 right_jacobian(const Vector3& omega);
  [[nodiscard]] static Matrix3 right_jacobian_inverse(const Vector3& omega);
  /// Left Jacobian Jl(ω) = Jr(−ω) [Sola2018] and its inverse.
  [[nodiscard]] static Matrix3 left_jacobian(const Vector3& omega);
  [[nodiscard]] static Matrix3 left_jacobian_inverse(const Vector3& omega);
  /// ½ q ⊗ (0, ω_B): the rate of the quaternion coefficients q = (w, x, y, z) of R_AB(t) when
  /// Ṙ_AB = R_AB hat(ω_B) (ω_B in the moving frame B, rad/s). q need not be unit: Runge–Kutta
  /// stages combine unnormalised coefficients. (w, v) ⊗ (0, ω) = (−v·ω, w ω + v × ω).
  [[nodiscard]] static Vector4 quaternion_rate(const Vector4& q, const Vector3& w_B) {
    const Vector3 v = q.template tail<3>();
    Vector4 r;
    r(0) = -0.5 * v.dot(w_B);
    r.template tail<3>() = 0.5 * (q(0) * w_B + v.cross(w_B));
    return r;
  }
  /// Haar-uniform random rotation (normalised 4-D Gaussian quaternion).
  [[nodiscard]] static SO3 sample(std::mt19937_64& rng);

  /// Logarithm: rotation vector with angle in [0, π], accurate near 0 and near π.
  /// @throws rigid::Error for invalid() (the marker of a diverged computation).
  [[nodiscard]] Vector3 log() const;
  /// Rotation angle in [0, π]. @throws rigid::Error for invalid().
  [[nodiscard]] Scalar angle() const;
  /// Rotation matrix (for SO3 the adjoint equals the matrix).
  [[nodiscard]] Matrix3 matrix() const;
  [[nodiscard]] Matrix3 adjoint() const { return matrix(); }
  /// Homogeneous 4×4 form [[R, 0], [0, 1]].
  [[nodiscard]] Eigen::Matrix<Scalar, 4, 4> homogeneous() const;
  /// Quaternion as (w, x, y, z).
  [[nodiscard]] Vector4 quaternion() const { return q_; }
  [[nodiscard]] const Scalar& w() const { return q_(0); }
  [[nodiscard]] const Scalar& x() const { return q_(1); }
  [[nodiscard]] const Scalar& y() const { return q_(2); }
  [[nodiscard]] const Scalar& z() const { return q_(3); }

  [[nodiscard]] SO3 inverse() const { return SO3(q_(0), -q_(1), -q_(2), -q_(3)); }
  /// Composition (Hamilton product of the quaternions; 16 multiplications, 12 additions).
  [[nodiscard]] SO3 operator*(const SO3& b) const {
#ifdef __SSE2__
    if constexpr (std::is_same_v<Scalar, double>) {
      // The same product on two SSE2 lanes, (w, x) and (y, z), so that the (w, x, y, z) storage
      // needs no reordering: with A = a's coefficients broadcast and B = b's pairs,
      //   (rw, rx) = aw (bw, bx) + ax (−bx, bw) + ay (−by, bz) + az (−bz, −by)
      //   (ry, rz) = aw (by, bz) + ax (−bz, by) + ay (bw, −bx) + az (bx, bw)
      // 8 packed multiplications, 6 packed additions.
      const __m128d a0 = _mm_loadu_pd(q_.data()), a1 = _mm_loadu_pd(q_.data() + 2);
      const __m128d b0 = _mm_loadu_pd(b.q_.data()), b1 = _mm_loadu_pd(b.q_.data() + 2);
      const __m128d aw = _mm_unpacklo_pd(a0, a0), ax = _mm_unpackhi_pd(a0, a0);
      const __m128d ay = _mm_unpacklo_pd(a1, a1), az = _mm_unpackhi_pd(a1, a1);
      const __m128d b0s = _mm_shuffle_pd(b0, b0, 1), b1s = _mm_shuffle_pd(b1, b1, 1);
      const __m128d neg_lo = _mm_set_pd(0.0, -0.0), neg_hi = _mm_set_pd(-0.0, 0.0);
      const __m128d neg_both = _mm_set1_pd(-0.0);
      const __m128d r0 = _mm_add_pd(
          _mm_add_pd(_mm_mul_pd(aw, b0), _mm_mul_pd(ax, _mm_xor_pd(b0s, neg_lo))),
          _mm_add_pd(_mm_mul_pd(ay, _mm_xor_pd(b1, neg_lo)), _mm_mul_pd(az, _mm_xor_pd(b1s, neg_both))));
      const __m128d r1 = _mm_add_pd(
          _mm_add_pd(_mm_mul_pd(aw, b1), _mm_mul_pd(ax, _mm_xor_pd(b1s, neg_lo))),
          _mm_add_pd(_mm_mul_pd(ay, _mm_xor_pd(b0, neg_hi)), _mm_mul_pd(az, b0s)));
      SO3 r;
      _mm_storeu_pd(r.q_.data(), r0);
      _mm_storeu_pd(r.q_.data() + 2, r1);
      return r;
    }
#endif
    const Scalar &aw = q_(0), &ax = q_(1), &ay = q_(2), &az = q_(3);
    const Scalar &bw = b.q_(0), &bx = b.q_(1), &by = b.q_(2), &bz = b.q_(3);
    return SO3(aw * bw - ax * bx - ay * by - az * bz, aw * bx + ax * bw + ay * bz - az * by,
               aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw);
  }
  SO3& operator*=(const SO3& b) { return *this = *this * b; }
  /// Rotates a point or vector: v' = v + 2w (u × v) + 2 u × (u × v), u = (x, y, z).
  [[nodiscard]] Vector3 operator*(const Vector3& v) const {
    const Scalar &w = q_(0), &x = q_(1), &y = q_(2), &z = q_(3);
    const Scalar tx = 2.0 * (y * v(2) - z * v(1));
    const Scalar ty = 2.0 * (z * v(0) - x * v(2));
    const Scalar tz = 2.0 * (x * v(1) - y * v(0));
    return Vector3(v(0) + w * tx + (y * tz - z * ty), v(1) + w * ty + (z * tx - x * tz),
                   v(2) + w * tz + (x * ty - y * tx));
  }
  /// R · exp(θ hat(e_i)): this rotation followed by the turn by θ about its own axis i
  /// (0, 1, 2 = x, y, z), given the half-angle values s = sin(θ/2) and c1 = cos(θ/2) − 1.
  /// Each coefficient is written as the old one plus a small increment,
  ///   (w, v) ⊗ (1 + c1, s e_i) = (w + (c1 w − s v_i), v + (c1 v + s w e_i + s v × e_i)),
  /// so its rounding error is half an ulp of the result and does not repeat with the same sign
  /// in every step of a steady motion (c1 rather than a cosine rounded next to 1). The norm
  /// stays 1 to round-off; a long product of such turns calls renormalized() once in a while.
  /// 12 multiplications, 16 additions.
  template <int i>
  [[nodiscard]] SO3 turned_about_axis(const Scalar& s, const Scalar& c1) const {
    static_assert(i >= 0 && i < 3, "axis index 0, 1 or 2");
    constexpr int j = (i + 1) % 3, k = (i + 2) % 3;
    SO3 r;
    r.q_(0) = q_(0) + (c1 * q_(0) - s * q_(1 + i));
    r.q_(1 + i) = q_(1 + i) + (c1 * q_(1 + i) + s * q_(0));
    r.q_(1 + j) = q_(1 + j) + (c1 * q_(1 + j) + s * q_(1 + k));
    r.q_(1 + k) = q_(1 + k) + (c1 * q_(1 + k) - s * q_(1 + j));
    return r;
  }
  /// The same rotation with |q| restored by one Newton step for 1/√(|q|²) at 1,
  /// q ← q (3 − |q|²)/2: for |q|² = 1 + δ it leaves |q|² − 1 = O(δ²), as normalising does,
  /// without a square root or a division. For quaternions that drifted from 1 by round-off
  /// only (|δ| ≪ 1). ≈ 10 flops.
  [[nodiscard]] SO3 renormalized() const {
    const Scalar f = 1.5 - 0.5 * q_.squaredNorm();
    SO3 r;
    r.q_ = f * q_;
    return r;
  }
  /// Geodesic interpolation a · exp(s · log(a⁻¹ b)), s ∈ [0, 1] (any finite s allowed).
  /// @throws rigid::Error if s is not finite or the turn |s| · angle(a⁻¹ b) exceeds kMaxAngle.
  [[nodiscard]] SO3 interpolate(const SO3& b, const Scalar& s) const;
  /// True if the two represent the same rotation within `tol` (angle of a⁻¹ b, radians).
  [[nodiscard]] bool is_approx(const SO3& b, double tol = 1e-12) const;

 private:
  SO3(const Scalar& w, const Scalar& x, const Scalar& y, const Scalar& z) : q_(w, x, y, z) {}
  SO3() = default;  // uninitialised storage, filled at once by operator*
  Vector4 q_;
};

using SO3d = SO3<double>;

extern template class SO3<double>;
extern template class SO3<AutoDiffXd>;

}  // namespace rigid
