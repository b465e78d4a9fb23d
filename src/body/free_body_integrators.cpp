#include "rigid/body/free_body_integrators.hpp"

#include <array>
#include <string>
#include <vector>
#include <cmath>
#include <limits>
#include <utility>

#include "rigid/body/euler.hpp"
#include "rigid/common/did_you_mean.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"
#include "rigid/mass/mass_properties.hpp"

#include "detail/splitting.hpp"

namespace rigid::body {

namespace {

using detail::AxisFlow;

constexpr std::array<std::pair<std::string_view, FreeBodyMethod>, 7> kMethods{{
    {"rk4", FreeBodyMethod::kRk4},
    {"splitting2", FreeBodyMethod::kSplitting2},
    {"splitting4", FreeBodyMethod::kSplitting4},
    {"splitting6", FreeBodyMethod::kSplitting6},
    {"midpoint", FreeBodyMethod::kLiePoissonMidpoint},
    {"rkmk4", FreeBodyMethod::kRkmk4},
    {"moser_veselov", FreeBodyMethod::kMoserVeselov},
}};

// RK4 on (q, ω) with q the unnormalised quaternion coefficients of the stages,
// q̇ = ½ q ⊗ (0, ω_B) (SO3::quaternion_rate) and Euler's equations for ω̇; the result is
// projected back onto |q| = 1 (SO3's invariant; SO3::from_integrated_quaternion).
FreeBodyState step_rk4(const Eigen::Vector3d& I_B, const FreeBodyState& s, double h) {
  const Eigen::Vector3d z = Eigen::Vector3d::Zero();
  const Eigen::Vector4d q0 = s.R_WB.quaternion();
  const Eigen::Vector3d& w0 = s.w_B;
  const Eigen::Vector4d k1q = SO3d::quaternion_rate(q0, w0);
  const Eigen::Vector3d k1w = euler_rhs<double>(I_B, w0, z);
  const Eigen::Vector3d w2 = w0 + 0.5 * h * k1w;
  const Eigen::Vector4d k2q = SO3d::quaternion_rate(q0 + 0.5 * h * k1q, w2);
  const Eigen::Vector3d k2w = euler_rhs<double>(I_B, w2, z);
  const Eigen::Vector3d w3 = w0 + 0.5 * h * k2w;
  const Eigen::Vector4d k3q = SO3d::quaternion_rate(q0 + 0.5 * h * k2q, w3);
  const Eigen::Vector3d k3w = euler_rhs<double>(I_B, w3, z);
  const Eigen::Vector3d w4 = w0 + h * k3w;
  const Eigen::Vector4d k4q = SO3d::quaternion_rate(q0 + h * k3q, w4);
  const Eigen::Vector3d k4w = euler_rhs<double>(I_B, w4, z);
  const Eigen::Vector4d q1 = q0 + h / 6.0 * (k1q + 2.0 * k2q + 2.0 * k3q + k4q);
  // back onto |q| = 1 (a step that overflowed gives SO3d::invalid() for the check to report)
  return {SO3d::from_integrated_quaternion(q1), w0 + h / 6.0 * (k1w + 2.0 * k2w + 2.0 * k3w + k4w)};
}

// SO3d::exp(theta) for the update of a step, or SO3d::invalid() where theta is not finite or
// longer than kMaxAngle (a diverged step: left for the caller's finiteness check, which names
// the component and t, rather than refused by exp here).
SO3d step_rotation(const Eigen::Vector3d& theta) {
  if (!(theta.squaredNorm() <= kMaxAngle * kMaxAngle)) [[unlikely]]
    return SO3d::invalid();
  return SO3d::exp(theta);
}

// sin x and cos x − 1 (detail::small_sincos_series for |x| ≤ 0.5). Larger |x| (a sub-flow
// turning by more than one radian) falls back to std::sin/std::cos.
inline void small_sincos(double x, double& s, double& cm1) {
  if (std::abs(x) > detail::kSeriesBound) {
    s = std::sin(x);
    cm1 = std::cos(x) - 1.0;  // ≤ −0.12 here: no precision lost
    return;
  }
  detail::small_sincos_series(x, s, cm1);
}

// The Strang step R1(h/2) R2(h/2) R3(h) R2(h/2) R1(h/2) [McLachlan1993] composed by Yoshida's
// triple jump γ1 = 1/(2 − 2^{1/(p+1)}), γ0 = 1 − 2γ1 [Yoshida1990] `levels` times, as a list
// of axis flows with neighbours about the same axis merged: the flow of H_i = L_i²/(2 I_i)
// keeps L_i, so flows of lengths a and b about axis i compose to one of length a + b.
// Yoshida-4 has 13 sub-flows instead of 15, Yoshida-6 37 instead of 45.
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
  // stored as half-angle fractions: the kernel needs θ/2 = (c/2) h L_i / I_i
  for (AxisFlow& f : merged) f.c *= 0.5;
  return merged;
}


// Exact flow of H_i = L_i²/(2 I_i) through the half angle θ/2 = `half`: ω_i = L_i/I_i is
// constant, L_B turns by −θ about e_i and the body by +θ. One sin/cos pair of θ/2 gives
// 1 − cos θ = 2 sin²(θ/2), sin θ = 2 sin(θ/2) cos(θ/2), and the body turn R ← R exp(θ e_i)
// (SO3::turned_about_axis, from the same half-angle pair). Each new component of L is written
// as the old one plus a small increment (L_j + (sin θ L_k − (1 − cos θ) L_j)), so its rounding
// error is one half-ulp of the result and does not repeat with the same sign in every step
// (see small_sincos). ≈ 40 flops + small_sincos.
template <int i>
inline void axis_flow(double half, SO3d& R, double L[3]) {
  constexpr int j = (i + 1) % 3, k = (i + 2) % 3;
  double sh = 0, cm = 0;  // sin θ/2, cos θ/2 − 1
  small_sincos(half, sh, cm);
  const double d = 2.0 * sh * sh;             // 1 − cos θ
  const double s = 2.0 * sh + 2.0 * sh * cm;  // sin θ
  const double Lj = L[j], Lk = L[k];
  L[j] = Lj + (s * Lk - d * Lj);
  L[k] = Lk - (s * Lj + d * Lk);
  R = R.turned_about_axis<i>(sh, cm);
}

// The splitting step shared by step_free_body and step_free_bodies (free_body_batch.cpp).
FreeBodyState step_splitting(const std::vector<AxisFlow>& flows, const Eigen::Vector3d& I_B,
                             const FreeBodyState& st, double h) {
  // Divisions, not products with a rounded 1/I_i: ω = L/I here and L = I ω at the start of
  // the next step must round-trip without a bias that repeats every step (with 1/I_i rounded
  // once, the tennis racket's ω error at t = 100 s grew 70× and |L| drifted 30–50× more).
  const double a[3] = {h / I_B(0), h / I_B(1), h / I_B(2)};  // θ/2 = c_half · a_i · L_i
  SO3d R = st.R_WB;
  double L[3] = {I_B(0) * st.w_B(0), I_B(1) * st.w_B(1), I_B(2) * st.w_B(2)};
  for (const AxisFlow& f : flows) {
    if (f.axis == 0) axis_flow<0>(f.c * a[0] * L[0], R, L);
    else if (f.axis == 1) axis_flow<1>(f.c * a[1] * L[1], R, L);
    else axis_flow<2>(f.c * a[2] * L[2], R, L);
  }
  // Products of unit quaternions stay unit only up to round-off, which would random-walk:
  // one Newton step per step restores |q| (SO3::renormalized).
  return {R.renormalized(), Eigen::Vector3d(L[0] / I_B(0), L[1] / I_B(1), L[2] / I_B(2))};
}

// The fixed-point iterations of the midpoint and Moser–Veselov steps stop when an update is
// below about one ulp of the solution. An iteration that has not stopped after
// kFixedPointIterations has either stalled at round-off just above that rule (its update
// wanders by an ulp or two and never reaches it) or not converged (the step is too large for
// the contraction, h|ω| max(I)/min(I) ≳ 1): the residual of the implicit equation at the last
// iterate tells them apart. It is accepted at round-off, kResidualUlps · ε · (the sum of the
// magnitudes of the terms the residual adds up, each rounded), and refused above. Measured on
// 6e6 random bodies, spins and steps whose iterations stalled and whose result is within
// 4 ulps of the fixed point iterated to convergence in long double: residuals up to 6 ε·scale
// (midpoint) and 1.3 ε·scale (Moser–Veselov); 16 leaves a margin of 2.7. The iterations and
// their stopping rules are those the steps always had, so a step that converges returns the
// same bits as before; only a step that does not converge is refused.
constexpr int kFixedPointIterations = 100;
constexpr double kResidualUlps = 16;
constexpr double kEps = std::numeric_limits<double>::epsilon();

// h |ω| max(I)/min(I): below 1 the fixed-point iterations contract.
double contraction_bound(const Eigen::Vector3d& I_B, const Eigen::Vector3d& w_B, double h) {
  return h * w_B.norm() * I_B.maxCoeff() / I_B.minCoeff();
}

// Refuses a midpoint step whose iteration did not stop: converged unless its residual
// r = L0 + h L̄ × ω̄ − L1 is above round-off.
void require_midpoint_converged(const Eigen::Vector3d& I_B, const FreeBodyState& s, double h,
                                const Eigen::Vector3d& L0, const Eigen::Vector3d& L1) {
  const Eigen::Vector3d Lm = 0.5 * (L0 + L1);
  const Eigen::Vector3d wm = Lm.cwiseQuotient(I_B);
  const double residual = (L0 + h * Lm.cross(wm) - L1).lpNorm<Eigen::Infinity>();
  const double L0_max = L0.lpNorm<Eigen::Infinity>();  // > 0: L0 = 0 stops at once
  // |L0| and h |L̄| |ω̄| (the products of the cross product) are what the residual sums
  const double tolerance =
      kResidualUlps * kEps *
      (L0_max + h * Lm.lpNorm<Eigen::Infinity>() * wm.lpNorm<Eigen::Infinity>());
  RIGID_REQUIRE_AS("step_free_body", residual <= tolerance,
                   "the Lie–Poisson midpoint step (midpoint) did not converge: h = {} s, |ω| = {} "
                   "rad/s; after {} fixed-point iterations the residual of its implicit equation, "
                   "|L1 − L0 − h L̄ × ω̄|/|L0| = {:.3g}, is above the tolerance {:.3g} (round-off); "
                   "use a smaller step (the iteration contracts for h |ω| max(I)/min(I) < 1, here "
                   "{:.3g})",
                   h, s.w_B.norm(), kFixedPointIterations, residual / L0_max, tolerance / L0_max,
                   contraction_bound(I_B, s.w_B, h));
}

FreeBodyState step_midpoint(const Eigen::Vector3d& I_B, const FreeBodyState& s, double h) {
  // L1 = L0 + h L̄ × ω̄, L̄ = (L0 + L1)/2, ω̄ = I⁻¹ L̄: keeps every quadratic
  // invariant (|L|², 2E) of the Lie–Poisson system. Fixed-point iteration,
  // a contraction for h|ω|·max(I)/min(I) < 1.
  const Eigen::Vector3d L0 = I_B.cwiseProduct(s.w_B);
  Eigen::Vector3d L1 = L0;
  bool stopped = false;
  for (int it = 0; it < kFixedPointIterations; ++it) {
    const Eigen::Vector3d Lm = 0.5 * (L0 + L1);
    const Eigen::Vector3d next = L0 + h * Lm.cross(Lm.cwiseQuotient(I_B));
    const double change = (next - L1).lpNorm<Eigen::Infinity>();
    L1 = next;
    if (change <= 1e-16 * L0.lpNorm<Eigen::Infinity>()) {
      stopped = true;
      break;
    }
  }
  // a non-finite state in is left for the caller's finiteness check, as before
  if (!stopped && s.w_B.allFinite()) [[unlikely]]
    require_midpoint_converged(I_B, s, h, L0, L1);
  const Eigen::Vector3d wm = (0.5 * (L0 + L1)).cwiseQuotient(I_B);
  return {s.R_WB * step_rotation(h * wm), L1.cwiseQuotient(I_B)};
}

FreeBodyState step_rkmk4(const Eigen::Vector3d& I_B, const FreeBodyState& st, double h) {
  // R = R0 exp(Θ̂): Θ̇ = dexp⁻¹_{−Θ}(ω) = ω + ½ Θ×ω + (1/12) Θ×(Θ×ω) + O(|Θ|⁴|ω|)
  // [Iserles2000, eq. 5.6, Bernoulli numbers B1 = −½, B2 = 1/6 with the sign of −Θ].
  // Stage Θ's are O(h), so the dropped term is O(h⁴) in Θ̇ and O(h⁵) per step.
  const auto theta_dot = [](const Eigen::Vector3d& th, const Eigen::Vector3d& w) -> Eigen::Vector3d {
    const Eigen::Vector3d tw = th.cross(w);
    return w + 0.5 * tw + th.cross(tw) / 12.0;
  };
  const Eigen::Vector3d z = Eigen::Vector3d::Zero();
  const Eigen::Vector3d& w0 = st.w_B;
  // Stage i: Θ_i, ω_i (the state exp(Θ_i) R0, ω_i) → (Θ̇, ω̇).
  const Eigen::Vector3d k1t = w0;
  const Eigen::Vector3d k1w = euler_rhs<double>(I_B, w0, z);
  const Eigen::Vector3d th2 = 0.5 * h * k1t, w2 = w0 + 0.5 * h * k1w;
  const Eigen::Vector3d k2t = theta_dot(th2, w2), k2w = euler_rhs<double>(I_B, w2, z);
  const Eigen::Vector3d th3 = 0.5 * h * k2t, w3 = w0 + 0.5 * h * k2w;
  const Eigen::Vector3d k3t = theta_dot(th3, w3), k3w = euler_rhs<double>(I_B, w3, z);
  const Eigen::Vector3d th4 = h * k3t, w4 = w0 + h * k3w;
  const Eigen::Vector3d k4t = theta_dot(th4, w4), k4w = euler_rhs<double>(I_B, w4, z);
  const Eigen::Vector3d theta = h / 6.0 * (k1t + 2.0 * k2t + 2.0 * k3t + k4t);
  return {(st.R_WB * step_rotation(theta)).renormalized(), w0 + h / 6.0 * (k1w + 2.0 * k2w + 2.0 * k3w + k4w)};
}

// Refuses a Moser–Veselov step whose iteration did not stop or left |q| ≥ 1: converged unless
// the residual r = h L/2 − q0 I q − q × I q is above round-off (or there is no q0).
void require_moser_veselov_converged(const Eigen::Vector3d& I_B, const FreeBodyState& st, double h,
                                     const Eigen::Vector3d& half_hL, const Eigen::Vector3d& q,
                                     double q0) {
  const Eigen::Vector3d Iq = I_B.cwiseProduct(q);
  const double residual = (half_hL - q0 * Iq - q.cross(Iq)).lpNorm<Eigen::Infinity>();
  const double hL_max = half_hL.lpNorm<Eigen::Infinity>();  // > 0: L = 0 stops at once
  // |h L/2|, q0 |Iq| and |q| |Iq| (the products of the cross product) are what the residual sums
  const double tolerance =
      kResidualUlps * kEps *
      (hL_max + (q0 + q.lpNorm<Eigen::Infinity>()) * Iq.lpNorm<Eigen::Infinity>());
  RIGID_REQUIRE_AS("step_free_body", q.squaredNorm() < 1.0 && residual <= tolerance,
                   "the Moser–Veselov step (moser_veselov) did not converge: h = {} s, |ω| = {} "
                   "rad/s; after {} fixed-point iterations the residual of its implicit equation, "
                   "|h L − 2 q0 I q − 2 q × I q|/(h |L|) = {:.3g} with |q| = {:.3g} (< 1 needed), "
                   "is above the tolerance {:.3g} (round-off); use a smaller step (the iteration "
                   "contracts for h |ω| max(I)/min(I) < 1, here {:.3g})",
                   h, st.w_B.norm(), kFixedPointIterations, residual / hL_max, q.norm(),
                   tolerance / hL_max, contraction_bound(I_B, st.w_B, h));
}

FreeBodyState step_moser_veselov(const Eigen::Vector3d& I_B, const FreeBodyState& st, double h) {
  // With Ω = R(q0, q): ΩJ − JΩᵀ = 2 (q × Iq)^ + 2 q0 (Iq)^ since q̂J + Jq̂ = (Iq)^ and
  // q qᵀJ − J q qᵀ = ((Jq) × q)^ = (q × Iq)^ for J = ½ tr(I) 1 − I. Solve
  //   h L = 2 q0 I q + 2 q × I q,  q0 = √(1 − |q|²)
  // by fixed-point iteration q ← I⁻¹ (h L/2 − q × Iq) / q0 from q = h ω/2 (a contraction
  // for h|ω| max(I)/min(I) < 1), to round-off.
  const Eigen::Vector3d L = I_B.cwiseProduct(st.w_B);
  const Eigen::Vector3d half_hL = 0.5 * h * L;
  Eigen::Vector3d q = 0.5 * h * st.w_B;
  double q0 = std::sqrt(std::max(0.0, 1.0 - q.squaredNorm()));
  bool stopped = false;
  for (int it = 0; it < kFixedPointIterations; ++it) {
    const Eigen::Vector3d next = (half_hL - q.cross(I_B.cwiseProduct(q))).cwiseQuotient(I_B) / q0;
    const double change = (next - q).lpNorm<Eigen::Infinity>();
    q = next;
    q0 = std::sqrt(std::max(0.0, 1.0 - q.squaredNorm()));
    if (change <= 1e-17 * (1.0 + q.lpNorm<Eigen::Infinity>())) {
      stopped = true;
      break;
    }
  }
  if (!stopped || !(q.squaredNorm() < 1.0)) [[unlikely]] {
    require_moser_veselov_converged(I_B, st, h, half_hL, q, q0);
  }
  const SO3d Omega = SO3d::from_quaternion(q0, q(0), q(1), q(2));
  // L_{k+1} = Ωᵀ L_k, R_{k+1} = R_k Ω (so L_W = R L is unchanged up to round-off).
  return {(st.R_WB * Omega).renormalized(), (Omega.inverse() * L).cwiseQuotient(I_B)};
}

}  // namespace

