#include "rigid/io/atomic_file.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "support/expect_error.hpp"

namespace rigid::io {
namespace {

namespace fs = std::filesystem;

fs::path scratch_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("rigid_io_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(AtomicFile, WritesAndReplacesWholeFile) {
  const fs::path dir = scratch_dir("replace");
  const fs::path file = dir / "out.txt";
  write_file_atomically(file, "first version, long");
  EXPECT_EQ(slurp(file), "first version, long");
  write_file_atomically(file, "second");
  EXPECT_EQ(slurp(file), "second");
  // Only the target is left: no temporary files.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(AtomicFile, MissingDirectoryIsAnErrorAndLeavesNothing) {
  const fs::path dir = scratch_dir("missing");
  EXPECT_RIGID_ERROR(write_file_atomically(dir / "no" / "such.csv", "x"),
                     "directory '" + (dir / "no").string() + "' does not exist");
  EXPECT_FALSE(fs::exists(dir / "no"));
}

TEST(AtomicFile, UnwritableTargetKeepsOldContents) {
  const fs::path dir = scratch_dir("dir_target");
  // A directory where the file should go: the rename fails, the temp file is removed.
  fs::create_directories(dir / "taken");
  fs::create_directories(dir / "taken" / "child");
  EXPECT_RIGID_ERROR(write_file_atomically(dir / "taken", "x"), "cannot write");
  EXPECT_TRUE(fs::is_directory(dir / "taken"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

}  // namespace
}  // namespace rigid::io
