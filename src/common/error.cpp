#include "rigid/common/error.hpp"

namespace rigid {

std::string to_string(const SourceLocation& where) {
  if (where.line <= 0) return where.file;
  if (where.column <= 0) return fmt::format("{}:{}", where.file, where.line);
  return fmt::format("{}:{}:{}", where.file, where.line, where.column);
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
