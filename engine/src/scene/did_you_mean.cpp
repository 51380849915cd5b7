// SPDX-License-Identifier: MIT
#include "scene/did_you_mean.h"

#include <algorithm>
#include <cstdint>

namespace supermodal::scene_io
{
namespace
{

// Words longer than this get no suggestion: the O(n·m) distance would let a hostile file with
// megabyte-long keys cost seconds, and nobody mistypes a 64-character key.
constexpr size_t k_max_suggest_length = 64;
// Absolute edit budget for a typo; "radi" → "radii" is 1, "densty" → "density" is 1.
constexpr size_t k_max_typo_edits = 2;

} // namespace

size_t edit_distance(std::string_view a, std::string_view b)
{
    // Two-row dynamic programme (Wagner–Fischer): row j holds distances from a[0, i) to b[0, j).
    std::vector<size_t> previous(b.size() + 1), current(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j)
        previous[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        current[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t substitution = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
            current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitution});
        }
        std::swap(previous, current);
    }
    return previous[b.size()];
}

std::string_view closest_match(std::string_view word, const std::vector<std::string_view>& candidates)
{
    if (word.empty() || word.size() > k_max_suggest_length)
        return {};
    std::string_view best;
    size_t best_distance = SIZE_MAX;
    for (std::string_view candidate : candidates) {
        if (candidate.size() > k_max_suggest_length)
            continue;
        const size_t d = edit_distance(word, candidate);
        // A distance as long as the shorter word means "replace everything": not a typo ("x" vs "dt").
        const bool small_typo = d <= k_max_typo_edits && d < std::min(word.size(), candidate.size());
        const bool relative_typo = 3 * d <= word.size();
        if (d > 0 && (small_typo || relative_typo) && d < best_distance) {
            best = candidate;
            best_distance = d;
        }
    }
    return best;
}

std::string did_you_mean(std::string_view word, const std::vector<std::string_view>& candidates)
{
    const std::string_view match = closest_match(word, candidates);
    if (match.empty())
        return {};
    return "; did you mean \"" + std::string(match) + "\"?";
}

std::string join_names(const std::vector<std::string_view>& names, size_t max_listed)
{
    std::string out;
    for (size_t i = 0; i < names.size(); ++i) {
        if (i == max_listed) {
            out += ", ...";
            break;
        }
        if (i > 0)
            out += ", ";
        out += names[i];
    }
    return out;
}

} // namespace supermodal::scene_io
