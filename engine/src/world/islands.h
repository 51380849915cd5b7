// SPDX-License-Identifier: MIT
// Islands: the groups of rows (constraint rows; contact rows can join the same builder) linked through
// bodies whose velocity or modes the rows change. Found by union-find over the bodies' node indices
// (entity indices), with path compression. Rows of different islands write no common state, so each
// island can be solved on its own thread, its rows in their global order, and the result is bit for
// bit the serial one. An end that a row's impulse does not change (the world, a static or kinematic
// body) joins nothing: it carries no velocity change from one row to the next, so two chains hanging
// from the same static body stay two islands.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace supermodal
{

/// A row end that joins no island (the world, a static or kinematic body).
inline constexpr uint32_t k_no_node = UINT32_MAX;

/// Reusable island scratch: its buffers are kept between uses, so a warm builder allocates nothing.
/// Use: clear(), add_row() per row in row order, build(), then read the islands.
class IslandBuilder
{
  public:
    /// Forgets the previous rows; the cost is that of the nodes they touched, not of the node range.
    void clear();
    /// Appends the next row (numbered in call order from 0) linking nodes a and b; either may be
    /// k_no_node. A row whose ends are both k_no_node is an island of its own.
    void add_row(uint32_t a, uint32_t b);
    /// Groups the rows: each island's rows ascending, islands ordered by their first row.
    void build();

    [[nodiscard]] size_t row_count() const { return m_ends.size(); }
    [[nodiscard]] size_t island_count() const { return m_start.empty() ? 0 : m_start.size() - 1; }
    /// Rows of island i, ascending.
    [[nodiscard]] std::span<const uint32_t> island(size_t i) const
    {
        return {m_rows.data() + m_start[i], m_start[i + 1] - m_start[i]};
    }
    /// Islands [first, last) for part `part` of `parts` when the islands are split by row count: island
    /// i goes to the part whose share of the rows [p·n/P, (p+1)·n/P) holds its first grouped row.
    [[nodiscard]] std::pair<size_t, size_t> islands_of_part(size_t part, size_t parts) const;
    /// Representative node of n's island after build() (n itself when no row touched it): nodes with
    /// the same representative are in the same island (for grouping bodies, e.g. to sleep them).
    [[nodiscard]] uint32_t root(uint32_t n);

  private:
    void touch(uint32_t n);
    uint32_t find(uint32_t n);

    std::vector<uint32_t> m_parent;  ///< Per node: union-find parent, or unset when untouched.
    std::vector<uint32_t> m_label;   ///< Per node: island of a root during build(), or unset.
    std::vector<uint32_t> m_touched; ///< Nodes whose m_parent / m_label are set (to reset them).
    std::vector<std::pair<uint32_t, uint32_t>> m_ends; ///< Per row: its two nodes.
    std::vector<uint32_t> m_row_island;                ///< Per row: its island.
    std::vector<uint32_t> m_start;                     ///< Per island + 1: offset into m_rows.
    std::vector<uint32_t> m_fill;                      ///< Per island: next free slot (build only).
    std::vector<uint32_t> m_rows;                      ///< Row indices grouped by island.
};

} // namespace supermodal
