// SPDX-License-Identifier: MIT
#include "world/islands.h"

#include <algorithm>

namespace supermodal
{
namespace
{

constexpr uint32_t k_unset = UINT32_MAX;

} // namespace

void IslandBuilder::clear()
{
    for (uint32_t n : m_touched) {
        m_parent[n] = k_unset;
        m_label[n] = k_unset;
    }
    m_touched.clear();
    m_ends.clear();
    m_start.clear();
    m_rows.clear();
}

void IslandBuilder::touch(uint32_t n)
{
    if (n >= m_parent.size()) {
        m_parent.resize(static_cast<size_t>(n) + 1, k_unset);
        m_label.resize(static_cast<size_t>(n) + 1, k_unset);
    }
    if (m_parent[n] == k_unset) {
        m_parent[n] = n;
        m_touched.push_back(n);
    }
}

// Path halving: every node on the way points to its grandparent, which flattens the tree as it walks.
uint32_t IslandBuilder::find(uint32_t n)
{
    while (m_parent[n] != n) {
        m_parent[n] = m_parent[m_parent[n]];
        n = m_parent[n];
    }
    return n;
}

uint32_t IslandBuilder::root(uint32_t n)
{
    return n < m_parent.size() && m_parent[n] != k_unset ? find(n) : n;
}

void IslandBuilder::add_row(uint32_t a, uint32_t b)
{
    m_ends.emplace_back(a, b);
    if (a != k_no_node)
        touch(a);
    if (b != k_no_node)
        touch(b);
    if (a == k_no_node || b == k_no_node)
        return;
    // Which root wins does not matter: only the partition is used, and it is unique.
    const uint32_t ra = find(a), rb = find(b);
    if (ra != rb)
        m_parent[std::max(ra, rb)] = std::min(ra, rb);
}

void IslandBuilder::build()
{
    // Islands are numbered as their first row comes, so they are ordered by first row.
    uint32_t count = 0;
    m_row_island.resize(m_ends.size());
    for (size_t r = 0; r < m_ends.size(); ++r) {
        const auto [a, b] = m_ends[r];
        const uint32_t node = a != k_no_node ? a : b;
        if (node == k_no_node) {
            m_row_island[r] = count++;
            continue;
        }
        uint32_t& label = m_label[find(node)];
        if (label == k_unset)
            label = count++;
        m_row_island[r] = label;
    }
    // Counting sort by island; rows are visited in order, so each island's rows stay ascending.
    m_start.assign(static_cast<size_t>(count) + 1, 0);
    for (uint32_t island : m_row_island)
        ++m_start[island + 1];
    for (size_t i = 0; i < count; ++i)
        m_start[i + 1] += m_start[i];
    m_fill.assign(m_start.begin(), m_start.end() - 1);
    m_rows.resize(m_ends.size());
    for (size_t r = 0; r < m_ends.size(); ++r)
        m_rows[m_fill[m_row_island[r]]++] = static_cast<uint32_t>(r);
}

std::pair<size_t, size_t> IslandBuilder::islands_of_part(size_t part, size_t parts) const
{
    const size_t rows = m_rows.size();
    auto first_at = [&](size_t row) {
        return static_cast<size_t>(std::lower_bound(m_start.begin(), m_start.end() - 1, row) -
                                   m_start.begin());
    };
    if (m_start.empty())
        return {0, 0};
    return {first_at(rows * part / parts), first_at(rows * (part + 1) / parts)};
}

} // namespace supermodal
