#pragma once
// The exp and log loops of rigid.so3 (python/so3_batch_py.cpp), in two kinds:
// - exact (the default): the operations of rigid.SO3 (SO3d::exp; the batch's quaternion reader
//   then SO3d::log) in the same order, on blocks of rows: the arithmetic in vectorised loops
//   around a loop that calls only the C library's sin/cos or atan2. Bitwise the same numbers as
//   the SO3d functions (python/tests/test_so3_batch.py), at about half the cost per row.
// - fast (fast=True): rows in blocks of structure-of-arrays, with polynomial sin, cos and atan
//   and no calls, so that the compiler vectorises the loop (AVX2 where the CPU has it, chosen
//   at run time, else SSE2: the same operations, bitwise the same numbers). Within kFastLogUlps and
//   kFastExpUlps of the exact kind (bounds below). A row that either kind cannot take (a
//   refusal, or a fast row outside the fast domain) makes the caller compute it by the exact
//   per-row code, which refuses in the usual words.
#include <cstddef>

#include "rigid/lie/angle_limit.hpp"

namespace rigid::python::so3_kernels {

/// SO3d's small-angle threshold θ < 1e-5 as θ² (kSmallAngle in src/lie/so3.cpp).
inline constexpr double kSmallAngle2 = 1e-5 * 1e-5;

/// The exact log of rows [0, n) of quaternions `q` (n × 4; w, x, y, z, or x, y, z, w when
/// `scalar_last`) into rotation vectors `omega` (n × 3): normalised by one Newton step as
/// SO3d::from_integrated_quaternion, then SO3d::log, the same operations in the same order.
/// Returns false if some row has |q|² not finite or below 1e-24 (the batch's quaternion reader
/// scales or refuses those); the rows are then to be recomputed one by one.
bool log_exact(const double* q, std::ptrdiff_t n, bool scalar_last, double* omega);
/// The exact exp of rows [0, n) of rotation vectors `omega` (n × 3) into quaternions `q`
/// (n × 4, in the given order): SO3d::exp, the same operations in the same order. Returns false
/// if some row is one SO3d::exp refuses (not finite, or longer than kMaxAngle).
bool exp_exact(const double* omega, std::ptrdiff_t n, bool scalar_last, double* q);

/// Bound of the fast log against the exact one: |fast_i − exact_i| ≤ kFastLogUlps · ε · |ω|
/// for each component i (ε = 2⁻⁵², |ω| the angle). The exact kind is within about an ulp of
/// the true value (glibc's atan2, Newton normalisation); the fast one takes the angle from the
/// unnormalised quaternion (atan2 does not depend on the scale) with Cephes' rational atan
/// (≤ 1 ulp on its interval) after one reduction, π/2 − atan(1/x) beyond x = 1: a few roundings
/// each. Measured on 2·10⁵ random rows and the edges (θ near 0, near π, exactly π, w = ±0,
/// unnormalised): max 2.5 (python/tests/test_so3_batch.py checks the bound).
inline constexpr double kFastLogUlps = 4.0;
/// Bound of the fast exp against the exact one: |fast_i − exact_i| ≤ kFastExpUlps · ε for each
/// quaternion component (|q| = 1). Cody–Waite reduction of θ/2 by π/2 (three parts, exact for
/// the rows the fast kind takes) and Cephes' sin/cos polynomials (≤ 1 ulp on [−π/4, π/4]).
/// Measured max 1.0 over random rows, θ up to 10⁶ and the edges; matrices built from the
/// fast quaternions are within 24 ε (python/tests/test_so3_batch.py).
inline constexpr double kFastExpUlps = 4.0;
/// The fast exp takes rows with |ω| ≤ this (rad); a longer one (still ≤ kMaxAngle) goes to the
/// exact kind, so that the π/2 multiples stay exact in the reduction.
inline constexpr double kFastExpMaxAngle = 1e6;

/// The fast log of rows [0, n) of quaternions `q` (n × 4) into `omega` (n × 3). Returns false
/// if some row is not finite or has |q|² < 2e-24 (the exact kind decides those: refused below
/// 1e-24); the rows written are then to be recomputed by the exact kind.
bool log_fast(const double* q, std::ptrdiff_t n, bool scalar_last, double* omega);
/// The fast exp of rows [0, n) of rotation vectors `omega` (n × 3) into quaternions `q` (n × 4,
/// in the given order). Returns false if some row is not finite or longer than
/// kFastExpMaxAngle; the rows are then to be recomputed by the exact kind.
bool exp_fast(const double* omega, std::ptrdiff_t n, bool scalar_last, double* q);

}  // namespace rigid::python::so3_kernels
