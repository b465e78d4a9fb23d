#include "rigid/body/free_body_batch.hpp"

#include <cmath>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "rigid/common/error.hpp"

namespace rigid::body {

namespace {

// One sub-flow: rotation about body axis `axis` for the fraction `c` of the step.
struct AxisFlow {
  int axis;
  double c;
};

// The Strang step R1(h/2) R2(h/2) R3(h) R2(h/2) R1(h/2) composed by Yoshida's triple jump
// γ1 = 1/(2 − 2^{1/(p+1)}), γ0 = 1 − 2γ1 [Yoshida1990] `levels` times, as a list of axis
// flows with neighbours about the same axis merged.
std::vector<AxisFlow> composition(int levels) {
  std::vector<AxisFlow> seq{{0, 0.5}, {1, 0.5}, {2, 1.0}, {1, 0.5}, {0, 0.5}};
  for (int level = 0, p = 2; level < levels; ++level, p += 2) {
    const double g1 = 1.0 / (2.0 - std::pow(2.0, 1.0 / (p + 1)));
    const double g0 = 1.0 - 2.0 * g1;
    std::vector<AxisFlow> next;
    for (const double g : {g1, g0, g1})
      for (const AxisFlow& f : seq) next.push_back({f.axis, g * f.c});
    seq = std::move(next);
  }
  std::vector<AxisFlow> merged;
  for (const AxisFlow& f : seq) {
    if (!merged.empty() && merged.back().axis == f.axis) merged.back().c += f.c;
    else merged.push_back(f);
  }
  return merged;
}

const std::vector<AxisFlow>& flows_of(FreeBodyMethod method) {
  static const std::vector<AxisFlow> k2 = composition(0), k4 = composition(1), k6 = composition(2);
  if (method == FreeBodyMethod::kSplitting4) return k4;
  if (method == FreeBodyMethod::kSplitting6) return k6;
  return k2;
}

// Exact flow of H_i = L_i²/(2 I_i) for time τ: L_B turns by −θ about e_i and the body by +θ,
// θ = τ L_i / I_i. Quaternion of the body turn r = (cos θ/2, sin θ/2 e_i); q ← q r.
// ≈ 30 flops + one sincos.
template <int i>
void axis_flow(double tau, double inv_I, double q[4], double L[3]) {
  constexpr int j = (i + 1) % 3, k = (i + 2) % 3;
  const double half = 0.5 * tau * L[i] * inv_I;
  const double sh = std::sin(half), ch = std::cos(half);
  const double c = 1.0 - 2.0 * sh * sh, s = 2.0 * sh * ch;
  const double Lj = L[j], Lk = L[k];
  L[j] = c * Lj + s * Lk;
  L[k] = -s * Lj + c * Lk;
  // (w, v) ⊗ (ch, sh e_i) = (w ch − sh v_i, ch v + w sh e_i + sh v × e_i)
  const double w = q[0], v[3] = {q[1], q[2], q[3]};
  q[0] = ch * w - sh * v[i];
  q[1 + i] = ch * v[i] + sh * w;
  q[1 + j] = ch * v[j] + sh * v[k];
  q[1 + k] = ch * v[k] - sh * v[j];
}

}  // namespace

void step_free_bodies(FreeBodyMethod method, std::span<const Eigen::Vector3d> I_B,
                      std::span<FreeBodyState> states, double h) {
  RIGID_REQUIRE(I_B.size() == states.size(), "{} principal-moment vectors for {} states; expected one per body",
                I_B.size(), states.size());
  RIGID_REQUIRE(std::isfinite(h) && h > 0, "step h must be positive and finite, got {} s", h);
  if (method == FreeBodyMethod::kRk4 || method == FreeBodyMethod::kLiePoissonMidpoint) {
    for (std::size_t b = 0; b < states.size(); ++b) states[b] = step_free_body(method, I_B[b], states[b], h);
    return;
  }
  const std::vector<AxisFlow>& flows = flows_of(method);
  for (std::size_t b = 0; b < states.size(); ++b) {
    FreeBodyState& s = states[b];
    const Eigen::Vector3d inv_I = I_B[b].cwiseInverse();
    double q[4] = {s.q_WB.w(), s.q_WB.x(), s.q_WB.y(), s.q_WB.z()};
    double L[3] = {I_B[b](0) * s.w_B(0), I_B[b](1) * s.w_B(1), I_B[b](2) * s.w_B(2)};
    for (const AxisFlow& f : flows) {
      const double tau = f.c * h;
      if (f.axis == 0) axis_flow<0>(tau, inv_I(0), q, L);
      else if (f.axis == 1) axis_flow<1>(tau, inv_I(1), q, L);
      else axis_flow<2>(tau, inv_I(2), q, L);
    }
    // renormalise as the single-body stepper does (keeps ‖RᵀR − 1‖ at a few ulps)
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    s.q_WB = Eigen::Quaterniond(q[0] / n, q[1] / n, q[2] / n, q[3] / n);
    s.w_B = Eigen::Vector3d(L[0] * inv_I(0), L[1] * inv_I(1), L[2] * inv_I(2));
  }
}

}  // namespace rigid::body
