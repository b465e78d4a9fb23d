#pragma once

#include <type_traits>

#include <Eigen/Core>
#include <fmt/ostream.h>

/// Lets fmt print any Eigen dense expression through Eigen's operator<<, so that
/// error messages and tests can show vectors and matrices.
template <typename T>
struct fmt::formatter<T, char, std::enable_if_t<std::is_base_of_v<Eigen::DenseBase<T>, T>>>
    : fmt::ostream_formatter {};

namespace rigid {

/// One-line form "[a, b, c]" of a vector or a matrix (rows separated by "; "),
/// with shortest round-trip doubles, for messages.
template <typename Derived>
[[nodiscard]] std::string to_string(const Eigen::DenseBase<Derived>& m) {
  std::string out = "[";
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    for (Eigen::Index j = 0; j < m.cols(); ++j) {
      if (j > 0) out += ", ";
      out += fmt::format("{}", static_cast<double>(m(i, j)));
    }
    if (i + 1 < m.rows()) out += "; ";
  }
  return out + "]";
}

}  // namespace rigid
