// Tests for engine/src/contact/broadphase.cpp.
#include "contact/broadphase.h"

#include <algorithm>
#include <gtest/gtest.h>
#include <random>

namespace sm = supermodal;

namespace
{

std::vector<sm::BroadphaseProxy> random_boxes(int n, uint32_t seed, double world_size, double max_half)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> pos(0.0, world_size), half(0.01, max_half);
    std::vector<sm::BroadphaseProxy> out;
    for (int i = 0; i < n; ++i) {
        const sm::Vec3 c{pos(rng), pos(rng), pos(rng)};
        const sm::Vec3 h{half(rng), half(rng), half(rng)};
        out.push_back(
            {.entity = {static_cast<uint32_t>(i + 1), 1}, .box = {c - h, c + h}, .is_static = i % 10 == 0});
    }
    return out;
}

std::vector<sm::BodyPair> brute_force(const std::vector<sm::BroadphaseProxy>& ps)
{
    std::vector<sm::BodyPair> out;
    for (size_t i = 0; i < ps.size(); ++i)
        for (size_t j = i + 1; j < ps.size(); ++j)
            if (!(ps[i].is_static && ps[j].is_static) && sm::overlaps(ps[i].box, ps[j].box))
                out.push_back({ps[i].entity, ps[j].entity});
    std::sort(out.begin(), out.end(), [](auto& l, auto& r) { return l.key() < r.key(); });
    return out;
}

} // namespace

TEST(Broadphase, MatchesBruteForceOnRandomBoxes)
{
    for (uint32_t seed : {1u, 2u, 3u}) {
        const auto ps = random_boxes(600, seed, 10.0, 0.6);
        sm::BroadphaseScratch scratch;
        std::vector<sm::BodyPair> pairs;
        sm::find_overlapping_pairs(ps, scratch, pairs);
        EXPECT_EQ(pairs, brute_force(ps)) << "seed " << seed;
        EXPECT_FALSE(pairs.empty());
    }
}

TEST(Broadphase, OrderDoesNotDependOnInputOrder)
{
    auto ps = random_boxes(300, 7, 5.0, 0.5);
    sm::BroadphaseScratch scratch;
    std::vector<sm::BodyPair> a, b;
    sm::find_overlapping_pairs(ps, scratch, a);
    std::reverse(ps.begin(), ps.end());
    sm::find_overlapping_pairs(ps, scratch, b);
    EXPECT_EQ(a, b);
}

TEST(Broadphase, TouchingBoxesPairAndStaticPairsDoNot)
{
    std::vector<sm::BroadphaseProxy> ps = {
        {.entity = {1, 1}, .box = {{0, 0, 0}, {1, 1, 1}}},
        {.entity = {2, 1}, .box = {{1, 0, 0}, {2, 1, 1}}},                    // touches 1
        {.entity = {3, 1}, .box = {{0, 0, 0}, {5, 5, 5}}, .is_static = true}, // overlaps all
        {.entity = {4, 1}, .box = {{4, 4, 4}, {6, 6, 6}}, .is_static = true}, // static: not with 3
    };
    sm::BroadphaseScratch scratch;
    std::vector<sm::BodyPair> pairs;
    sm::find_overlapping_pairs(ps, scratch, pairs);
    const std::vector<sm::BodyPair> expected = {{{1, 1}, {2, 1}}, {{1, 1}, {3, 1}}, {{2, 1}, {3, 1}}};
    EXPECT_EQ(pairs, expected);
}

TEST(Broadphase, IdenticalBoxesAreAllPaired)
{
    // Ties in the sweep key are broken by entity index; every pair must still be found exactly once.
    std::vector<sm::BroadphaseProxy> ps;
    for (uint32_t i = 1; i <= 20; ++i)
        ps.push_back({.entity = {i, 1}, .box = {{0, 0, 0}, {1, 1, 1}}});
    sm::BroadphaseScratch scratch;
    std::vector<sm::BodyPair> pairs;
    sm::find_overlapping_pairs(ps, scratch, pairs);
    EXPECT_EQ(pairs.size(), 20u * 19u / 2u);
}
