#include "rigid/body/free_body_integrators.hpp"

#include <array>
#include <cmath>

#include "rigid/body/euler.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"

namespace rigid::body {

namespace {

constexpr std::array<std::pair<std::string_view, FreeBodyMethod>, 7> kMethods{{
    {"rk4", FreeBodyMethod::kRk4},
    {"splitting2", FreeBodyMethod::kSplitting2},
    {"splitting4", FreeBodyMethod::kSplitting4},
    {"splitting6", FreeBodyMethod::kSplitting6},
    {"midpoint", FreeBodyMethod::kLiePoissonMidpoint},
    {"rkmk4", FreeBodyMethod::kRkmk4},
    {"moser_veselov", FreeBodyMethod::kMoserVeselov},
}};

struct Rk4Deriv {
  Eigen::Vector4d qdot;  // (w, x, y, z)
  Eigen::Vector3d wdot;
};

Eigen::Vector4d coeffs_wxyz(const Eigen::Quaterniond& q) { return {q.w(), q.x(), q.y(), q.z()}; }
Eigen::Quaterniond from_wxyz(const Eigen::Vector4d& c) { return {c(0), c(1), c(2), c(3)}; }

Rk4Deriv rk4_deriv(const Eigen::Vector3d& I_B, const Eigen::Vector4d& q, const Eigen::Vector3d& w) {
  // q̇ = ½ q ⊗ (0, ω_B)
  const Eigen::Quaterniond qq = from_wxyz(q);
  const Eigen::Quaterniond wq(0.0, w(0), w(1), w(2));
  const Eigen::Quaterniond prod = qq * wq;
  return {0.5 * coeffs_wxyz(prod), euler_rhs<double>(I_B, w, Eigen::Vector3d::Zero())};
}

FreeBodyState step_rk4(const Eigen::Vector3d& I_B, const FreeBodyState& s, double h) {
  const Eigen::Vector4d q0 = coeffs_wxyz(s.q_WB);
  const Eigen::Vector3d& w0 = s.w_B;
  const Rk4Deriv k1 = rk4_deriv(I_B, q0, w0);
  const Rk4Deriv k2 = rk4_deriv(I_B, q0 + 0.5 * h * k1.qdot, w0 + 0.5 * h * k1.wdot);
  const Rk4Deriv k3 = rk4_deriv(I_B, q0 + 0.5 * h * k2.qdot, w0 + 0.5 * h * k2.wdot);
  const Rk4Deriv k4 = rk4_deriv(I_B, q0 + h * k3.qdot, w0 + h * k3.wdot);
  FreeBodyState out;
  out.q_WB = from_wxyz(q0 + h / 6.0 * (k1.qdot + 2.0 * k2.qdot + 2.0 * k3.qdot + k4.qdot));
  out.w_B = w0 + h / 6.0 * (k1.wdot + 2.0 * k2.wdot + 2.0 * k3.wdot + k4.wdot);
  return out;
}

// Exact flow of H_i = L_i²/(2 I_i) for time h: ω_i = L_i / I_i is constant;
// L_B turns by −h ω_i about e_i, the body by +h ω_i.
void axis_flow(int i, const Eigen::Vector3d& I_B, Eigen::Quaterniond& q, Eigen::Vector3d& L, double h) {
  const double theta = h * L(i) / I_B(i);
  const double c = std::cos(theta), s = std::sin(theta);
  const int j = (i + 1) % 3, k = (i + 2) % 3;
  const double Lj = L(j), Lk = L(k);
  L(j) = c * Lj + s * Lk;
  L(k) = -s * Lj + c * Lk;
  const double ch = std::cos(0.5 * theta), sh = std::sin(0.5 * theta);
  Eigen::Quaterniond r(ch, 0, 0, 0);
  r.vec()(i) = sh;
  q = q * r;
}

void strang(const Eigen::Vector3d& I_B, Eigen::Quaterniond& q, Eigen::Vector3d& L, double h) {
  axis_flow(0, I_B, q, L, 0.5 * h);
  axis_flow(1, I_B, q, L, 0.5 * h);
  axis_flow(2, I_B, q, L, h);
  axis_flow(1, I_B, q, L, 0.5 * h);
  axis_flow(0, I_B, q, L, 0.5 * h);
}

// Triple-jump composition [Yoshida1990]: order p → p + 2 with
// γ1 = 1/(2 − 2^{1/(p+1)}), γ0 = 1 − 2γ1.
void yoshida4(const Eigen::Vector3d& I_B, Eigen::Quaterniond& q, Eigen::Vector3d& L, double h) {
  const double g1 = 1.0 / (2.0 - std::cbrt(2.0));
  const double g0 = 1.0 - 2.0 * g1;
  strang(I_B, q, L, g1 * h);
  strang(I_B, q, L, g0 * h);
  strang(I_B, q, L, g1 * h);
}

void yoshida6(const Eigen::Vector3d& I_B, Eigen::Quaterniond& q, Eigen::Vector3d& L, double h) {
  const double g1 = 1.0 / (2.0 - std::pow(2.0, 0.2));
  const double g0 = 1.0 - 2.0 * g1;
  yoshida4(I_B, q, L, g1 * h);
  yoshida4(I_B, q, L, g0 * h);
  yoshida4(I_B, q, L, g1 * h);
}

FreeBodyState step_midpoint(const Eigen::Vector3d& I_B, const FreeBodyState& s, double h) {
  // L1 = L0 + h L̄ × ω̄, L̄ = (L0 + L1)/2, ω̄ = I⁻¹ L̄: keeps every quadratic
  // invariant (|L|², 2E) of the Lie–Poisson system. Fixed-point iteration,
  // a contraction for h|ω|·max(I)/min(I) < 1.
  const Eigen::Vector3d L0 = I_B.cwiseProduct(s.w_B);
  Eigen::Vector3d L1 = L0;
  for (int it = 0; it < 100; ++it) {
    const Eigen::Vector3d Lm = 0.5 * (L0 + L1);
    const Eigen::Vector3d next = L0 + h * Lm.cross(Lm.cwiseQuotient(I_B));
    const double change = (next - L1).lpNorm<Eigen::Infinity>();
    L1 = next;
    if (change <= 1e-16 * L0.lpNorm<Eigen::Infinity>()) break;
  }
  const Eigen::Vector3d wm = (0.5 * (L0 + L1)).cwiseQuotient(I_B);
  const double angle = h * wm.norm();
  FreeBodyState out;
  out.q_WB = angle > 0 ? s.q_WB * Eigen::Quaterniond(Eigen::AngleAxisd(angle, wm.normalized()))
                       : s.q_WB;
  out.q_WB.normalize();
  out.w_B = L1.cwiseQuotient(I_B);
  return out;
}

// Unit quaternion exp(θ̂/2 …): the rotation by the vector θ (rad), Taylor-safe at 0
// (sin(|θ|/2)/|θ| = ½ − |θ|²/48 + …).
Eigen::Quaterniond quat_exp(const Eigen::Vector3d& theta) {
  const double a2 = theta.squaredNorm();
  const double a = std::sqrt(a2);
  const double s = a2 < 1e-12 ? 0.5 - a2 / 48.0 : std::sin(0.5 * a) / a;
  return {std::cos(0.5 * a), s * theta(0), s * theta(1), s * theta(2)};
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
  FreeBodyState out;
  out.q_WB = (st.q_WB * quat_exp(theta)).normalized();
  out.w_B = w0 + h / 6.0 * (k1w + 2.0 * k2w + 2.0 * k3w + k4w);
  return out;
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
  for (int it = 0; it < 100; ++it) {
    const Eigen::Vector3d next = (half_hL - q.cross(I_B.cwiseProduct(q))).cwiseQuotient(I_B) / q0;
    const double change = (next - q).lpNorm<Eigen::Infinity>();
    q = next;
    q0 = std::sqrt(std::max(0.0, 1.0 - q.squaredNorm()));
    if (change <= 1e-17 * (1.0 + q.lpNorm<Eigen::Infinity>())) break;
  }
  RIGID_REQUIRE(q.squaredNorm() < 1.0,
                "Moser–Veselov step did not converge (h = {} s too large for |ω| = {} rad/s); "
                "use a smaller step",
                h, st.w_B.norm());
  const Eigen::Quaterniond Omega(q0, q(0), q(1), q(2));
  // L_{k+1} = Ωᵀ L_k, R_{k+1} = R_k Ω (so L_W = R L is unchanged up to round-off).
  FreeBodyState out;
  out.q_WB = (st.q_WB * Omega).normalized();
  out.w_B = (Omega.conjugate() * L).cwiseQuotient(I_B);
  return out;
}

}  // namespace

FreeBodyMethod free_body_method_from_name(std::string_view name) {
  for (const auto& [n, m] : kMethods)
    if (n == name) return m;
  RIGID_THROW("unknown free-body method '{}'; expected one of rk4, splitting2, splitting4, "
              "splitting6, midpoint, rkmk4, moser_veselov",
              name);
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
  Eigen::Quaterniond q = state.q_WB;
  Eigen::Vector3d L = I_B.cwiseProduct(state.w_B);
  if (method == FreeBodyMethod::kSplitting2) strang(I_B, q, L, h);
  else if (method == FreeBodyMethod::kSplitting4) yoshida4(I_B, q, L, h);
  else yoshida6(I_B, q, L, h);
  // Products of unit quaternions stay unit up to round-off, which would random-walk;
  // renormalising keeps ‖RᵀR − 1‖ at a few ulps for any number of steps.
  q.normalize();
  return {q, L.cwiseQuotient(I_B)};
}

FreeBodyDiagnostics diagnose(const Eigen::Vector3d& I_B, const FreeBodyState& state) {
  FreeBodyDiagnostics d;
  d.energy = rotational_energy<double>(I_B, state.w_B);
  // Rotation matrix of a possibly non-unit quaternion, not renormalised, so the
  // defect shows |q| drift: R = (w² − v·v) 1 + 2 v vᵀ + 2 w v̂.
  const double w = state.q_WB.w();
  const Eigen::Vector3d v = state.q_WB.vec();
  Eigen::Matrix3d vhat;
  vhat << 0, -v(2), v(1), v(2), 0, -v(0), -v(1), v(0), 0;
  const Eigen::Matrix3d R_WB =
      (w * w - v.squaredNorm()) * Eigen::Matrix3d::Identity() + 2.0 * v * v.transpose() + 2.0 * w * vhat;
  d.L_W = R_WB * I_B.cwiseProduct(state.w_B);
  d.orthonormality_error =
      (R_WB.transpose() * R_WB - Eigen::Matrix3d::Identity()).lpNorm<Eigen::Infinity>();
  return d;
}

FreeBodyTrajectory simulate_free_body(FreeBodyMethod method, const Eigen::Vector3d& I_B,
                                      const FreeBodyState& initial, double h_max,
                                      const std::vector<double>& output_times) {
  RIGID_REQUIRE(I_B.allFinite() && (I_B.array() > 0).all(),
                "principal moments must be finite and > 0 kg·m², got {}", rigid::to_string(I_B.transpose()));
  RIGID_REQUIRE(std::isfinite(h_max) && h_max > 0, "step h_max must be finite and > 0 s, got {}", h_max);
  RIGID_REQUIRE(initial.w_B.allFinite() && initial.q_WB.coeffs().allFinite() &&
                    std::abs(initial.q_WB.norm() - 1.0) < 1e-9,
                "initial state must be finite with a unit quaternion, got |q| = {}", initial.q_WB.norm());
  FreeBodyTrajectory traj;
  FreeBodyState s = initial;
  double t = 0;
  for (std::size_t i = 0; i < output_times.size(); ++i) {
    const double t_out = output_times[i];
    RIGID_REQUIRE(std::isfinite(t_out) && t_out >= t,
                  "output times must be finite, ≥ 0 and ascending; entry {} is {} after {}", i, t_out, t);
    const double span = t_out - t;
    const auto n = static_cast<long>(std::ceil(span / h_max - 1e-12));
    for (long k = 0; k < n; ++k) s = step_free_body(method, I_B, s, span / static_cast<double>(n));
    t = t_out;
    traj.t.push_back(t);
    traj.states.push_back(s);
    traj.diagnostics.push_back(diagnose(I_B, s));
  }
  return traj;
}

}  // namespace rigid::body
