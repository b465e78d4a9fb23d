#pragma once
// What the mesh readers share (private to the mesh module): opening a file only when it is a
// regular file within the size limit, errors with the file's line or byte, whitespace
// separated tokens with their line numbers.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace rigid::mesh::detail {

[[noreturn]] void fail_line(const std::string& path, int line, const std::string& msg);
[[noreturn]] void fail_byte(const std::string& path, std::uint64_t byte, const std::string& msg);
[[noreturn]] void fail_file(const std::string& path, const std::string& msg);

/// The size in bytes of the mesh file at `path`, after refusing what cannot be one: a missing
/// file, a directory, anything that is not a regular file (a device such as /dev/zero, a
/// FIFO, a socket: they are never opened), an empty file and a file larger than
/// kMaxMeshFileBytes.
[[nodiscard]] std::uint64_t mesh_file_size(const std::string& path);

/// The whole file (mesh_file_size's checks first).
[[nodiscard]] std::string slurp(const std::string& path);

/// Whitespace-separated tokens with their line numbers; '#' comments optional.
class Tokens {
 public:
  Tokens(const std::string& path, const std::string& text, std::size_t pos, int line,
         bool hash_comments)
      : path_(path), text_(text), pos_(pos), line_(line), hash_(hash_comments) {}

  /// The next token, or nothing at the end of the text.
  std::optional<std::string_view> next();
  /// The next token; at the end of the text, an error naming `what` was expected.
  std::string_view expect(const char* what);
  /// The next token as a double (C locale; a leading '+' allowed). "nan", "inf" and values
  /// beyond the double range are refused with the line unless `finite` is false.
  double number(const char* what, bool finite = true);
  /// The next token as an integer.
  long long integer(const char* what);
  /// Skips the rest of the current line (trailing per-vertex colours, normals, ...).
  void skip_line();
  /// True when the current line has another token (comments and the end of line excluded).
  [[nodiscard]] bool more_on_line();

  [[nodiscard]] int line() const { return token_line_; }
  [[nodiscard]] int current_line() const { return line_; }
  [[nodiscard]] std::size_t pos() const { return pos_; }

 private:
  void skip();

  const std::string& path_;
  const std::string& text_;
  std::size_t pos_;
  int line_;
  int token_line_ = 0;
  bool hash_;
};

/// Parses a whole token as a double (C locale, leading '+' allowed); nothing if it is not one.
[[nodiscard]] std::optional<double> parse_double(std::string_view token);

}  // namespace rigid::mesh::detail
