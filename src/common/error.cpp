#include "rigid/common/error.hpp"

#include "rigid/common/escape.hpp"

namespace rigid {

// The file name escaped (rigid::escaped): a name holding a control character or a byte that
// is not UTF-8 (a file named \xff on a Linux file system) would otherwise reach a terminal, or a
// JSON writer, as the raw bytes.
std::string to_string(const SourceLocation& where) {
  const std::string file = escaped(where.file);
  if (where.line <= 0) return file;
  if (where.column <= 0) return fmt::format("{}:{}", file, where.line);
  return fmt::format("{}:{}:{}", file, where.line, where.column);
}

namespace detail {

void throw_error(std::string_view function, std::string message) {
  throw Error(fmt::format("{}(): {}", function, message));
}

void throw_error_at(const SourceLocation& where, std::string message) {
  throw Error(fmt::format("{}: {}", to_string(where), message));
}

void throw_assertion(const char* condition, const char* file, int line, const char* function) {
  throw Error(fmt::format(
      "internal error in {}() at {}:{}: invariant `{}` does not hold; this is a bug in rigid, "
      "please report it with the input that triggered it",
      function, file, line, condition));
}

}  // namespace detail
}  // namespace rigid
