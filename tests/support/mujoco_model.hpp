#pragma once
// MuJoCo (libmujoco, Debian's libmujoco-dev) as the independent reference of the tests that
// link it: its models and data owned by unique_ptr, a model loaded from a file with the
// loader's message on failure (support/mjcf_text.hpp: the file without its free joints).

#include <filesystem>
#include <memory>
#include <random>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include "support/mjcf_text.hpp"

namespace rigid::test {

struct MjModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct MjDataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using MjModelPtr = std::unique_ptr<mjModel, MjModelDeleter>;
using MjDataPtr = std::unique_ptr<mjData, MjDataDeleter>;

/// MuJoCo's model of an XML file (MJCF or URDF); null, with a test failure naming the file and
/// MuJoCo's message, when it does not load.
inline MjModelPtr load_mujoco(const std::filesystem::path& path) {
  char error[1000] = "";
  MjModelPtr m(mj_loadXML(path.c_str(), nullptr, error, sizeof error));
  EXPECT_NE(m, nullptr) << path << ": " << error;
  return m;
}

/// A uniformly distributed rotation (a normalised 4-D Gaussian).
inline Eigen::Quaterniond random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n;
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
}

/// A random state of MuJoCo's model: unit quaternions for ball and free joints, a free joint's
/// position near its placement, hinge and slide amounts within their range (or ±2 when not
/// limited), every velocity in [−2, 2].
inline void random_state(const mjModel* m, std::mt19937& rng, Eigen::VectorXd& q, Eigen::VectorXd& v) {
  std::uniform_real_distribution<double> u(-1, 1), unit(0, 1);
  q.resize(m->nq);
  v.resize(m->nv);
  for (int j = 0; j < m->njnt; ++j) {
    const int a = m->jnt_qposadr[j];
    switch (m->jnt_type[j]) {
      case mjJNT_FREE: {
        for (int k = 0; k < 3; ++k) q(a + k) = m->qpos0[a + k] + u(rng);
        const Eigen::Quaterniond r = random_rotation(rng);
        q.segment<4>(a + 3) << r.w(), r.x(), r.y(), r.z();
        break;
      }
      case mjJNT_BALL: {
        const Eigen::Quaterniond r = random_rotation(rng);
        q.segment<4>(a) << r.w(), r.x(), r.y(), r.z();
        break;
      }
      default: {
        const double lo = m->jnt_limited[j] ? m->jnt_range[2 * j] : -2;
        const double hi = m->jnt_limited[j] ? m->jnt_range[2 * j + 1] : 2;
        q(a) = lo + (hi - lo) * unit(rng);
      }
    }
  }
  for (int i = 0; i < m->nv; ++i) v(i) = 2 * u(rng);
}

}  // namespace rigid::test
