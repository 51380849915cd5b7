// Tests for engine/src/world/registry.h.
#include "core/registry.h"

#include <algorithm>
#include <gtest/gtest.h>

namespace sm = supermodal;

namespace
{
struct A {
    int v = 0;
};
struct B {
    double v = 0;
};
using TestRegistry = sm::BasicRegistry<A, B>;
} // namespace

TEST(EntityPool, NullHandleIsNeverValidAndSlotZeroIsNeverHandedOut)
{
    sm::EntityPool pool;
    EXPECT_FALSE(pool.valid(sm::Entity{}));
    for (int i = 0; i < 10; ++i)
        EXPECT_NE(pool.create().index, 0u);
}

TEST(EntityPool, DestroyedHandleIsStaleAndReuseBumpsGeneration)
{
    sm::EntityPool pool;
    const sm::Entity a = pool.create();
    ASSERT_TRUE(pool.destroy(a));
    EXPECT_FALSE(pool.valid(a));
    EXPECT_FALSE(pool.destroy(a)); // double destroy is refused, not corrupting the free list
    const sm::Entity b = pool.create();
    EXPECT_EQ(b.index, a.index);
    EXPECT_NE(b.generation, a.generation);
    EXPECT_TRUE(pool.valid(b));
    EXPECT_FALSE(pool.valid(a));
    EXPECT_EQ(pool.alive_count(), 1u);
}

TEST(EntityPool, SlotAtLastGenerationIsRetiredNotWrapped)
{
    sm::EntityPool pool;
    const sm::Entity a = pool.create();
    pool.debug_set_generation(a.index, sm::EntityPool::k_max_generation - 1);
    const sm::Entity old{a.index, sm::EntityPool::k_max_generation - 1};
    ASSERT_TRUE(pool.destroy(old));
    const sm::Entity fresh = pool.create();
    EXPECT_NE(fresh.index, a.index); // the worn-out slot is never handed out again
    EXPECT_FALSE(pool.valid(old));
    EXPECT_FALSE(pool.valid(sm::Entity{a.index, 1}));
}

TEST(SparseSet, SwapAndPopKeepsOtherEntitiesReachable)
{
    sm::EntityPool pool;
    sm::SparseSet<A> set;
    std::vector<sm::Entity> es;
    for (int i = 0; i < 5; ++i) {
        es.push_back(pool.create());
        set.emplace(es.back(), A{i});
    }
    ASSERT_TRUE(set.remove(es[1]));
    EXPECT_FALSE(set.contains(es[1]));
    EXPECT_EQ(set.size(), 4u);
    for (int i : {0, 2, 3, 4})
        EXPECT_EQ(set.get(es[i]).v, i);
}

TEST(SparseSet, StaleHandleDoesNotSeeTheNewOwnersComponent)
{
    sm::EntityPool pool;
    sm::SparseSet<A> set;
    const sm::Entity a = pool.create();
    set.emplace(a, A{1});
    set.remove(a);
    pool.destroy(a);
    const sm::Entity b = pool.create();
    set.emplace(b, A{2});
    EXPECT_FALSE(set.contains(a));
    EXPECT_EQ(set.find(a), nullptr);
    EXPECT_EQ(set.get(b).v, 2);
}

TEST(Registry, ViewVisitsExactlyTheEntitiesWithAllComponents)
{
    TestRegistry reg;
    std::vector<sm::Entity> both;
    for (int i = 0; i < 20; ++i) {
        const sm::Entity e = reg.create();
        reg.emplace(e, A{i});
        if (i % 3 == 0) {
            reg.emplace(e, B{i * 0.5});
            both.push_back(e);
        }
    }
    std::vector<sm::Entity> seen;
    reg.each<A, B>([&](sm::Entity e, A& a, B& b) {
        EXPECT_DOUBLE_EQ(b.v, a.v * 0.5);
        seen.push_back(e);
    });
    std::sort(seen.begin(), seen.end());
    EXPECT_EQ(seen, both);
}

TEST(Registry, DestroyRemovesAllComponents)
{
    TestRegistry reg;
    const sm::Entity e = reg.create();
    reg.emplace(e, A{1});
    reg.emplace(e, B{2});
    ASSERT_TRUE(reg.destroy(e));
    EXPECT_FALSE(reg.valid(e));
    EXPECT_EQ(reg.store<A>().size(), 0u);
    EXPECT_EQ(reg.store<B>().size(), 0u);
    EXPECT_FALSE(reg.destroy(e));
}

TEST(Registry, IterationOrderIsTheSameForTheSameHistory)
{
    auto history = [] {
        TestRegistry reg;
        std::vector<sm::Entity> es;
        for (int i = 0; i < 50; ++i) {
            es.push_back(reg.create());
            reg.emplace(es.back(), A{i});
        }
        for (int i = 0; i < 50; i += 7)
            reg.destroy(es[i]);
        for (int i = 0; i < 5; ++i)
            reg.emplace(reg.create(), A{100 + i});
        std::vector<int> order;
        reg.each<A>([&](sm::Entity, A& a) { order.push_back(a.v); });
        return order;
    };
    EXPECT_EQ(history(), history());
}