namespace detail {

const std::vector<AxisFlow>& splitting_flows(FreeBodyMethod method) {
  static const std::vector<AxisFlow> k2 = composition(0), k4 = composition(1), k6 = composition(2);
  if (method == FreeBodyMethod::kSplitting4) return k4;
  if (method == FreeBodyMethod::kSplitting6) return k6;
  return k2;
}

}  // namespace detail

FreeBodyMethod free_body_method_from_name(std::string_view name) {
  for (const auto& [n, m] : kMethods)
    if (n == name) return m;
  std::vector<std::string> names;
  for (const auto& [n, m] : kMethods) names.emplace_back(n);
  RIGID_THROW("unknown free-body method '{}'; expected one of rk4, splitting2, splitting4, "
              "splitting6, midpoint, rkmk4, moser_veselov{}",
              name, did_you_mean_hint(name, names));
}

std::string_view name_of(FreeBodyMethod method) {
  for (const auto& [n, m] : kMethods)
    if (m == method) return n;
  RIGID_ASSERT(false);
  return {};
}

int order_of(FreeBodyMethod method) {
  switch (method) {
    case FreeBodyMethod::kRk4:
    case FreeBodyMethod::kSplitting4:
    case FreeBodyMethod::kRkmk4:
      return 4;
    case FreeBodyMethod::kSplitting2:
    case FreeBodyMethod::kLiePoissonMidpoint:
    case FreeBodyMethod::kMoserVeselov:
      return 2;
    case FreeBodyMethod::kSplitting6:
      return 6;
  }
  return 0;
}

