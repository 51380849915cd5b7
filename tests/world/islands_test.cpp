// Tests for engine/src/world/islands.h: rows linked through shared nodes form one island, ends that
// join nothing (k_no_node) split chains, islands come in first-row order with ascending rows, the
// builder is reusable, and the row-balanced split of islands into parts covers each island once; a large
// island's slab split puts every row in one group, and no two groups of a phase share a body.
#include "world/islands.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <set>
#include <vector>

namespace sm = supermodal;
using sm::k_no_node;

namespace
{

std::vector<std::vector<uint32_t>> islands_of(sm::IslandBuilder& b)
{
    b.build();
    std::vector<std::vector<uint32_t>> out;
    for (size_t i = 0; i < b.island_count(); ++i) {
        const auto rows = b.island(i);
        out.emplace_back(rows.begin(), rows.end());
    }
    return out;
}

using Islands = std::vector<std::vector<uint32_t>>;

} // namespace

TEST(Islands, EmptyBuilderHasNoIslands)
{
    sm::IslandBuilder b;
    EXPECT_TRUE(islands_of(b).empty());
    EXPECT_EQ(b.islands_of_part(0, 1), (std::pair<size_t, size_t>{0, 0}));
}

TEST(Islands, ChainIsOneIslandWhateverTheRowOrder)
{
    sm::IslandBuilder b;
    // Links 1-2, 5-3, 2-5, 3-4: one chain 1-2-5-3-4 whose rows only meet through later rows.
    b.add_row(1, 2);
    b.add_row(5, 3);
    b.add_row(2, 5);
    b.add_row(3, 4);
    EXPECT_EQ(islands_of(b), (Islands{{0, 1, 2, 3}}));
    EXPECT_EQ(b.root(1), b.root(4));
}

TEST(Islands, WorldAnchoredChainsSplitAtTheWorld)
{
    sm::IslandBuilder b;
    // Two chains hanging from the world (k_no_node) or the same static body (also k_no_node), their rows
    // interleaved: each chain is its own island.
    b.add_row(k_no_node, 10);
    b.add_row(k_no_node, 20);
    b.add_row(10, 11);
    b.add_row(20, 21);
    b.add_row(11, 12);
    EXPECT_EQ(islands_of(b), (Islands{{0, 2, 4}, {1, 3}}));
    EXPECT_NE(b.root(10), b.root(20));
}

TEST(Islands, RowWithoutDynamicEndIsAnIslandOfItsOwn)
{
    sm::IslandBuilder b;
    b.add_row(k_no_node, k_no_node); // e.g. a kinematic body on a world point
    b.add_row(3, k_no_node);
    b.add_row(k_no_node, k_no_node);
    b.add_row(k_no_node, 3);
    EXPECT_EQ(islands_of(b), (Islands{{0}, {1, 3}, {2}}));
}

TEST(Islands, IslandsAreOrderedByFirstRowAndRowsAscend)
{
    sm::IslandBuilder b;
    // Island {7, 8} starts at row 0, {1, 2} at row 1; a late row merges node 9 into the first.
    b.add_row(8, 7);
    b.add_row(2, 1);
    b.add_row(9, k_no_node);
    b.add_row(1, 2);
    b.add_row(7, 9);
    EXPECT_EQ(islands_of(b), (Islands{{0, 2, 4}, {1, 3}}));
    EXPECT_EQ(b.root(42), 42u); // untouched node: itself
}

TEST(Islands, ReuseForgetsThePreviousRows)
{
    sm::IslandBuilder b;
    b.add_row(0, 1);
    b.add_row(1, 2);
    EXPECT_EQ(islands_of(b), (Islands{{0, 1}}));
    b.clear();
    b.add_row(2, 3);
    b.add_row(0, 1);
    EXPECT_EQ(islands_of(b), (Islands{{0}, {1}}));
    EXPECT_EQ(b.row_count(), 2u);
}

TEST(Islands, PartsCoverEveryIslandOnceBalancedByRows)
{
    sm::IslandBuilder b;
    // Islands of 6, 1, 1, 1, 1 rows (nodes 100.. for the big one).
    for (uint32_t i = 0; i < 6; ++i)
        b.add_row(100 + i, 101 + i);
    for (uint32_t i = 0; i < 4; ++i)
        b.add_row(i, k_no_node);
    b.build();
    ASSERT_EQ(b.island_count(), 5u);
    for (size_t parts : {1, 2, 3, 7}) {
        size_t next = 0;
        for (size_t p = 0; p < parts; ++p) {
            const auto [first, last] = b.islands_of_part(p, parts);
            EXPECT_EQ(first, next);
            next = last;
        }
        EXPECT_EQ(next, b.island_count());
    }
    // Two parts: the 6-row island alone takes rows [0, 5), the other part gets the four small ones.
    EXPECT_EQ(b.islands_of_part(0, 2), (std::pair<size_t, size_t>{0, 1}));
    EXPECT_EQ(b.islands_of_part(1, 2), (std::pair<size_t, size_t>{1, 5}));
}

