#include "rigid/io/atomic_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

#include "rigid/common/error.hpp"

namespace rigid::io {
namespace {

// POSIX file descriptors are used (not std::ofstream) because only they give both a
// reliable error code for every step and fsync before the rename.
std::string errno_text() { return std::strerror(errno); }

class TempFile {
 public:
  explicit TempFile(std::filesystem::path path) : path_(std::move(path)) {}
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  ~TempFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!committed_) {
      std::error_code ignored;
      std::filesystem::remove(path_, ignored);
    }
  }
  int& fd() { return fd_; }
  const std::filesystem::path& path() const { return path_; }
  void commit() { committed_ = true; }

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  bool committed_ = false;
};

}  // namespace

void write_file_atomically(const std::filesystem::path& path, std::string_view contents) {
  RIGID_REQUIRE(!path.empty(), "the output path is empty");
  const std::filesystem::path dir =
      path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  RIGID_REQUIRE(std::filesystem::is_directory(dir, ec),
                "cannot write '{}': directory '{}' does not exist", path.string(), dir.string());

  std::random_device seed;
  TempFile tmp(dir / fmt::format(".{}.tmp{:08x}", path.filename().string(), seed()));
  tmp.fd() = ::open(tmp.path().c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  RIGID_REQUIRE(tmp.fd() >= 0, "cannot write '{}': {}", path.string(), errno_text());

  const char* data = contents.data();
  std::size_t left = contents.size();
  while (left > 0) {
    const ssize_t n = ::write(tmp.fd(), data, left);
    if (n < 0 && errno == EINTR) continue;
    RIGID_REQUIRE(n > 0, "cannot write '{}': {}", path.string(), errno_text());
    data += n;
    left -= static_cast<std::size_t>(n);
  }
  RIGID_REQUIRE(::fsync(tmp.fd()) == 0, "cannot write '{}': {}", path.string(), errno_text());
  const int fd = tmp.fd();
  tmp.fd() = -1;
  RIGID_REQUIRE(::close(fd) == 0, "cannot write '{}': {}", path.string(), errno_text());
  RIGID_REQUIRE(std::rename(tmp.path().c_str(), path.c_str()) == 0, "cannot write '{}': {}",
                path.string(), errno_text());
  tmp.commit();
}

}  // namespace rigid::io
