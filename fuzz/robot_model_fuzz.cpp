// Fuzz target: io::read_robot_model on a URDF/MJCF/SDF document (the URDF tree and its refusals,
// MJCF bodies, joints, default classes, orientations, <include> of files that do not exist,
// inertials from geoms; SDF models and worlds, poses in their frames). What it reads must be a
// tree with proper parts: every parent comes before its child, rotations are rotations, axes
// are unit vectors, inertials are checked.
#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "fuzz_support.hpp"
#include "rigid/io/robot_model.hpp"

namespace {

bool proper(const rigid::io::RobotModel& m) {
  for (std::size_t i = 0; i < m.links.size(); ++i) {
    const auto& l = m.links[i];
    if (l.parent < -1 || l.parent >= static_cast<int>(i)) return false;
    const Eigen::Matrix3d RtR = l.rotation.transpose() * l.rotation;
    if (!((RtR - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <= 1e-9) ||
        !(std::abs(l.rotation.col(0).cross(l.rotation.col(1)).dot(l.rotation.col(2)) - 1) <=
          1e-9) ||
        !l.position.allFinite()) {
      return false;
    }
    for (const auto& j : l.joints) {
      if (!(std::abs(j.axis.norm() - 1) <= 1e-12) || !j.anchor.allFinite()) return false;
    }
    if (l.mass != 0 && rigid::MassProperties::check(l.mass, l.com, l.inertia_com)) return false;
  }
  // qpos and qvel: a free joint has 7 and 6 entries, a ball 4 and 3, hinge and slide 1 and 1
  return m.coordinate_names().size() == m.nq() && m.velocity_names().size() == m.nv() &&
         m.nv() <= m.nq() && m.dof() == m.nv();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input = rigid::fuzz::as_text(data, size);
  const std::string xml(input);
  for (const bool pin : {false, true}) {
    rigid::fuzz::refuse_or_return(input, [&] {
      // a name no file has: includes and meshes resolve to nothing on disk
      const auto m = rigid::io::read_robot_model(xml, "/nonexistent-rigid-fuzz/model.xml",
                                                 {.pin_free_root = pin});
      if (!proper(m)) {
        std::fprintf(stderr, "rigid fuzz: read_robot_model read an improper tree:\n%s\n",
                     xml.c_str());
        std::abort();
      }
    });
  }
  return 0;
}
