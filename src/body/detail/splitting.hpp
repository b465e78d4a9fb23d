#pragma once

// The body-axis splitting shared by step_free_body (free_body_integrators.cpp) and the
// batch kernel of step_free_bodies (free_body_batch.cpp): the list of sub-flows of a method
// and the half-angle sine and cosine, written once for a double and for a vector of doubles
// (GCC's vector extension), so the batch kernel performs the same operations, in the same
// order, as the step of one body and returns the same bits.

#include <vector>

#include "rigid/body/free_body_integrators.hpp"

namespace rigid::body::detail {

/// One sub-flow of the body-axis splitting: rotation about body axis `axis` through the half
/// angle c · h L_axis / I_axis (c is stored as the half-angle fraction of the step).
struct AxisFlow {
  int axis;
  double c;
};

/// The sub-flows of kSplitting2, kSplitting4 or kSplitting6 (neighbours about the same axis
/// merged), made once.
const std::vector<AxisFlow>& splitting_flows(FreeBodyMethod method);

/// Largest |x| for which small_sincos_series is used; beyond it std::sin/std::cos.
inline constexpr double kSeriesBound = 0.5;

/// sin x and cos x − 1 for |x| ≤ kSeriesBound by their Maclaurin series [DLMF, eqs. 4.19.1,
/// 4.19.2]:
///   sin x     = x − x³/3! + … + x¹³/13!   (first dropped term x¹⁵/15! ≤ 2.3e-17 < ε/4 · sin x)
///   cos x − 1 = −x²/2! + … − x¹⁴/14!      (first dropped term x¹⁶/16! ≤ 7e-19)
/// Horner in x² rounds to about one ulp. cos x − 1 is returned rather than cos x: a cosine
/// rounded next to 1 carries an absolute error up to ε/2 that is the same in every step of
/// a steady motion (the same angle each step), so rotations built from it would change |L|
/// systematically, step after step; the small difference keeps its relative precision.
/// T is double or a GCC vector of doubles (the operations are element-wise, in the same
/// order). ≈ 16 flops.
template <class T>
inline void small_sincos_series(const T& x, T& s, T& cm1) {
  const T x2 = x * x;
  T ps = T{} + 1.0 / 6227020800.0;  // 1/13! (T{} + c: the constant as a T)
  ps = ps * x2 - 1.0 / 39916800.0;
  ps = ps * x2 + 1.0 / 362880.0;
  ps = ps * x2 - 1.0 / 5040.0;
  ps = ps * x2 + 1.0 / 120.0;
  ps = ps * x2 - 1.0 / 6.0;
  s = x + x * (x2 * ps);
  T pc = T{} - 1.0 / 87178291200.0;  // −1/14!
  pc = pc * x2 + 1.0 / 479001600.0;
  pc = pc * x2 - 1.0 / 3628800.0;
  pc = pc * x2 + 1.0 / 40320.0;
  pc = pc * x2 - 1.0 / 720.0;
  pc = pc * x2 + 1.0 / 24.0;
  pc = pc * x2 - 0.5;
  cm1 = x2 * pc;
}

}  // namespace rigid::body::detail
