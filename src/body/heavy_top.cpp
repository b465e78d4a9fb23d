#include "rigid/body/heavy_top.hpp"

#include <Eigen/LU>

#include "rigid/body/euler.hpp"
#include "body/detail/principal_frame.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"

namespace rigid::body {

void require_splitting(FreeBodyMethod free_method, std::string_view who) {
  if (free_method != FreeBodyMethod::kSplitting2 && free_method != FreeBodyMethod::kSplitting4 &&
      free_method != FreeBodyMethod::kSplitting6) {
    throw Error(fmt::format("{}: the free flow around a torque kick must be a splitting method "
                            "(splitting2, splitting4 or splitting6), got '{}'",
                            who, name_of(free_method)));
  }
}

HeavyTop::HeavyTop(const MassProperties& mass_B, const Eigen::Vector3d& pivot_B, const Eigen::Vector3d& g_W)
    : mass_(mass_B.mass()), pivot_B_(pivot_B), p_PC_B_(mass_B.com() - pivot_B), g_W_(g_W) {
  RIGID_REQUIRE(pivot_B.allFinite(), "the pivot must be finite, got {} m", rigid::to_string(pivot_B.transpose()));
  RIGID_REQUIRE(g_W.allFinite(), "gravity must be finite, got {} m/s²", rigid::to_string(g_W.transpose()));
  I_P_B_ = mass_B.inertia_about(pivot_B);
  const PrincipalFrame frame = principal_frame(I_P_B_, "HeavyTop", "about the pivot");
  I_P_ = frame.moments;
  R_BP_ = frame.R_BP;
  principal_is_body_ = frame.is_body;
  I_P_B_inv_ = I_P_B_.inverse();
}

double HeavyTop::energy(const FreeBodyState& s) const {
  return 0.5 * s.w_B.dot(I_P_B_ * s.w_B) - mass_ * g_W_.dot(s.R_WB * p_PC_B_);
}

Eigen::Vector3d HeavyTop::torque(const SO3d& R_WB) const {
  return p_PC_B_.cross(mass_ * (R_WB.inverse() * g_W_));
}

Eigen::Vector3d HeavyTop::angular_momentum_world(const FreeBodyState& s) const {
  return s.R_WB * (I_P_B_ * s.w_B);
}

FreeBodyState HeavyTop::step(const FreeBodyState& state, double h, FreeBodyMethod free_method) const {
  require_splitting(free_method, "heavy top");
  FreeBodyState s = state;
  // kick: ΔL_B = ½h τ_B with I fixed in B, so Δω_B = ½h I⁻¹ τ_B
  s.w_B += 0.5 * h * (I_P_B_inv_ * torque(s.R_WB));
  s = principal_is_body_ ? step_free_body(free_method, I_P_, s, h)
                         : from_principal(step_free_body(free_method, I_P_, to_principal(s, R_BP_), h), R_BP_);
  s.w_B += 0.5 * h * (I_P_B_inv_ * torque(s.R_WB));
  return s;
}

FreeBodyTrajectory HeavyTop::simulate(const FreeBodyState& initial, double h_max,
                                      const std::vector<double>& output_times,
                                      FreeBodyMethod free_method,
                                      const integrate::MarchControl& control) const {
  require_splitting(free_method, "heavy top");
  if (auto bad = find_nonfinite(initial)) {
    RIGID_THROW("the initial state is not finite: {} = {}", bad->component, bad->value);
  }
  FreeBodyTrajectory traj;
  FreeBodyState s = initial;
  (void)integrate::march(
      integrate::TimeGrid::from_times(0.0, output_times), h_max,
      [&](double, double h) { s = step(s, h, free_method); }, [&] { return find_nonfinite(s); },
      [&](std::size_t, double t) {
        traj.t.push_back(t);
        traj.states.push_back(s);
        FreeBodyDiagnostics d;
        d.energy = energy(s);
        d.L_W = angular_momentum_world(s);
        const Eigen::Matrix3d R = s.R_WB.matrix();
        d.orthonormality_error = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
        traj.diagnostics.push_back(d);
      },
      control);
  return traj;
}

}  // namespace rigid::body
