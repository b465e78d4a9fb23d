#include "detail/read_text.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <system_error>

#include <fmt/format.h>

#include "rigid/common/error.hpp"
#include "rigid/mesh/read_mesh.hpp"

namespace rigid::mesh::detail {

void fail_line(const std::string& path, int line, const std::string& msg) {
  rigid::detail::throw_error_at(SourceLocation{path, line, 0}, msg);
}

void fail_byte(const std::string& path, std::uint64_t byte, const std::string& msg) {
  rigid::detail::throw_error_at(SourceLocation{path, 0, 0}, fmt::format("byte {}: {}", byte, msg));
}

void fail_file(const std::string& path, const std::string& msg) {
  rigid::detail::throw_error_at(SourceLocation{path, 0, 0}, msg);
}

std::uint64_t mesh_file_size(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);  // follows symbolic links
  if (st.type() == fs::file_type::not_found) fail_file(path, "cannot open the file: no such file");
  if (ec) fail_file(path, fmt::format("cannot open the file: {}", ec.message()));
  if (st.type() == fs::file_type::directory) {
    fail_file(path, "is a directory: expected a mesh file");
  }
  if (st.type() != fs::file_type::regular) {
    // a device (/dev/zero, /dev/urandom) or a pipe never ends: refused before it is opened
    fail_file(path, "is not a regular file (a device, FIFO or socket): expected a mesh file");
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) fail_file(path, fmt::format("cannot read the file's size: {}", ec.message()));
  if (size == 0) fail_file(path, "the file is empty: expected a mesh");
  if (size > kMaxMeshFileBytes) {
    fail_file(path, fmt::format("the file has {} bytes, more than the limit of {} bytes (2 GiB) "
                                "for a mesh file",
                                size, kMaxMeshFileBytes));
  }
  return size;
}

std::string slurp(const std::string& path) {
  const std::uint64_t size = mesh_file_size(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) fail_file(path, "cannot open the file for reading");
  std::string data(static_cast<std::size_t>(size), '\0');
  if (!in.read(data.data(), static_cast<std::streamsize>(data.size()))) {
    fail_file(path, "reading the file failed (did it shrink while being read?)");
  }
  return data;
}

std::optional<double> parse_double(std::string_view t) {
  if (t.size() > 1 && t.front() == '+' && t[1] != '-' && t[1] != '+') t.remove_prefix(1);
  double v = 0;
  const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (t.empty() || p != t.data() + t.size()) return std::nullopt;
  if (ec == std::errc::result_out_of_range) {
    // from_chars leaves v unset: strtod tells overflow (±HUGE_VAL, refused as not finite)
    // from underflow (a value that rounds to zero or a subnormal, kept)
    const std::string s(t);
    return std::strtod(s.c_str(), nullptr);
  }
  if (ec != std::errc()) return std::nullopt;
  return v;
}

std::optional<std::string_view> Tokens::next() {
  skip();
  if (pos_ >= text_.size()) return std::nullopt;
  const std::size_t start = pos_;
  while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  token_line_ = line_;
  return std::string_view(text_).substr(start, pos_ - start);
}

std::string_view Tokens::expect(const char* what) {
  auto t = next();
  if (!t) fail_line(path_, line_, fmt::format("unexpected end of file: expected {}", what));
  return *t;
}

double Tokens::number(const char* what, bool finite) {
  const std::string_view t = expect(what);
  const std::optional<double> v = parse_double(t);
  if (!v) {
    fail_line(path_, token_line_, fmt::format("'{}' is not a number: expected {}",
                                              t.substr(0, 40), what));
  }
  if (finite && !std::isfinite(*v)) {
    fail_line(path_, token_line_,
              fmt::format("{} is {}: expected a finite number", what, t.substr(0, 40)));
  }
  return *v;
}

long long Tokens::integer(const char* what) {
  const std::string_view t = expect(what);
  long long v = 0;
  const char* b = t.data() + (t.size() > 1 && t.front() == '+' ? 1 : 0);
  const auto [p, ec] = std::from_chars(b, t.data() + t.size(), v);
  if (ec != std::errc() || p != t.data() + t.size()) {
    fail_line(path_, token_line_, fmt::format("'{}' is not an integer: expected {}",
                                              t.substr(0, 40), what));
  }
  return v;
}

void Tokens::skip_line() {
  while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
}

bool Tokens::more_on_line() {
  while (pos_ < text_.size() && text_[pos_] != '\n' &&
         std::isspace(static_cast<unsigned char>(text_[pos_]))) {
    ++pos_;
  }
  return pos_ < text_.size() && text_[pos_] != '\n' && !(hash_ && text_[pos_] == '#');
}

void Tokens::skip() {
  while (pos_ < text_.size()) {
    const char c = text_[pos_];
    if (c == '\n') {
      ++line_;
      ++pos_;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++pos_;
    } else if (hash_ && c == '#') {
      while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    } else {
      break;
    }
  }
}

}  // namespace rigid::mesh::detail
