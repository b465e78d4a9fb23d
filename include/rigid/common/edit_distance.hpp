#pragma once

#include <cstddef>
#include <string_view>

namespace rigid {

/// Optimal-string-alignment distance: Levenshtein plus the transposition of two neighbouring
/// characters as one edit ("t_ned" is one slip away from "t_end"). What did_you_mean ranks by;
/// for lists of several close names (rigid plot's unknown column).
[[nodiscard]] std::size_t edit_distance(std::string_view a, std::string_view b);

}  // namespace rigid
