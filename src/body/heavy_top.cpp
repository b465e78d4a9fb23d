#include "rigid/body/heavy_top.hpp"

#include <Eigen/Geometry>

#include "rigid/body/euler.hpp"
#include "rigid/common/error.hpp"

namespace rigid::body {

double heavy_top_energy(const HeavyTop& top, const FreeBodyState& state) {
  const Eigen::Vector3d p_PC_W = state.q_WB * top.p_PC_B;
  return rotational_energy<double>(top.I_B, state.w_B) - top.mass * top.g_W.dot(p_PC_W);
}

Eigen::Vector3d heavy_top_torque_body(const HeavyTop& top, const Eigen::Quaterniond& q_WB) {
  const Eigen::Vector3d g_B = q_WB.conjugate() * top.g_W;
  return top.p_PC_B.cross(top.mass * g_B);
}

FreeBodyState step_heavy_top(const HeavyTop& top, const FreeBodyState& state, double h,
                             FreeBodyMethod free_method) {
  RIGID_REQUIRE(free_method != FreeBodyMethod::kRk4 && free_method != FreeBodyMethod::kLiePoissonMidpoint,
                "heavy-top free flow must be a splitting method (splitting2/4/6), got '{}'",
                name_of(free_method));
  FreeBodyState s = state;
  s.w_B += 0.5 * h * heavy_top_torque_body(top, s.q_WB).cwiseQuotient(top.I_B);
  s = step_free_body(free_method, top.I_B, s, h);
  s.w_B += 0.5 * h * heavy_top_torque_body(top, s.q_WB).cwiseQuotient(top.I_B);
  return s;
}

}  // namespace rigid::body
