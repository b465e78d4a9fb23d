#pragma once

// The bodies of a tree as its recursions take them (recursive.cpp); System::Impl keeps them
// for the recursions the export derives when asked (the body-coordinate inverse dynamics).

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <ginac/ginac.h>

#include "symbolic.hpp"

namespace rigid::lagrange::detail {

/// A joint of a tree body: a turn about, or a slide along, the unit `axis` (in the frame the
/// joint starts from) through `anchor`, by the coordinate number `coordinate` (its velocity's
/// index, which is its index in q but after a ball); or a ball about `anchor`, its quaternion
/// q[quaternion … quaternion + 3] (w x y z), its ω (in the frame after it) the velocities
/// coordinate … coordinate + 2.
struct TreeJoint {
  bool turn = true;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();
  std::size_t coordinate = 0;
  bool ball = false;
  std::size_t quaternion = 0;
};

/// A body of the tree: X_PB = Trans(position) · orientation · J₁ ⋯ J_m (as lagrange::Body),
/// its parent an earlier body (or −1, the world); mass, COM and inertia about the COM in B.
struct TreeBody {
  std::string name;
  int parent = -1;
  Vec3 position;
  Mat3 orientation;
  std::vector<TreeJoint> joints;
  GiNaC::ex mass;
  Vec3 com;
  Mat3 inertia;
};

}  // namespace rigid::lagrange::detail
