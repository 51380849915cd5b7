// Tests for engine/src/contact/radix_sort.h: the same order as a stable comparison sort, for keys that
// vary in every byte, in a few bytes only, or not at all, with ties kept in their input order.
#include "contact/radix_sort.h"

#include <algorithm>
#include <gtest/gtest.h>
#include <random>
#include <vector>

namespace sm = supermodal;

namespace
{

struct Item {
    uint64_t key;
    uint32_t order; // input position, to check stability
};

void expect_like_stable_sort(std::vector<Item> items)
{
    for (uint32_t i = 0; i < items.size(); ++i)
        items[i].order = i;
    std::vector<Item> expected = items, scratch;
    std::stable_sort(expected.begin(), expected.end(),
                     [](const Item& l, const Item& r) { return l.key < r.key; });
    sm::radix_sort(items, scratch, [](const Item& t) { return t.key; });
    ASSERT_EQ(items.size(), expected.size());
    for (size_t i = 0; i < items.size(); ++i) {
        EXPECT_EQ(items[i].key, expected[i].key) << i;
        EXPECT_EQ(items[i].order, expected[i].order) << i;
    }
}

} // namespace

TEST(RadixSort, OrdersLikeAStableSort)
{
    std::mt19937_64 rng(7);
    std::vector<Item> full(5000), sparse(5000), ties(5000);
    for (Item& t : full)
        t.key = rng();
    // Pair keys as the broadphase makes them (index << 32 | index), and packed cells: few bytes vary.
    for (Item& t : sparse)
        t.key = ((rng() % 3000) << 32) | (rng() % 3000) | (uint64_t{1} << 63);
    for (Item& t : ties)
        t.key = rng() % 7;
    expect_like_stable_sort(full);
    expect_like_stable_sort(sparse);
    expect_like_stable_sort(ties);
    expect_like_stable_sort(std::vector<Item>(100, Item{42, 0})); // one key: no pass at all
    expect_like_stable_sort({});
}

TEST(RadixSort, TwoSortsOrderByBothKeys)
{
    std::mt19937_64 rng(11);
    std::vector<Item> items(3000), scratch;
    for (Item& t : items)
        t = {rng() % 50, static_cast<uint32_t>(rng() % 1000)};
    std::vector<Item> expected = items;
    std::sort(expected.begin(), expected.end(), [](const Item& l, const Item& r) {
        return l.key != r.key ? l.key < r.key : l.order < r.order;
    });
    sm::radix_sort(items, scratch, [](const Item& t) { return uint64_t{t.order}; });
    sm::radix_sort(items, scratch, [](const Item& t) { return t.key; });
    for (size_t i = 0; i < items.size(); ++i) {
        EXPECT_EQ(items[i].key, expected[i].key);
        EXPECT_EQ(items[i].order, expected[i].order);
    }
}
