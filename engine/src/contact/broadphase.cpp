// SPDX-License-Identifier: MIT
#include "contact/broadphase.h"

#include "contact/radix_sort.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace supermodal
{

namespace
{

// A box wider than this many cells on an axis (or unbounded, as a plane's, or non-finite) is tested
// against every other box instead of being binned: at most (4 + 1)³ cells per binned box.
constexpr double k_big_cells = 4.0;
// Cell size over the median box extent: a typical box covers one or two cells per axis.
constexpr double k_cell_per_extent = 2.0;
// Cell coordinates are clamped to ±2^20 and packed 21 bits per axis into one key. Clamping keeps the
// test exact (it is monotone, so overlapping boxes still share a cell); far-out boxes only crowd
// the boundary cells.
constexpr int64_t k_coord_limit = (int64_t{1} << 20) - 1;
// Fewest boxes (or cell entries) worth a thread part: a box's cells and tests are a few dozen
// nanoseconds, and waking a worker costs microseconds.
constexpr size_t k_min_boxes_per_part = 256;

int64_t cell_coord(double x, double inv_cell)
{
    const double c = std::floor(x * inv_cell);
    return static_cast<int64_t>(
        std::clamp(c, -static_cast<double>(k_coord_limit), static_cast<double>(k_coord_limit)));
}

uint64_t cell_key(int64_t ix, int64_t iy, int64_t iz)
{
    constexpr int64_t off = k_coord_limit + 1;
    return (static_cast<uint64_t>(ix + off) << 42) | (static_cast<uint64_t>(iy + off) << 21) |
           static_cast<uint64_t>(iz + off);
}

double max_extent(const Aabb& b)
{
    return std::max({b.max.x - b.min.x, b.max.y - b.min.y, b.max.z - b.min.z});
}

// Whether a pair of these two can matter: one is an awake dynamic body, or one sleeps and the other is
// a moving kinematic body that may wake it (static and kinematic bodies never pair with each other).
bool may_pair(const BroadphaseProxy& p, const BroadphaseProxy& q)
{
    const bool p_awake = !p.is_static && !p.asleep, q_awake = !q.is_static && !q.asleep;
    return p_awake || q_awake || (p.asleep && q.moving) || (q.asleep && p.moving);
}

void add_pair(const BroadphaseProxy& p, const BroadphaseProxy& q, std::vector<BodyPair>& out)
{
    if (!may_pair(p, q) || !overlaps(p.box, q.box))
        return;
    out.push_back(p.entity.index < q.entity.index ? BodyPair{p.entity, q.entity}
                                                  : BodyPair{q.entity, p.entity});
}

// Uniform grid cell size [m]: twice the median finite box extent (nth_element on values: the same
// result for any input order); 1 when no box has a positive finite extent.
double grid_cell(std::span<const BroadphaseProxy> proxies, std::vector<double>& extents)
{
    extents.clear();
    for (const BroadphaseProxy& p : proxies) {
        const double e = max_extent(p.box);
        if (std::isfinite(e))
            extents.push_back(e);
    }
    double cell = 1.0;
    if (!extents.empty()) {
        auto mid = extents.begin() + static_cast<std::ptrdiff_t>(extents.size() / 2);
        std::nth_element(extents.begin(), mid, extents.end());
        if (*mid > 0.0)
            cell = k_cell_per_extent * *mid;
    }
    return cell;
}

// A key's three cell coordinates, offset as packed (each below 2^21).
BroadphaseScratch::Cell unpack(uint64_t key)
{
    constexpr uint64_t mask = (uint64_t{1} << 21) - 1;
    return {static_cast<uint32_t>(key >> 42), static_cast<uint32_t>((key >> 21) & mask),
            static_cast<uint32_t>(key & mask)};
}

// Box i's entries, one per cell it covers, and the cell of its lower corner; false if it is too big to
// bin.
bool bin_box(const Aabb& b, uint32_t i, double inv_cell, double big_extent,
             std::vector<BroadphaseScratch::Entry>& out, BroadphaseScratch::Cell& out_low)
{
    if (!(max_extent(b) <= big_extent) || !is_finite(b.min) || !is_finite(b.max))
        return false;
    const int64_t x0 = cell_coord(b.min.x, inv_cell), x1 = cell_coord(b.max.x, inv_cell);
    const int64_t y0 = cell_coord(b.min.y, inv_cell), y1 = cell_coord(b.max.y, inv_cell);
    const int64_t z0 = cell_coord(b.min.z, inv_cell), z1 = cell_coord(b.max.z, inv_cell);
    out_low = unpack(cell_key(x0, y0, z0));
    for (int64_t x = x0; x <= x1; ++x)
        for (int64_t y = y0; y <= y1; ++y)
            for (int64_t z = z0; z <= z1; ++z)
                out.push_back({cell_key(x, y, z), i});
    return true;
}

// The lists parts[0, count), each sorted by key(item), merged into `out` (`other` is scratch): stable,
// so of items with equal keys the earlier part's come first.
template <class T, class Key>
void merge_parts(std::vector<PartList<T>>& parts, size_t count, std::vector<T>& out, std::vector<T>& other,
                 Key key)
{
    auto less = [key](const T& x, const T& y) { return key(x) < key(y); };
    out.swap(parts[0]); // the first part is where the merge starts: the buffers trade places
    for (size_t p = 1; p < count; ++p) {
        other.resize(out.size() + parts[p].size());
        std::merge(out.begin(), out.end(), parts[p].begin(), parts[p].end(), other.begin(), less);
        out.swap(other);
    }
}

// The sort keys, as lambdas: a function passed by reference is called, not inlined, per item and pass
// (measured 30% slower broadphase).
constexpr auto entry_key = [](const BroadphaseScratch::Entry& e) { return e.key; };
constexpr auto pair_key = [](const BodyPair& p) { return p.key(); };

// One entry per (box, cell it covers), sorted by cell then proxy; boxes too big to bin go to `big`
// (ascending). The boxes split into ranges over the threads, each range's entries sorted there; the
// ranges merged in order.
void bin_boxes(std::span<const BroadphaseProxy> proxies, double cell, const Parallel& par,
               BroadphaseScratch& io)
{
    const double inv_cell = 1.0 / cell;
    const double big_extent = k_big_cells * cell;
    const size_t parts = par.part_count(proxies.size(), k_min_boxes_per_part);
    io.part_entries.resize(std::max(io.part_entries.size(), parts));
    io.part_other_entries.resize(std::max(io.part_other_entries.size(), parts));
    io.part_big.resize(std::max(io.part_big.size(), parts));
    io.low_cells.resize(proxies.size());
    par.for_parts(proxies.size(), k_min_boxes_per_part, [&](size_t part, size_t begin, size_t end) {
        std::vector<BroadphaseScratch::Entry>& entries = io.part_entries[part];
        entries.clear();
        io.part_big[part].clear();
        for (size_t i = begin; i < end; ++i)
            if (!bin_box(proxies[i].box, static_cast<uint32_t>(i), inv_cell, big_extent, entries,
                         io.low_cells[i]))
                io.part_big[part].push_back(static_cast<uint32_t>(i));
        // By cell, then box: entries are made box by box, so their boxes already ascend and one stable
        // pass by cell sorts by both.
        radix_sort(entries, io.part_other_entries[part], entry_key);
    });
    merge_parts(io.part_entries, parts, io.entries, io.sorted_entries, entry_key);
    io.big.clear();
    for (size_t p = 0; p < parts; ++p)
        io.big.insert(io.big.end(), io.part_big[p].begin(), io.part_big[p].end());
}

// The pairs of one cell's entries; a pair sharing several cells is reported only in the cell holding
// the corner max(min_p, min_q) of the boxes' overlap, which both boxes cover when they overlap. That
// cell is the larger of the two lower corners' cells on each axis (cell_coord never decreases), so it
// is found from the cells bin_box noted, with no rounding: the cheapest test, so it goes first.
void pairs_in_cell(std::span<const BroadphaseProxy> proxies, std::span<const BroadphaseScratch::Cell> low,
                   std::span<const BroadphaseScratch::Entry> cell, std::vector<BodyPair>& out_pairs)
{
    const BroadphaseScratch::Cell here = unpack(cell[0].key);
    for (size_t i = 0; i < cell.size(); ++i) {
        const BroadphaseScratch::Cell& li = low[cell[i].proxy];
        const BroadphaseProxy& p = proxies[cell[i].proxy];
        for (size_t j = i + 1; j < cell.size(); ++j) {
            const BroadphaseScratch::Cell& lj = low[cell[j].proxy];
            if (std::max(li.x, lj.x) != here.x || std::max(li.y, lj.y) != here.y ||
                std::max(li.z, lj.z) != here.z)
                continue;
            add_pair(p, proxies[cell[j].proxy], out_pairs);
        }
    }
}

// The first entry of the cell holding entry i, or of the next cell: where a thread's range starts.
size_t cell_start(std::span<const BroadphaseScratch::Entry> entries, size_t i)
{
    while (i > 0 && i < entries.size() && entries[i].key == entries[i - 1].key)
        ++i;
    return i;
}

// Pairs within the cells of entries [begin, end) (whole cells: a range starting inside a cell starts at
// the next one, and ending inside one runs to its end).
void pairs_in_range(std::span<const BroadphaseProxy> proxies, std::span<const BroadphaseScratch::Cell> low,
                    std::span<const BroadphaseScratch::Entry> entries, size_t begin, size_t end,
                    std::vector<BodyPair>& out_pairs)
{
    for (size_t first = cell_start(entries, begin), stop = cell_start(entries, end); first < stop;) {
        size_t last = first + 1;
        while (last < entries.size() && entries[last].key == entries[first].key)
            ++last;
        pairs_in_cell(proxies, low, entries.subspan(first, last - first), out_pairs);
        first = last;
    }
}

// Big boxes (planes, huge static bodies) against the boxes [begin, end), each pair once.
void pairs_of_big(std::span<const BroadphaseProxy> proxies, std::span<const uint32_t> big, size_t begin,
                  size_t end, std::vector<BodyPair>& out_pairs)
{
    for (size_t bi = 0; bi < big.size(); ++bi) {
        const BroadphaseProxy& p = proxies[big[bi]];
        for (size_t j = begin; j < end; ++j) {
            const bool other_big = std::binary_search(big.begin(), big.end(), static_cast<uint32_t>(j));
            if (j == big[bi] || (other_big && j < big[bi]))
                continue;
            add_pair(p, proxies[j], out_pairs);
        }
    }
}

// The pairs of the cells and of the big boxes, each thread part's sorted there, then merged: sorted by
// key, each once.
void find_pairs(std::span<const BroadphaseProxy> proxies, const Parallel& par, BroadphaseScratch& io,
                std::vector<BodyPair>& out_pairs)
{
    const std::span<const BroadphaseScratch::Entry> entries = io.entries;
    // Each part takes the same share of the cells and of the boxes the big ones are tested against: its
    // range of `work` scaled onto each (consecutive parts' ranges meet, so every cell and box is once
    // in one part); the ranges even out the parts' measured times.
    const size_t work = entries.size() + proxies.size();
    const size_t parts = par.part_count(work, k_min_boxes_per_part);
    io.part_pairs.resize(std::max(io.part_pairs.size(), parts));
    io.part_other_pairs.resize(std::max(io.part_other_pairs.size(), parts));
    auto scaled = [work](size_t at, size_t n) { return at * n / work; };
    par.for_parts(work, k_min_boxes_per_part, io.pairs_balance, [&](size_t part, size_t begin, size_t end) {
        std::vector<BodyPair>& pairs = io.part_pairs[part];
        pairs.clear();
        pairs_in_range(proxies, io.low_cells, entries, scaled(begin, entries.size()),
                       scaled(end, entries.size()), pairs);
        if (!io.big.empty())
            pairs_of_big(proxies, io.big, scaled(begin, proxies.size()), scaled(end, proxies.size()), pairs);
        radix_sort(pairs, io.part_other_pairs[part], pair_key);
    });
    merge_parts(io.part_pairs, parts, out_pairs, io.sorted_pairs, pair_key);
}

} // namespace

void find_overlapping_pairs(std::span<const BroadphaseProxy> proxies, BroadphaseScratch& io_scratch,
                            std::vector<BodyPair>& out_pairs, const Parallel& par)
{
    out_pairs.clear();
    if (proxies.size() < 2)
        return;
    const double cell = grid_cell(proxies, io_scratch.extents);
    bin_boxes(proxies, cell, par, io_scratch);
    find_pairs(proxies, par, io_scratch, out_pairs);
}

} // namespace supermodal