FreeBodyState step_free_body(FreeBodyMethod method, const Eigen::Vector3d& I_B,
                             const FreeBodyState& state, double h) {
  switch (method) {
    case FreeBodyMethod::kRk4:
      return step_rk4(I_B, state, h);
    case FreeBodyMethod::kLiePoissonMidpoint:
      return step_midpoint(I_B, state, h);
    case FreeBodyMethod::kRkmk4:
      return step_rkmk4(I_B, state, h);
    case FreeBodyMethod::kMoserVeselov:
      return step_moser_veselov(I_B, state, h);
    default:
      break;
  }
  return step_splitting(detail::splitting_flows(method), I_B, state, h);
}

std::optional<integrate::NonFinite> find_nonfinite(const FreeBodyState& s, std::string_view owner) {
  // fast path, every step: a NaN or an infinity makes the sum non-finite (finite values whose
  // sum overflows fall through to the scan, which then finds nothing)
  if (std::isfinite(s.R_WB.quaternion().sum() + s.w_B.sum())) [[likely]] return std::nullopt;
  static constexpr const char* kNames[7] = {"R_WB.w", "R_WB.x", "R_WB.y", "R_WB.z",
                                            "w_B.x",  "w_B.y",  "w_B.z"};
  const Eigen::Vector4d q = s.R_WB.quaternion();
  const double values[7] = {q(0), q(1), q(2), q(3), s.w_B(0), s.w_B(1), s.w_B(2)};
  if (auto i = integrate::first_nonfinite(values)) [[unlikely]] {
    return integrate::NonFinite{std::string(owner), kNames[*i], values[*i]};
  }
  return std::nullopt;
}

