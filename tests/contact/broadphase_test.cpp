// Tests for engine/src/contact/broadphase.cpp.
#include "contact/broadphase.h"
#include "supermodal/tasks.h"

#include <algorithm>
#include <gtest/gtest.h>
#include <limits>
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

TEST(Broadphase, ThreadsFindTheSamePairs)
{
    // Enough boxes for several thread parts, some of them big (tested against all) and unbounded.
    auto ps = random_boxes(3000, 11, 20.0, 0.5);
    ps[5].box = {{-1e300, -1e300, -1e300}, {1e300, 0.0, 1e300}};
    ps[17].box.max.x += 6.0;
    const std::vector<sm::BodyPair> expected = brute_force(ps);
    for (int threads : {2, 3, 8}) {
        const std::shared_ptr<sm::TaskSystem> pool = sm::make_thread_pool(threads);
        sm::BroadphaseScratch scratch;
        std::vector<sm::BodyPair> pairs;
        sm::find_overlapping_pairs(ps, scratch, pairs, sm::Parallel(pool.get()));
        EXPECT_EQ(pairs, expected) << threads << " threads";
        EXPECT_GT(sm::Parallel(pool.get()).part_count(ps.size(), 256), 1u); // the split is exercised
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

TEST(Broadphase, MixedSizesFarCoordinatesAndUnboundedBoxesMatchBruteForce)
{
    // Boxes from 1 mm to 5 m (the big ones go to the all-against-all list), a few beyond the grid's
    // coordinate clamp (1e9 m with 2 cm cells), an unbounded box like a plane's, and a NaN box that
    // must pair with nothing.
    auto ps = random_boxes(800, 11, 4.0, 0.05);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int i = 0; i < 40; ++i) {
        auto& b = ps[static_cast<size_t>(i * 20 + 1)].box;
        const double h = 0.0005 + 2.5 * u(rng);
        const sm::Vec3 c = 0.5 * (b.min + b.max);
        b = {c - sm::Vec3{h, h, h}, c + sm::Vec3{h, h, h}};
    }
    for (int i = 0; i < 3; ++i) {
        const sm::Vec3 far{1e9 + i * 0.01, -1e9, 1e9};
        ps[static_cast<size_t>(i * 7 + 3)].box = {far, far + sm::Vec3{0.05, 0.05, 0.05}};
    }
    constexpr double inf = std::numeric_limits<double>::infinity();
    ps[5].box = {{-inf, -inf, -inf}, {inf, 0.5, inf}};
    ps[5].is_static = true;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    ps[9].box = {{nan, 0, 0}, {nan, 1, 1}};
    sm::BroadphaseScratch scratch;
    std::vector<sm::BodyPair> pairs;
    sm::find_overlapping_pairs(ps, scratch, pairs);
    EXPECT_EQ(pairs, brute_force(ps));
    for (const sm::BodyPair& p : pairs)
        EXPECT_TRUE(p.a.index != 10 && p.b.index != 10); // the NaN box (entity 10)
}

TEST(Broadphase, DensePileMatchesBruteForce)
{
    // The pile's situation: 3000 boxes of 0.1 m at 0.12 m pitch, jittered ±2 cm: neighbours within
    // the jitter touch (1271 pairs).
    std::vector<sm::BroadphaseProxy> ps;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> jitter(-0.02, 0.02);
    for (uint32_t i = 0; i < 3000; ++i) {
        const sm::Vec3 c{0.12 * (i % 15) + jitter(rng), 0.12 * ((i / 15) % 20) + jitter(rng),
                         0.12 * (i / 300) + jitter(rng)};
        ps.push_back(
            {.entity = {i + 1, 1}, .box = {c - sm::Vec3{0.05, 0.05, 0.05}, c + sm::Vec3{0.05, 0.05, 0.05}}});
    }
    sm::BroadphaseScratch scratch;
    std::vector<sm::BodyPair> pairs;
    sm::find_overlapping_pairs(ps, scratch, pairs);
    EXPECT_EQ(pairs, brute_force(ps));
    EXPECT_GT(pairs.size(), 1000u);
}

TEST(Broadphase, PairKeyUnpacksToItsTwoIndices)
{
    // The key orders pairs by a's index, then b's; the largest indices must survive the round trip.
    const sm::BodyPair pair{.a = {.index = 7, .generation = 3}, .b = {.index = 0xfffffffeu, .generation = 1}};
    const auto [a, b] = sm::pair_key_indices(pair.key());
    EXPECT_EQ(a, 7u);
    EXPECT_EQ(b, 0xfffffffeu);
    EXPECT_LT(pair.key(), (sm::BodyPair{.a = {.index = 8}, .b = {.index = 9}}.key()));
}
