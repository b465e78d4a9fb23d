// The fast (vectorised) exp and log of rigid.so3: python/so3_kernels.hpp.
#include "so3_kernels.hpp"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>

namespace rigid::python::so3_kernels {

namespace {

// Rows per structure-of-arrays block: the columns of 64 rows fit in L1 beside the rows.
constexpr int kRows = 64;

constexpr double kPi2 = 1.57079632679489661923;  // π/2
constexpr double kPi4 = 0.78539816339744830962;  // π/4
// π/2 − kPi2 and π/4 − kPi4 (the bits beyond double precision), as Cephes' MOREBITS.
constexpr double kPi2Tail = 6.123233995736765886130e-17;
// π/2 in three parts of 24, 24 and 53 bits (Cody–Waite; Cephes' DP1..DP3 for π/4, doubled):
// j · kPi2A and j · kPi2B are exact for j < 2²⁹.
constexpr double kPi2A = 1.57079625129699707031;
constexpr double kPi2B = 7.54978941586159635336e-08;
constexpr double kPi2C = 5.39030285815811905290e-15;
// Adding then subtracting 1.5 · 2⁵² rounds a double of magnitude < 2⁵¹ to an integer (no
// contraction or reassociation in ISO C++ mode).
constexpr double kRound = 6755399441055744.0;

// c[0] z^(N−1) + c[1] z^(N−2) + … + c[N−1], by Horner's rule.
template <std::size_t N>
[[gnu::always_inline]] inline double horner(double z, const std::array<double, N>& c) {
  double p = c[0];
  for (std::size_t i = 1; i < N; ++i) p = p * z + c[i];
  return p;
}

// atan(x) = x + x · z P(z)/Q(z), z = x², for |x| ≤ 0.66: Cephes atan.c (S. L. Moshier), relative
// error ≤ 1 ulp there (checked against glibc's atan on 2·10⁶ points).
constexpr std::array<double, 5> kAtanP = {-8.750608600031904122785e-1, -1.615753718733365076637e1,
                                          -7.500855792314704667340e1, -1.228866684490136173410e2,
                                          -6.485021904942025371773e1};
constexpr std::array<double, 6> kAtanQ = {1.0,
                                          2.485846490142306297962e1,
                                          1.650270098316988542046e2,
                                          4.328810604912902668951e2,
                                          4.853903996359136964868e2,
                                          1.945506571482613964425e2};
inline double atan_ratio(double z) { return z * horner(z, kAtanP) / horner(z, kAtanQ); }

// sin(r) = r + r · z S(z), cos(r) = 1 − z/2 + z² C(z), z = r², |r| ≤ π/4: Cephes sin.c.
constexpr std::array<double, 6> kSin = {1.58962301576546568060e-10, -2.50507477628578072866e-8,
                                        2.75573136213857245213e-6,  -1.98412698295895385996e-4,
                                        8.33333333332211858878e-3,  -1.66666666666666307295e-1};
constexpr std::array<double, 6> kCos = {-1.13585365213876817300e-11, 2.08757008419747316778e-9,
                                        -2.75573141792967388112e-7,  2.48015872888517045348e-5,
                                        -1.38888888888730564116e-3,  4.16666666666665929218e-2};
inline double sin_series(double z) { return z * horner(z, kSin); }
inline double cos_series(double z) { return z * z * horner(z, kCos); }

// The m rows of quaternions at q (w first, or last with kScalarLast) into four columns.
template <bool kScalarLast>
[[gnu::always_inline]] inline void load_quaternions(const double* q, int m, double* W, double* X,
                                                    double* Y, double* Z) {
  constexpr int iw = kScalarLast ? 3 : 0, ix = kScalarLast ? 0 : 1;
  for (int i = 0; i < m; ++i) {
    W[i] = q[4 * i + iw], X[i] = q[4 * i + ix], Y[i] = q[4 * i + ix + 1];
    Z[i] = q[4 * i + ix + 2];
  }
}

// One block of m ≤ kRows rows of log; returns 1 for a row the fast kind does not take.
template <bool kScalarLast>
[[gnu::always_inline]] inline int log_block(const double* q, int m, double* omega) {
  alignas(64) double W[kRows], X[kRows], Y[kRows], Z[kRows], K[kRows];
  load_quaternions<kScalarLast>(q, m, W, X, Y, Z);
  int bad = 0;
  for (int i = 0; i < m; ++i) {
    const double w = W[i], x = X[i], y = Y[i], z = Z[i];
    const double v2 = x * x + y * y + z * z;
    const double n2 = w * w + v2;
    // 2e-24: a margin over the exact kind's 1e-24 (its sum rounds differently)
    bad |= static_cast<int>(!(n2 >= 2e-24) | !(n2 <= DBL_MAX));
    // θ/2 = atan2(n, a), n = |v|, a = |w| (the representative with w ≥ 0; the scale of q
    // cancels): with lo/hi = min/max(n, a), atan(lo/hi), reduced beyond 0.66 by
    // atan(t) = π/4 + atan((t − 1)/(t + 1)); π/2 minus it when n > a. (Every operation is
    // done on every row and only values are selected, so that the loop has no branch to
    // vectorise around: divisions too, one per quotient, on selected operands.)
    const double n = std::sqrt(v2), a = std::abs(w);
    const double lo = std::min(n, a), hi = std::max(n, a);
    const bool reduce = lo > 0.66 * hi;
    const double t = (reduce ? lo - hi : lo) / (reduce ? lo + hi : hi);
    const double r = atan_ratio(t * t);
    const double at = reduce ? kPi4 + (t + (t * r + 0.5 * kPi2Tail)) : t + t * r;
    const double half = n > a ? kPi2 + (kPi2Tail - at) : at;
    // k = 2 (θ/2)/n; where no reduction was made and n ≤ a, θ/2 = t (1 + r) with t = n/a, so
    // k = 2 (1 + r)/a: no 0/0 at n = 0, and full accuracy as n → 0
    const bool near_zero = (n <= a) & !reduce;
    const double k = 2.0 * (near_zero ? 1.0 + r : half) / (near_zero ? a : n);
    K[i] = w < 0.0 ? -k : k;
  }
  for (int i = 0; i < m; ++i) {
    omega[3 * i] = K[i] * X[i], omega[3 * i + 1] = K[i] * Y[i], omega[3 * i + 2] = K[i] * Z[i];
  }
  return bad;
}

// One block of m ≤ kRows rows of exp; returns 1 for a row the fast kind does not take.
template <bool kScalarLast>
[[gnu::always_inline]] inline int exp_block(const double* omega, int m, double* q) {
  alignas(64) double X[kRows], Y[kRows], Z[kRows], C[kRows], K[kRows];
  for (int i = 0; i < m; ++i) X[i] = omega[3 * i], Y[i] = omega[3 * i + 1], Z[i] = omega[3 * i + 2];
  int bad = 0;
  for (int i = 0; i < m; ++i) {
    const double x = X[i], y = Y[i], z = Z[i];
    const double theta2 = x * x + y * y + z * z;
    const bool ok = theta2 <= kFastExpMaxAngle * kFastExpMaxAngle;  // false for NaN
    bad |= static_cast<int>(!ok);
    const double theta = std::sqrt(ok ? theta2 : 0.0);
    const double h = 0.5 * theta;
    // h = j π/2 + r, |r| ≤ π/4; j mod 4 picks the signs and whether sin and cos swap
    const double j = (h * (1.0 / kPi2) + kRound) - kRound;
    const double r = ((h - j * kPi2A) - j * kPi2B) - j * kPi2C;
    const double j4 = ((j * 0.25 - 0.375) + kRound) - kRound;  // floor(j/4): no ties
    const double quadrant = j - 4.0 * j4;                      // 0, 1, 2 or 3
    const double z2 = r * r;
    const double ss = sin_series(z2);
    const double s = r + r * ss, c = 1.0 - 0.5 * z2 + cos_series(z2);
    // (selects on doubles only: boolean algebra on the comparisons keeps GCC from vectorising)
    const double sin_h = quadrant == 0.0 ? s : quadrant == 1.0 ? c : quadrant == 2.0 ? -s : -c;
    const double cos_h = quadrant == 0.0 ? c : quadrant == 1.0 ? -s : quadrant == 2.0 ? -c : s;
    // k = sin(θ/2)/θ; for j = 0 (θ ≤ π/2), r = θ/2 and k = (1 + z S(z))/2: no 0/0 at θ = 0
    C[i] = cos_h;
    K[i] = (j == 0.0 ? 1.0 + ss : sin_h) / (j == 0.0 ? 2.0 : theta);
  }
  constexpr int iw = kScalarLast ? 3 : 0, ix = kScalarLast ? 0 : 1;
  for (int i = 0; i < m; ++i) {
    q[4 * i + iw] = C[i], q[4 * i + ix] = K[i] * X[i], q[4 * i + ix + 1] = K[i] * Y[i];
    q[4 * i + ix + 2] = K[i] * Z[i];
  }
  return bad;
}

// One block of m ≤ kRows rows of the exact log: the operations of from_integrated_quaternion
// and SO3d::log (the same roundings; Eigen's |q|² is (w² + y²) + (x² + z²)), the arithmetic
// vectorised on either side of a loop of atan2 calls. Returns 1 for a row to leave to
// read_rotation (|q|² not finite or below 1e-24).
template <bool kScalarLast>
[[gnu::always_inline]] inline int log_exact_block(const double* q, int m, double* omega) {
  alignas(64) double W[kRows], X[kRows], Y[kRows], Z[kRows], N[kRows], A[kRows];
  load_quaternions<kScalarLast>(q, m, W, X, Y, Z);
  int bad = 0;
  for (int i = 0; i < m; ++i) {
    const double n2 = (W[i] * W[i] + Y[i] * Y[i]) + (X[i] * X[i] + Z[i] * Z[i]);
    bad |= static_cast<int>(!(n2 >= 1e-24) | !(n2 <= DBL_MAX));
    const double newton = 1.5 - 0.5 * n2, inverse_norm = 1.0 / std::sqrt(n2);
    const double f = std::abs(n2 - 1.0) <= 1e-8 ? newton : inverse_norm;
    const double sign = f * W[i] < 0.0 ? -1.0 : 1.0;
    W[i] = sign * (f * W[i]), X[i] = sign * (f * X[i]), Y[i] = sign * (f * Y[i]);
    Z[i] = sign * (f * Z[i]);
    N[i] = std::sqrt(X[i] * X[i] + Y[i] * Y[i] + Z[i] * Z[i]);
  }
  for (int i = 0; i < m; ++i) A[i] = std::atan2(N[i], W[i]);
  for (int i = 0; i < m; ++i) {
    const double w = W[i], v2 = X[i] * X[i] + Y[i] * Y[i] + Z[i] * Z[i];
    const double series = 2.0 / w * (1.0 - v2 / (3.0 * w * w)), closed = 2.0 * A[i] / N[i];
    const double k = v2 < kSmallAngle2 ? series : closed;
    omega[3 * i] = k * X[i], omega[3 * i + 1] = k * Y[i], omega[3 * i + 2] = k * Z[i];
  }
  return bad;
}

// One block of m ≤ kRows rows of the exact exp: SO3d::exp's operations (|ω|² as Eigen sums
// it, (x² + y²) + z²), vectorised around a loop of sin and cos calls. Returns 1 for a row
// SO3d::exp refuses (not finite, or longer than kMaxAngle).
template <bool kScalarLast>
[[gnu::always_inline]] inline int exp_exact_block(const double* omega, int m, double* q) {
  alignas(64) double X[kRows], Y[kRows], Z[kRows], H[kRows], C[kRows], S[kRows];
  for (int i = 0; i < m; ++i) X[i] = omega[3 * i], Y[i] = omega[3 * i + 1], Z[i] = omega[3 * i + 2];
  int bad = 0;
  for (int i = 0; i < m; ++i) {
    const double theta2 = (X[i] * X[i] + Y[i] * Y[i]) + Z[i] * Z[i];
    bad |= static_cast<int>(!(theta2 < kSmallAngle2) & !(theta2 <= kMaxAngle * kMaxAngle));
    H[i] = 0.5 * std::sqrt(theta2);
  }
  for (int i = 0; i < m; ++i) C[i] = std::cos(H[i]), S[i] = std::sin(H[i]);
  constexpr int iw = kScalarLast ? 3 : 0, ix = kScalarLast ? 0 : 1;
  for (int i = 0; i < m; ++i) {
    const double x = X[i], y = Y[i], z = Z[i];
    const double theta2 = (x * x + y * y) + z * z;
    const bool small = theta2 < kSmallAngle2;
    const double theta = std::sqrt(theta2);
    const double c = small ? 1.0 - theta2 / 8.0 : C[i];
    const double k = small ? 0.5 - theta2 / 48.0 : S[i] / theta;
    double qw = c, qx = k * x, qy = k * y, qz = k * z;
    // the truncated series is renormalised (|q|² summed as Eigen does for a Vector4d)
    const double n = std::sqrt((qw * qw + qy * qy) + (qx * qx + qz * qz));
    qw = small ? qw / n : qw, qx = small ? qx / n : qx, qy = small ? qy / n : qy;
    qz = small ? qz / n : qz;
    q[4 * i + iw] = qw, q[4 * i + ix] = qx, q[4 * i + ix + 1] = qy, q[4 * i + ix + 2] = qz;
  }
  return bad;
}

// Rows [0, n) a block at a time; false if some block had a row it does not take.
template <int (*kBlock)(const double*, int, double*), int kIn, int kOut>
[[gnu::always_inline]] inline bool rows(const double* in, std::ptrdiff_t n, double* out) {
  int bad = 0;
  for (std::ptrdiff_t b = 0; b < n; b += kRows) {
    const int m = static_cast<int>(std::min<std::ptrdiff_t>(kRows, n - b));
    bad |= kBlock(in + kIn * b, m, out + kOut * b);
  }
  return bad == 0;
}

// Every loop of this file, for one instruction set (called from the dispatchers below).
struct Loops {
  template <bool kLast>
  [[gnu::always_inline]] static bool log(const double* q, std::ptrdiff_t n, double* omega,
                                         bool exact) {
    return exact ? rows<log_exact_block<kLast>, 4, 3>(q, n, omega)
                 : rows<log_block<kLast>, 4, 3>(q, n, omega);
  }
  template <bool kLast>
  [[gnu::always_inline]] static bool exp(const double* omega, std::ptrdiff_t n, double* q,
                                         bool exact) {
    return exact ? rows<exp_exact_block<kLast>, 3, 4>(omega, n, q)
                 : rows<exp_block<kLast>, 3, 4>(omega, n, q);
  }
};

bool log_baseline(const double* q, std::ptrdiff_t n, bool scalar_last, bool exact, double* omega) {
  return scalar_last ? Loops::log<true>(q, n, omega, exact) : Loops::log<false>(q, n, omega, exact);
}

bool exp_baseline(const double* omega, std::ptrdiff_t n, bool scalar_last, bool exact, double* q) {
  return scalar_last ? Loops::exp<true>(omega, n, q, exact) : Loops::exp<false>(omega, n, q, exact);
}

// The same loops compiled for AVX2 (four rows a vector), chosen once at run time; the same
// operations in the same order (no FMA: contraction is off in ISO C++ mode), so both give the
// same numbers, as src/mesh/mesh_mass.cpp does for its volume sums.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && defined(__linux__)
bool avx2_available() { return __builtin_cpu_supports("avx2") != 0; }

[[gnu::target("avx2")]] bool log_avx2(const double* q, std::ptrdiff_t n, bool scalar_last,
                                      bool exact, double* omega) {
  return scalar_last ? Loops::log<true>(q, n, omega, exact) : Loops::log<false>(q, n, omega, exact);
}

[[gnu::target("avx2")]] bool exp_avx2(const double* omega, std::ptrdiff_t n, bool scalar_last,
                                      bool exact, double* q) {
  return scalar_last ? Loops::exp<true>(omega, n, q, exact) : Loops::exp<false>(omega, n, q, exact);
}
#else
bool avx2_available() { return false; }
bool log_avx2(const double* q, std::ptrdiff_t n, bool scalar_last, bool exact, double* omega) {
  return log_baseline(q, n, scalar_last, exact, omega);
}
bool exp_avx2(const double* omega, std::ptrdiff_t n, bool scalar_last, bool exact, double* q) {
  return exp_baseline(omega, n, scalar_last, exact, q);
}
#endif

bool log_rows(const double* q, std::ptrdiff_t n, bool scalar_last, bool exact, double* omega) {
  static const bool avx2 = avx2_available();
  return avx2 ? log_avx2(q, n, scalar_last, exact, omega)
              : log_baseline(q, n, scalar_last, exact, omega);
}

bool exp_rows(const double* omega, std::ptrdiff_t n, bool scalar_last, bool exact, double* q) {
  static const bool avx2 = avx2_available();
  return avx2 ? exp_avx2(omega, n, scalar_last, exact, q)
              : exp_baseline(omega, n, scalar_last, exact, q);
}

}  // namespace

bool log_fast(const double* q, std::ptrdiff_t n, bool scalar_last, double* omega) {
  return log_rows(q, n, scalar_last, false, omega);
}

bool exp_fast(const double* omega, std::ptrdiff_t n, bool scalar_last, double* q) {
  return exp_rows(omega, n, scalar_last, false, q);
}

bool log_exact(const double* q, std::ptrdiff_t n, bool scalar_last, double* omega) {
  return log_rows(q, n, scalar_last, true, omega);
}

bool exp_exact(const double* omega, std::ptrdiff_t n, bool scalar_last, double* q) {
  return exp_rows(omega, n, scalar_last, true, q);
}

}  // namespace rigid::python::so3_kernels
