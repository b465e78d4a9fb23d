#include "rigid/io/atomic_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <utility>
#include <system_error>

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <fmt/format.h>

#include "detail/temporary.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/escape.hpp"

namespace rigid::io {
namespace {

// POSIX file descriptors are used (not std::ofstream) because only they give both a
// reliable error code for every step and fsync before the rename.
std::string errno_text() { return std::strerror(errno); }

// The messages name the path, which is what a user acts on; no function name.
template <typename... Args>
void require(bool ok, fmt::format_string<Args...> format, Args&&... args) {
  if (!ok) [[unlikely]] throw Error(fmt::format(format, std::forward<Args>(args)...));
}

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

namespace detail {

namespace {
constexpr std::string_view kTag = ".rigid-tmp-";
}  // namespace

std::string temporary_name(std::string_view name) {
  std::random_device seed;
  return fmt::format(".{}{}{}-{:08x}", name, kTag, static_cast<long>(::getpid()), seed());
}

bool is_temporary_of(std::string_view entry, std::string_view name) {
  const std::string prefix = fmt::format(".{}{}", name, kTag);
  return entry.size() > prefix.size() && entry.substr(0, prefix.size()) == prefix;
}

void remove_stale_temporaries(const std::filesystem::path& dir, std::string_view name) {
  std::error_code ec;
  std::filesystem::directory_iterator it(dir, ec), end;
  const std::size_t skip = name.size() + 1 + kTag.size();
  for (; !ec && it != end; it.increment(ec)) {
    const std::string entry = it->path().filename().string();
    if (!is_temporary_of(entry, name)) continue;
    // the process id follows the tag; a process that no longer exists left it behind
    const long pid = std::strtol(entry.c_str() + skip, nullptr, 10);
    if (pid <= 0 || pid == static_cast<long>(::getpid())) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;
    std::error_code ignored;
    std::filesystem::remove_all(it->path(), ignored);
  }
}

}  // namespace detail

namespace {

// What a non-regular file is, in words.
const char* kind_of(std::filesystem::file_type type) {
  switch (type) {
    case std::filesystem::file_type::directory:
      return "a directory";
    case std::filesystem::file_type::fifo:
      return "a FIFO (named pipe)";
    case std::filesystem::file_type::socket:
      return "a socket";
    case std::filesystem::file_type::character:
      return "a character device";
    case std::filesystem::file_type::block:
      return "a block device";
    default:
      return "a file of unknown type";
  }
}

// The same limit as the kernel's path resolution (Linux MAXSYMLINKS, ELOOP beyond it).
constexpr int kMaxLinks = 40;

}  // namespace

std::filesystem::path check_output_file(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  require(!path.empty(), "the output path is empty");
  const std::string shown = escaped(path.string());
  fs::path target = path;
  fs::file_status status;
  for (int links = 0;; ++links) {
    std::error_code ec;
    status = fs::symlink_status(target, ec);
    require(!ec || status.type() == fs::file_type::not_found, "cannot write '{}': {}",
            shown, ec.message());
    if (!fs::is_symlink(status)) break;
    require(links < kMaxLinks, "cannot write '{}': more than {} symbolic links to follow",
            shown, kMaxLinks);
    const fs::path link = fs::read_symlink(target, ec);
    require(!ec, "cannot write '{}': {}", shown, ec.message());
    // a relative link is relative to the directory that holds it
    target = link.is_absolute() ? link : target.parent_path() / link;
  }
  const std::string through =
      target == path ? std::string() : fmt::format(" (a symbolic link to '{}')", escaped(target.string()));
  require(fs::is_regular_file(status) || status.type() == fs::file_type::not_found,
          "cannot write '{}'{}: it is {}, not a regular file; expected a regular file to "
          "replace or a new name",
          shown, through, kind_of(status.type()));
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  require(fs::is_directory(dir, ec), "cannot write '{}'{}: directory '{}' does not exist",
          shown, through, escaped(dir.string()));
  return target;
}

void write_file_atomically(const std::filesystem::path& path, std::string_view contents) {
  // a link is written through: the temporary goes next to the file it names
  const std::filesystem::path target = check_output_file(path);
  const std::filesystem::path dir =
      target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");

  detail::remove_stale_temporaries(dir, target.filename().string());
  TempFile tmp(dir / detail::temporary_name(target.filename().string()));
  tmp.fd() = ::open(tmp.path().c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  require(tmp.fd() >= 0, "cannot write '{}': {}", path.string(), errno_text());

  const char* data = contents.data();
  std::size_t left = contents.size();
  while (left > 0) {
    const ssize_t n = ::write(tmp.fd(), data, left);
    if (n < 0 && errno == EINTR) continue;
    require(n > 0, "cannot write '{}': {}", path.string(), errno_text());
    data += n;
    left -= static_cast<std::size_t>(n);
  }
  require(::fsync(tmp.fd()) == 0, "cannot write '{}': {}", path.string(), errno_text());
  const int fd = tmp.fd();
  tmp.fd() = -1;
  require(::close(fd) == 0, "cannot write '{}': {}", path.string(), errno_text());
  require(std::rename(tmp.path().c_str(), target.c_str()) == 0, "cannot write '{}': {}",
          path.string(), errno_text());
  tmp.commit();
}

}  // namespace rigid::io
