#pragma once
// MuJoCo (libmujoco, Debian's libmujoco-dev) as the independent reference of the tests that
// link it: its models and data owned by unique_ptr, a model loaded from a file with the
// loader's message on failure (support/mjcf_text.hpp: the file without its free joints).

#include <filesystem>
#include <memory>
#include <string>

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

}  // namespace rigid::test
