// SPDX-License-Identifier: MIT
#include "world/islands.h"

#include <algorithm>
#include <array>
#include <cmath>

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

void IslandSlabs::collect_nodes(std::span<const uint32_t> rows, const IslandBuilder& islands)
{
    m_nodes.clear();
    auto add = [&](uint32_t n) {
        if (n == k_no_node)
            return;
        if (n >= m_seen.size())
            m_seen.resize(static_cast<size_t>(n) + 1, 0);
        if (m_seen[n] == 0) {
            m_seen[n] = 1;
            m_nodes.push_back(n);
        }
    };
    for (uint32_t r : rows) {
        const auto [a, b] = islands.ends(r);
        add(a);
        add(b);
    }
    for (uint32_t n : m_nodes)
        m_seen[n] = 0;
    for (Trial& t : m_trials)
        if (t.slab.size() < m_seen.size())
            t.slab.resize(m_seen.size(), k_unset);
}

namespace
{

// A coordinate to sort by: a body whose state went non-finite (it is frozen later in the stage) sorts
// as if at 0 rather than breaking the order.
double sort_coordinate(const Vec3& p, int axis)
{
    const double x = axis == 0 ? p.x : axis == 1 ? p.y : p.z;
    return std::isfinite(x) ? x : 0.0;
}

// How far the points spread along each axis [m].
template <class Keys> std::array<double, 3> extents(const Keys& keys)
{
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (const auto& k : keys)
        for (int a = 0; a < 3; ++a) {
            const double x = sort_coordinate(k.position, a);
            lo[a] = std::min(lo[a], x);
            hi[a] = std::max(hi[a], x);
        }
    return {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
}

} // namespace

uint32_t IslandSlabs::group_of(uint32_t slab_a, uint32_t slab_b, size_t slabs)
{
    const auto k = static_cast<uint32_t>(slabs);
    const uint32_t lo = std::min(slab_a, slab_b), hi = std::max(slab_a, slab_b);
    if (lo == hi)
        return lo;
    if (hi != lo + 1)
        return 2 * k - 1;
    // Seams after even slabs first, then after odd ones.
    return lo % 2 == 0 ? k + lo / 2 : k + k / 2 + lo / 2;
}

void IslandSlabs::assign_slabs(int axis, size_t slabs, Trial& out) const
{
    auto before = [axis](const Key& x, const Key& y) {
        const double cx = sort_coordinate(x.position, axis), cy = sort_coordinate(y.position, axis);
        return cx < cy || (cx == cy && x.node < y.node);
    };
    // Slab s holds the ranks [ceil(s·n/K), ceil((s+1)·n/K)) of the order above: each boundary found by
    // selection in what is left, not a whole sort (the order is total, so the slabs are the same).
    std::vector<Key>& keys = out.keys;
    keys.assign(m_keys.begin(), m_keys.end());
    const size_t n = keys.size();
    size_t begin = 0;
    for (size_t slab = 0; slab < slabs; ++slab) {
        const size_t end = ((slab + 1) * n + slabs - 1) / slabs;
        if (end < n)
            std::nth_element(keys.begin() + static_cast<std::ptrdiff_t>(begin),
                             keys.begin() + static_cast<std::ptrdiff_t>(end), keys.end(), before);
        for (size_t i = begin; i < end; ++i)
            out.slab[keys[i].node] = static_cast<uint32_t>(slab);
        begin = end;
    }
}

uint32_t IslandSlabs::row_group(uint32_t row, const IslandBuilder& islands, size_t slabs,
                                const std::vector<uint32_t>& slab)
{
    const auto [a, b] = islands.ends(row);
    if (a == k_no_node && b == k_no_node)
        return static_cast<uint32_t>(2 * slabs - 1);
    const uint32_t sa = a != k_no_node ? slab[a] : slab[b];
    const uint32_t sb = b != k_no_node ? slab[b] : sa;
    return group_of(sa, sb, slabs);
}

// The slabs run along the axis, of those at least half as long as the longest, whose groups break the
// rows' own order least: a group walks its rows in that order, which is their order in memory, and
// short runs with gaps between them cost the hardware's prefetching (measured on a 4000-body pile: the
// passes 20% slower than unsplit across the grid the bodies were created along, 9% along it). Each
// axis is tried on its own thread; ties go to the first axis.
int IslandSlabs::choose_axis(std::span<const uint32_t> rows, const IslandBuilder& islands, size_t slabs,
                             const Parallel& par)
{
    const std::array<double, 3> extent = extents(m_keys);
    const double longest = std::max({extent[0], extent[1], extent[2]});
    std::array<int, 3> axes{};
    size_t count = 0;
    for (int axis = 0; axis < 3; ++axis)
        if (extent[axis] >= 0.5 * longest)
            axes[count++] = axis;
    if (count == 0) // no finite extent: any axis splits as well
        axes[count++] = 0;
    par.for_parts(count, 1, [&](size_t, size_t begin, size_t end) {
        for (size_t k = begin; k < end; ++k) {
            Trial& t = m_trials[static_cast<size_t>(axes[k])];
            assign_slabs(axes[k], slabs, t);
            t.group.resize(rows.size());
            t.breaks = 0;
            for (size_t i = 0; i < rows.size(); ++i) {
                t.group[i] = row_group(rows[i], islands, slabs, t.slab);
                t.breaks += i > 0 && t.group[i] != t.group[i - 1] ? 1 : 0;
            }
        }
    });
    int best = axes[0];
    for (size_t k = 1; k < count; ++k)
        if (m_trials[static_cast<size_t>(axes[k])].breaks < m_trials[static_cast<size_t>(best)].breaks)
            best = axes[k];
    return best;
}

void IslandSlabs::split(std::span<const uint32_t> rows, const IslandBuilder& islands, size_t slabs,
                        const Parallel& par)
{
    // The chosen axis's trial already holds each row's group.
    const std::vector<uint32_t>& row_groups =
        m_trials[static_cast<size_t>(choose_axis(rows, islands, slabs, par))].group;
    const size_t groups = 2 * slabs;
    m_phase[0] = 0;
    m_phase[1] = slabs;
    m_phase[2] = slabs + slabs / 2;
    m_phase[3] = groups - 1;
    m_phase[4] = groups;
    m_start.assign(groups + 1, 0);
    for (uint32_t g : row_groups)
        ++m_start[g + 1];
    for (size_t g = 0; g < groups; ++g)
        m_start[g + 1] += m_start[g];
    m_fill.assign(m_start.begin(), m_start.end() - 1);
    m_rows.resize(rows.size());
    for (size_t i = 0; i < rows.size(); ++i)
        m_rows[m_fill[row_groups[i]]++] = rows[i];
}

} // namespace supermodal
