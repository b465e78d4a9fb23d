#pragma once
// The N-link planar pendulum of the lagrange benchmarks: point masses m_k = 1 kg on massless
// rods l_k = 1 m (lengths kept as parameters), g = 9.81 m/s².
#include <string>

#include <fmt/format.h>

#include "rigid/lagrange/system.hpp"

namespace rigid::bench {

inline constexpr double kChainGravity = 9.81;

inline lagrange::SystemSpec chain_spec(int n) {
  lagrange::SystemSpec spec;
  std::string x = "0", y = "0";
  for (int i = 1; i <= n; ++i) {
    spec.parameters.push_back({fmt::format("l{}", i), 1.0});
    spec.coordinates.push_back({fmt::format("q{}", i), 0.1 * i, 0.0});
    x = fmt::format("{} + l{}*sin(q{})", x, i, i);
    y = fmt::format("{} - l{}*cos(q{})", y, i, i);
    spec.bodies.push_back(lagrange::Body{
        fmt::format("bob{}", i),
        MassProperties(1.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero()),
        {x, y, "0"}, {}});
  }
  spec.gravity_W = Eigen::Vector3d(0, -kChainGravity, 0);
  return spec;
}

}  // namespace rigid::bench
