#include "rigid/body/free_body_batch.hpp"

#include <cmath>
#include <algorithm>

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"

#include "detail/free_body_batch_paths.hpp"
#include "detail/splitting.hpp"

namespace rigid::body {

namespace {

// The refusal of body b when its moments are not positive and finite or its state is not
// finite (out of line: the check in the loop is a few comparisons). Returns when the state is
// finite after all (finite components whose sum overflowed).
[[gnu::cold, gnu::noinline]] void refuse_body_input(std::size_t b, const Eigen::Vector3d& I,
                                                   const FreeBodyState& state) {
  RIGID_REQUIRE_AS("step_free_bodies", (I.array() > 0.0).all() && I.allFinite(),
                   "body {}: principal moments {} kg·m² must be positive and finite", b,
                   rigid::to_string(I.transpose()));
  if (const auto bad = find_nonfinite(state)) {
    ::rigid::detail::throw_error("step_free_bodies",
                        fmt::format("body {}: the state is not finite: {} = {}, expected a "
                                    "finite state",
                                    b, bad->component, bad->value));
  }
}

// Each body's input is checked as it is loaded for its step (a separate pass over the batch
// first would read it from memory twice: 5-10 % of a splitting2 step at 1e5 bodies): the
// smallest moment positive (false for NaN) and a finite sum of the moments and the state's
// components (non-finite if one of them is; finite values whose sum overflows fall through
// to refuse_body_input, which accepts them). `&`, not `&&`: one branch per body.
inline bool input_ok(const Eigen::Vector3d& I, const FreeBodyState& state) {
  return (std::min({I(0), I(1), I(2)}) > 0.0) &
         std::isfinite(I.sum() + state.R_WB.quaternion().sum() + state.w_B.sum());
}

// The refusal of the first body whose state after the step is not finite; returns when there
// is none (finite components whose sum overflowed).
[[gnu::cold, gnu::noinline]] void refuse_body_result(std::span<const FreeBodyState> states,
                                                    double h) {
  for (std::size_t b = 0; b < states.size(); ++b) {
    if (const auto bad = find_nonfinite(states[b])) {
      ::rigid::detail::throw_error("step_free_bodies",
                          fmt::format("body {}: the step of h = {} s diverged: {} = {} after it, "
                                      "expected a finite state (a smaller step h)",
                                      b, h, bad->component, bad->value));
    }
  }
}


// One body through the checks and step_free_body (the scalar path, and the blocks holding a body
// whose input the checks refuse): refuses body b's bad input, steps it otherwise.
void step_one(FreeBodyMethod method, std::size_t b, const Eigen::Vector3d& I, FreeBodyState& state,
              double h) {
  if (!input_ok(I, state)) [[unlikely]]
    refuse_body_input(b, I, state);
  try {
    state = step_free_body(method, I, state, h);
  } catch (const Error& e) {
    // an implicit step that did not converge
    ::rigid::detail::throw_error("step_free_bodies", fmt::format("body {}: {}", b, e.what()));
  }
}

// The splittings four bodies at a time. Each block of four bodies is transposed into vectors
// of four doubles (GCC's vector extension: one AVX2 register, or two SSE2 registers on a CPU
// without AVX2) and taken through the sub-flows of detail::splitting_flows with the
// operations of step_splitting (free_body_integrators.cpp) in the same order, element-wise,
// without fused multiply-adds (AVX2 alone does not enable FMA): every body's result is the
// same bits as step_free_body's (tested for both code paths). A lane whose half angle
// exceeds detail::kSeriesBound takes std::sin/std::cos for that lane, as the scalar kernel
// does. The vectors are written by hand rather than left to the auto-vectoriser, which does
// not vectorise across the bodies of an array of structures.
using Lanes = double __attribute__((vector_size(4 * sizeof(double))));
constexpr int kLanes = 4;

// sin and cos − 1 of each lane of x, as small_sincos in free_body_integrators.cpp.
[[gnu::always_inline]] inline void lanes_sincos(const Lanes& x, Lanes& s, Lanes& cm1) {
  detail::small_sincos_series(x, s, cm1);
  const auto beyond = (x > detail::kSeriesBound) | (x < -detail::kSeriesBound);  // |x| > bound
  if ((beyond[0] | beyond[1] | beyond[2] | beyond[3]) != 0) [[unlikely]] {
    for (int l = 0; l < kLanes; ++l) {
      if (beyond[l] != 0) {
        s[l] = std::sin(x[l]);
        cm1[l] = std::cos(x[l]) - 1.0;
      }
    }
  }
}

// axis_flow<i> of free_body_integrators.cpp on four bodies: L turns by −θ about e_i and the
// quaternion q (w, x, y, z) by +θ (SO3::turned_about_axis<i>).
template <int i>
[[gnu::always_inline]] inline void lanes_axis_flow(const Lanes& half, Lanes (&q)[4],
                                                   Lanes (&L)[3]) {
  constexpr int j = (i + 1) % 3, k = (i + 2) % 3;
  Lanes sh, cm;
  lanes_sincos(half, sh, cm);
  const Lanes d = 2.0 * sh * sh;
  const Lanes s = 2.0 * sh + 2.0 * sh * cm;
  const Lanes Lj = L[j], Lk = L[k];
  L[j] = Lj + (s * Lk - d * Lj);
  L[k] = Lk - (s * Lj + d * Lk);
  const Lanes q0 = q[0], qi = q[1 + i], qj = q[1 + j], qk = q[1 + k];
  q[0] = q0 + (cm * q0 - sh * qi);
  q[1 + i] = qi + (cm * qi + sh * q0);
  q[1 + j] = qj + (cm * qj + sh * qk);
  q[1 + k] = qk + (cm * qk - sh * qj);
}

// GCC 12 warns that the vectors I[m] built from four scalars below "may be used uninitialized"
// when this is inlined into the AVX2 function (a false positive of its vector lowering: every
// vector is assigned whole before use).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
// Steps the `count` ≤ kLanes bodies from `states` (their input checked) and writes each one's
// result. A body whose result is not finite (a diverged step) is stepped again by
// step_free_body, so that it holds that path's bits for the caller's refusal.
[[gnu::always_inline]] inline void step_block(FreeBodyMethod method,
                                              const std::vector<detail::AxisFlow>& flows,
                                              const Eigen::Vector3d* I_B, FreeBodyState* states,
                                              int count, double h) {
  // the lanes past the last body hold a body at rest; each vector is built from four scalars
  // (writing lanes one by one into a vector in memory and reading it whole stalls the load)
  Eigen::Vector4d qs[kLanes];
  Eigen::Vector3d Is[kLanes], ws[kLanes];
  for (int l = 0; l < kLanes; ++l) {
    const bool body = l < count;
    qs[l] = body ? states[l].R_WB.quaternion() : Eigen::Vector4d(1, 0, 0, 0);
    Is[l] = body ? I_B[l] : Eigen::Vector3d(1, 1, 1);
    ws[l] = body ? states[l].w_B : Eigen::Vector3d::Zero();
  }
  Lanes I[3], q[4], w[3];
  for (int m = 0; m < 4; ++m) q[m] = Lanes{qs[0](m), qs[1](m), qs[2](m), qs[3](m)};
  for (int m = 0; m < 3; ++m) {
    I[m] = Lanes{Is[0](m), Is[1](m), Is[2](m), Is[3](m)};
    w[m] = Lanes{ws[0](m), ws[1](m), ws[2](m), ws[3](m)};
  }
  // as step_splitting: θ/2 = c_half · a_i · L_i with a_i = h / I_i, L = I ω
  Lanes a[3], L[3];
  for (int m = 0; m < 3; ++m) {
    a[m] = h / I[m];
    L[m] = I[m] * w[m];
  }
  for (const detail::AxisFlow& f : flows) {
    if (f.axis == 0) {
      lanes_axis_flow<0>(f.c * a[0] * L[0], q, L);
    } else if (f.axis == 1) {
      lanes_axis_flow<1>(f.c * a[1] * L[1], q, L);
    } else {
      lanes_axis_flow<2>(f.c * a[2] * L[2], q, L);
    }
  }
  // SO3::renormalized: q (3 − |q|²)/2, |q|² summed in the order of Eigen's squaredNorm of a
  // Vector4d on two-double packets, (w² + y²) + (x² + z²)
  const Lanes n2 = (q[0] * q[0] + q[2] * q[2]) + (q[1] * q[1] + q[3] * q[3]);
  const Lanes f = 1.5 - 0.5 * n2;
  for (int m = 0; m < 4; ++m) q[m] = f * q[m];
  for (int m = 0; m < 3; ++m) w[m] = L[m] / I[m];
  for (int l = 0; l < count; ++l) {
    const double sum = q[0][l] + q[1][l] + q[2][l] + q[3][l] + w[0][l] + w[1][l] + w[2][l];
    if (std::isfinite(sum)) [[likely]] {
      states[l] = {SO3d::from_unit_quaternion(q[0][l], q[1][l], q[2][l], q[3][l]),
                   Eigen::Vector3d(w[0][l], w[1][l], w[2][l])};
    } else {
      states[l] = step_free_body(method, I_B[l], states[l], h);
    }
  }
}

#pragma GCC diagnostic pop

// The four-body path over the whole batch: blocks of kLanes bodies whose input passes the
// checks go through step_block; a block holding a body the checks refuse goes body by body
// (step_one), so that the bodies before it are stepped and the refusal names it.
[[gnu::always_inline]] inline void step_lanes(FreeBodyMethod method,
                                              std::span<const Eigen::Vector3d> I_B,
                                              std::span<FreeBodyState> states, double h) {
  const std::vector<detail::AxisFlow>& flows = detail::splitting_flows(method);
  for (std::size_t b = 0; b < states.size(); b += kLanes) {
    const int count = static_cast<int>(std::min<std::size_t>(kLanes, states.size() - b));
    bool ok = true;
    for (int l = 0; l < count; ++l) ok &= input_ok(I_B[b + l], states[b + l]);
    if (ok) [[likely]] {
      step_block(method, flows, &I_B[b], &states[b], count, h);
    } else {
      for (int l = 0; l < count; ++l) step_one(method, b + l, I_B[b + l], states[b + l], h);
    }
  }
}

void step_lanes_baseline(FreeBodyMethod method, std::span<const Eigen::Vector3d> I_B,
                         std::span<FreeBodyState> states, double h) {
  step_lanes(method, I_B, states, h);
}

[[gnu::target("avx2")]] void step_lanes_avx2(FreeBodyMethod method,
                                             std::span<const Eigen::Vector3d> I_B,
                                             std::span<FreeBodyState> states, double h) {
  step_lanes(method, I_B, states, h);
}

bool is_splitting(FreeBodyMethod method) {
  return method == FreeBodyMethod::kSplitting2 || method == FreeBodyMethod::kSplitting4 ||
         method == FreeBodyMethod::kSplitting6;
}

}  // namespace

namespace detail {

bool batch_path_available(BatchPath path) {
  if (path == BatchPath::kLanesAvx2) return __builtin_cpu_supports("avx2") != 0;
  return true;
}

BatchPath batch_path_of(FreeBodyMethod method) {
  if (!is_splitting(method)) return BatchPath::kScalar;
  static const bool avx2 = batch_path_available(BatchPath::kLanesAvx2);
  return avx2 ? BatchPath::kLanesAvx2 : BatchPath::kLanes;
}

void step_free_bodies_on(BatchPath path, FreeBodyMethod method,
                         std::span<const Eigen::Vector3d> I_B, std::span<FreeBodyState> states,
                         double h) {
  RIGID_REQUIRE_AS("step_free_bodies", I_B.size() == states.size(), "{} principal-moment vectors for {} states; expected one per body",
                I_B.size(), states.size());
  RIGID_REQUIRE_AS("step_free_bodies", std::isfinite(h) && h > 0, "step h must be positive and finite, got {} s", h);
  RIGID_REQUIRE_AS("step_free_bodies", batch_path_available(path), "this CPU lacks the instructions of the batch path asked for");
  RIGID_REQUIRE_AS("step_free_bodies", path == BatchPath::kScalar || is_splitting(method),
                "the four-body path takes the splittings only, not {}", name_of(method));
  if (path == BatchPath::kLanesAvx2) {
    step_lanes_avx2(method, I_B, states, h);
  } else if (path == BatchPath::kLanes) {
    step_lanes_baseline(method, I_B, states, h);
  } else {
    for (std::size_t b = 0; b < states.size(); ++b) step_one(method, b, I_B[b], states[b], h);
  }
  // every component after the step: non-finite iff one of them is (or a sum overflowed)
  double sum = 0.0;
  for (const FreeBodyState& s : states) sum += s.R_WB.quaternion().sum() + s.w_B.sum();
  if (!std::isfinite(sum)) [[unlikely]]
    refuse_body_result(states, h);
}

}  // namespace detail

void step_free_bodies(FreeBodyMethod method, std::span<const Eigen::Vector3d> I_B,
                      std::span<FreeBodyState> states, double h) {
  detail::step_free_bodies_on(detail::batch_path_of(method), method, I_B, states, h);
}

}  // namespace rigid::body
