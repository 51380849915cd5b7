// SPDX-License-Identifier: MIT
// "Did you mean" suggestions for misspelt keys, enum values and names in scene files.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace supermodal::scene_io
{

/// Levenshtein distance between a and b: the fewest single-byte insertions, deletions and
/// substitutions that turn one into the other [-].
[[nodiscard]] size_t edit_distance(std::string_view a, std::string_view b);

/// The candidate closest to `word` if it is close enough to be a likely typo (distance ≤ 2 and
/// shorter than either word, or ≤ a third of the word's length), else an empty view. Ties go to the
/// earliest candidate, so the answer does not depend on anything but the order given.
[[nodiscard]] std::string_view closest_match(std::string_view word,
                                             const std::vector<std::string_view>& candidates);

/// "; did you mean \"radii\"?" for the closest candidate, or an empty string when none is close.
[[nodiscard]] std::string did_you_mean(std::string_view word,
                                       const std::vector<std::string_view>& candidates);

/// The candidates joined as "a, b, c" (at most `max_listed`, then ", ..."), for "expected one of" lists.
[[nodiscard]] std::string join_names(const std::vector<std::string_view>& names, size_t max_listed = 20);

} // namespace supermodal::scene_io
