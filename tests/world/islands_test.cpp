// Tests for engine/src/world/islands.h: rows linked through shared nodes form one island, ends that
// join nothing (k_no_node) split chains, islands come in first-row order with ascending rows, the
// builder is reusable, and the row-balanced split of islands into parts covers each island once.
#include "world/islands.h"

#include <gtest/gtest.h>
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