FreeBodyDiagnostics diagnose(const Eigen::Vector3d& I_B, const FreeBodyState& state) {
  FreeBodyDiagnostics d;
  d.energy = rotational_energy<double>(I_B, state.w_B);
  const Eigen::Matrix3d R_WB = state.R_WB.matrix();
  d.L_W = R_WB * I_B.cwiseProduct(state.w_B);
  d.orthonormality_error =
      (R_WB.transpose() * R_WB - Eigen::Matrix3d::Identity()).lpNorm<Eigen::Infinity>();
  return d;
}

FreeBodyTrajectory simulate_free_body(FreeBodyMethod method, const Eigen::Vector3d& I_B,
                                      const FreeBodyState& initial, double h_max,
                                      const std::vector<double>& output_times,
                                      const integrate::MarchControl& control) {
  if (auto report = check_rotational_moments(I_B)) RIGID_THROW("{}", *report);
  if (auto bad = find_nonfinite(initial)) {
    RIGID_THROW("the initial state is not finite: {} = {}", bad->component, bad->value);
  }
  const integrate::TimeGrid grid = integrate::TimeGrid::from_times(0.0, output_times);
  FreeBodyTrajectory traj;
  FreeBodyState s = initial;
  (void)integrate::march(
      grid, h_max, [&](double, double h) { s = step_free_body(method, I_B, s, h); },
      [&] { return find_nonfinite(s); },
      [&](std::size_t, double t) {
        traj.t.push_back(t);
        traj.states.push_back(s);
        traj.diagnostics.push_back(diagnose(I_B, s));
      },
      control);
  return traj;
}

}  // namespace rigid::body
