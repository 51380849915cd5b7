// SPDX-License-Identifier: MIT
// Islands: the groups of rows (constraint rows; contact rows can join the same builder) linked through
// bodies whose velocity or modes the rows change. Found by union-find over the bodies' node indices
// (entity indices), with path compression. Rows of different islands write no common state, so each
// island can be solved on its own thread, its rows in their global order, and the result is bit for
// bit the serial one. An end that a row's impulse does not change (the world, a static or kinematic
// body) joins nothing: it carries no velocity change from one row to the next, so two chains hanging
// from the same static body stay two islands.
#pragma once

#include "core/parallel.h"
#include "supermodal/math.h"

#include <array>
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
    /// The two nodes row r links (as added).
    [[nodiscard]] std::pair<uint32_t, uint32_t> ends(size_t r) const { return m_ends[r]; }
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

/// One large island's rows in groups that threads can solve side by side (a domain split). The island's
/// bodies, sorted along one axis (of those at least half the island's longest extent, the one whose
/// slabs keep the rows' memory order in the longest runs), fill `slabs` slabs of equal count. A row whose
/// bodies are in one slab belongs to that slab; a row across two neighbouring slabs to their seam; any
/// other row (a body reaching past a whole slab) to one last group. Phases, in solving order: the slabs,
/// the seams after even slabs, the seams after odd slabs, the last group. No two groups of a phase share
/// a body, so a phase's groups may run on any threads in any order with the bits of one thread; each
/// group keeps its rows in their global order. The split depends only on the rows and the positions.
class IslandSlabs
{
  public:
    static constexpr size_t k_phases = 4;

    /// Splits `rows` (one island's, ascending, their ends read from `islands`) into `slabs` slabs;
    /// position(node) is the node's position [m], world.
    /// The candidate axes are tried on the threads of `par` (the same split on any).
    template <class Position>
    void build(std::span<const uint32_t> rows, const IslandBuilder& islands, size_t slabs,
               Position&& position, const Parallel& par = Parallel{})
    {
        collect_nodes(rows, islands);
        m_keys.clear();
        for (uint32_t n : m_nodes)
            m_keys.push_back({position(n), n});
        split(rows, islands, slabs, par);
    }

    /// Groups [first, last) of phase p.
    [[nodiscard]] std::pair<size_t, size_t> phase(size_t p) const { return {m_phase[p], m_phase[p + 1]}; }
    /// Rows of group g, ascending.
    [[nodiscard]] std::span<const uint32_t> group(size_t g) const
    {
        return {m_rows.data() + m_start[g], m_start[g + 1] - m_start[g]};
    }

  private:
    struct Key {
        Vec3 position;
        uint32_t node;
    };
    /// The slabs along one axis.
    struct Trial {
        std::vector<Key> keys;       ///< m_keys, partly ordered along the axis.
        std::vector<uint32_t> slab;  ///< Per node index (of the island's nodes): its slab.
        std::vector<uint32_t> group; ///< Per row of the island: its group.
        size_t breaks = 0;           ///< Where the rows' group changes from one row to the next [-].
    };
    void collect_nodes(std::span<const uint32_t> rows, const IslandBuilder& islands);
    void split(std::span<const uint32_t> rows, const IslandBuilder& islands, size_t slabs,
               const Parallel& par);
    int choose_axis(std::span<const uint32_t> rows, const IslandBuilder& islands, size_t slabs,
                    const Parallel& par);
    void assign_slabs(int axis, size_t slabs, Trial& out) const;
    [[nodiscard]] static uint32_t row_group(uint32_t row, const IslandBuilder& islands, size_t slabs,
                                            const std::vector<uint32_t>& slab);
    [[nodiscard]] static uint32_t group_of(uint32_t slab_a, uint32_t slab_b, size_t slabs);

    std::vector<uint32_t> m_nodes;  ///< The island's nodes, as their rows first name them.
    std::vector<Key> m_keys;        ///< Per node of m_nodes: its position.
    std::vector<uint8_t> m_seen;    ///< Per node index: whether m_nodes has it (collect_nodes).
    std::array<Trial, 3> m_trials;  ///< Per axis.
    std::vector<uint32_t> m_start;  ///< Per group + 1: offset into m_rows.
    std::vector<uint32_t> m_fill;   ///< Per group: next free slot (split only).
    std::vector<uint32_t> m_rows;   ///< Rows grouped.
    size_t m_phase[k_phases + 1]{}; ///< Per phase + 1: first group.
};

} // namespace supermodal
