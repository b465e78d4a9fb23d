#pragma once

#include <optional>
#include <vector>
#include <string>
#include <string_view>

namespace rigid {

/// The closest of `candidates` to `word` by optimal-string-alignment distance (Levenshtein
/// plus the transposition of two neighbouring characters as one edit), if close enough to be
/// a plausible typo: distance ≤ max(1, |word|/3). Ties go to the earlier candidate.
[[nodiscard]] std::optional<std::string> did_you_mean(std::string_view word,
                                                      const std::vector<std::string>& candidates);

/// "; did you mean 'x'?" when did_you_mean finds a candidate, else "" (for messages).
[[nodiscard]] std::string did_you_mean_hint(std::string_view word,
                                            const std::vector<std::string>& candidates);

}  // namespace rigid
