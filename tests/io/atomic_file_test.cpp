#include "rigid/io/atomic_file.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <unistd.h>

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

// The rename would put a regular file in the place of a FIFO, socket or device (as root,
// `-o /dev/null` replaced /dev/null): each is refused before anything is written, naming the
// path, what is there and what was expected, and is still there afterwards.
TEST(AtomicFile, SpecialFilesAreRefusedAndKept) {
  const fs::path dir = scratch_dir("special");
  const fs::path fifo = dir / "pipe.csv";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  EXPECT_RIGID_ERROR(write_file_atomically(fifo, "x"),
                     "cannot write '" + fifo.string() +
                         "': it is a FIFO (named pipe), not a regular file; expected a regular "
                         "file to replace or a new name");
  EXPECT_TRUE(fs::is_fifo(fifo));

  const fs::path socket_path = dir / "sock";
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  const std::string socket_name = socket_path.string();
  ASSERT_LT(socket_name.size(), sizeof(address.sun_path));
  std::copy(socket_name.begin(), socket_name.end(), address.sun_path);
  ASSERT_EQ(::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)), 0);
  EXPECT_RIGID_ERROR(write_file_atomically(socket_path, "x"), "it is a socket, not a regular file");
  EXPECT_TRUE(fs::is_socket(socket_path));
  ::close(fd);

  // a character device: /dev/null for a user (refused before the rename, which a user could not
  // do in /dev anyway); root makes its own null device (1, 3) here rather than risk /dev/null
  fs::path device = "/dev/null";
  if (::geteuid() == 0) {
    device = dir / "null";
    ASSERT_EQ(::mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 3)), 0);
  }
  EXPECT_RIGID_ERROR(write_file_atomically(device, "x"),
                     "'" + device.string() + "': it is a character device, not a regular file");
  EXPECT_TRUE(fs::is_character_file(device));
  // nothing else was made: no temporary left
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()),
            ::geteuid() == 0 ? 3 : 2);
}

// A symbolic link is written through: the file it names is replaced and the link stays.
TEST(AtomicFile, SymbolicLinksAreWrittenThrough) {
  const fs::path dir = scratch_dir("links");
  fs::create_directories(dir / "real");
  const fs::path file = dir / "real" / "out.txt";
  write_file_atomically(file, "old");
  // a relative link in another directory, and a link to that link
  fs::create_symlink("real/out.txt", dir / "link.txt");
  fs::create_symlink("link.txt", dir / "link2.txt");
  write_file_atomically(dir / "link2.txt", "new through two links");
  EXPECT_TRUE(fs::is_symlink(dir / "link.txt"));
  EXPECT_TRUE(fs::is_symlink(dir / "link2.txt"));
  EXPECT_EQ(fs::read_symlink(dir / "link.txt"), fs::path("real/out.txt"));
  EXPECT_EQ(slurp(file), "new through two links");
  // the temporary went next to the target: each directory holds only what it held
  EXPECT_EQ(std::distance(fs::directory_iterator(dir / "real"), fs::directory_iterator()), 1);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 3);

  // a dangling link: its target is created
  fs::create_symlink("real/new.txt", dir / "dangling.txt");
  write_file_atomically(dir / "dangling.txt", "made");
  EXPECT_TRUE(fs::is_symlink(dir / "dangling.txt"));
  EXPECT_EQ(slurp(dir / "real" / "new.txt"), "made");

  // a link to a FIFO or a directory is refused, naming the link's target
  const fs::path fifo = dir / "real" / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  fs::create_symlink(fifo, dir / "to_pipe");
  EXPECT_RIGID_ERROR(write_file_atomically(dir / "to_pipe", "x"),
                     "'" + (dir / "to_pipe").string() + "' (a symbolic link to '" + fifo.string() +
                         "'): it is a FIFO (named pipe)");
  EXPECT_TRUE(fs::is_symlink(dir / "to_pipe"));
  EXPECT_TRUE(fs::is_fifo(fifo));
  fs::create_directory_symlink("real", dir / "to_dir");
  EXPECT_RIGID_ERROR(write_file_atomically(dir / "to_dir", "x"), "it is a directory");
  EXPECT_TRUE(fs::is_symlink(dir / "to_dir"));

  // a loop is refused after the kernel's 40 links, not followed forever
  fs::create_symlink("loop_b", dir / "loop_a");
  fs::create_symlink("loop_a", dir / "loop_b");
  EXPECT_RIGID_ERROR(write_file_atomically(dir / "loop_a", "x"),
                     "more than 40 symbolic links to follow");
  EXPECT_TRUE(fs::is_symlink(dir / "loop_a"));
}

}  // namespace
}  // namespace rigid::io