namespace
{

// Every row of `rows` in exactly one group, each group ascending, no node in two groups of one phase.
void expect_valid_split(const sm::IslandSlabs& split, const sm::IslandBuilder& b,
                        std::span<const uint32_t> rows)
{
    std::vector<uint32_t> seen;
    for (size_t p = 0; p < sm::IslandSlabs::k_phases; ++p) {
        const auto [first, last] = split.phase(p);
        std::set<uint32_t> phase_nodes;
        for (size_t g = first; g < last; ++g) {
            const auto group = split.group(g);
            EXPECT_TRUE(std::is_sorted(group.begin(), group.end()));
            std::set<uint32_t> nodes;
            for (uint32_t r : group) {
                seen.push_back(r);
                const auto [a, c] = b.ends(r);
                for (uint32_t n : {a, c})
                    if (n != k_no_node)
                        nodes.insert(n);
            }
            if (p + 1 == sm::IslandSlabs::k_phases)
                continue; // the last phase is one group
            for (uint32_t n : nodes) {
                EXPECT_TRUE(phase_nodes.insert(n).second) << "node " << n << " in two groups of phase " << p;
            }
        }
    }
    std::sort(seen.begin(), seen.end());
    EXPECT_EQ(seen, std::vector<uint32_t>(rows.begin(), rows.end()));
}

sm::Vec3 on_a_line(uint32_t node)
{
    return {0.1 * node, 0.01 * (node % 3), 0.0};
}

// One island: a chain of rows linking nodes 1-2, 2-3, ..., (n-1)-n.
void add_chain(sm::IslandBuilder& b, uint32_t n)
{
    for (uint32_t i = 1; i < n; ++i)
        b.add_row(i, i + 1);
}

} // namespace

TEST(IslandSlabs, AChainSplitsIntoSlabsSeamsAndNoRest)
{
    // A chain of 4000 links along x, with a floor row (k_no_node) under every tenth body.
    sm::IslandBuilder b;
    for (uint32_t i = 1; i <= 4000; ++i) {
        b.add_row(i, i + 1);
        if (i % 10 == 0)
            b.add_row(k_no_node, i);
    }
    b.build();
    ASSERT_EQ(b.island_count(), 1u);
    const auto rows = b.island(0);
    sm::IslandSlabs split;
    split.build(rows, b, 4, on_a_line);
    expect_valid_split(split, b, rows);
    // Four slabs of about a thousand bodies; three seams of one link each (two after even slabs, one
    // after an odd one); nothing reaches past a slab.
    ASSERT_EQ(split.phase(0), (std::pair<size_t, size_t>{0, 4}));
    for (size_t g = 0; g < 4; ++g)
        EXPECT_NEAR(static_cast<double>(split.group(g).size()), 4400.0 / 4.0, 2.0);
    ASSERT_EQ(split.phase(1), (std::pair<size_t, size_t>{4, 6}));
    ASSERT_EQ(split.phase(2), (std::pair<size_t, size_t>{6, 7}));
    for (size_t g = 4; g < 7; ++g)
        EXPECT_EQ(split.group(g).size(), 1u);
    EXPECT_TRUE(split.group(7).empty());
}

TEST(IslandSlabs, FollowsThePositionsNotTheNodeNumbers)
{
    // The same chain with its bodies placed in reverse: the first slab is now the high node numbers.
    sm::IslandBuilder b;
    add_chain(b, 2000);
    b.build();
    const auto rows = b.island(0);
    sm::IslandSlabs split;
    split.build(rows, b, 2, [](uint32_t n) { return on_a_line(3000 - n); });
    expect_valid_split(split, b, rows);
    const auto first = split.group(0);
    ASSERT_FALSE(first.empty());
    EXPECT_GE(b.ends(first.front()).first, 1000u);
}

TEST(IslandSlabs, ARowPastAWholeSlabGoesLast)
{
    // A chain of 3000 along x and one long row from its first body to its last (a rope, say).
    sm::IslandBuilder b;
    add_chain(b, 3000);
    b.add_row(1, 3000);
    b.build();
    const auto rows = b.island(0);
    sm::IslandSlabs split;
    split.build(rows, b, 3, on_a_line);
    expect_valid_split(split, b, rows);
    const auto [first, last] = split.phase(3);
    ASSERT_EQ(last, first + 1);
    EXPECT_EQ(std::vector<uint32_t>(split.group(first).begin(), split.group(first).end()),
              std::vector<uint32_t>{2999});
}

TEST(IslandSlabs, NonFinitePositionsStillSplitEveryRow)
{
    sm::IslandBuilder b;
    add_chain(b, 1500);
    b.build();
    const auto rows = b.island(0);
    sm::IslandSlabs split;
    split.build(rows, b, 3, [](uint32_t n) {
        return n % 7 == 0 ? sm::Vec3{NAN, INFINITY, -INFINITY} : on_a_line(n);
    });
    expect_valid_split(split, b, rows);
    // Reused with other rows: the old slabs are forgotten.
    split.build(rows.first(200), b, 2, on_a_line);
    expect_valid_split(split, b, rows.first(200));
}
