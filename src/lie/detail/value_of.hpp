#pragma once

#include <type_traits>

namespace rigid::detail {

/// The double value of a scalar: itself for double, the value part of an AutoDiffXd.
/// Used for branch decisions and messages, which must not depend on derivatives.
template <typename Scalar>
double value_of(const Scalar& s) {
  if constexpr (std::is_same_v<Scalar, double>) {
    return s;
  } else {
    return s.value();
  }
}

}  // namespace rigid::detail
