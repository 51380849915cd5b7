// SPDX-License-Identifier: MIT
// Narrowphase cost per touching pair: libccd MPR on the analytic support map alone, the full
// support-map path (MPR + manifold update), and the sampling path, for the pile benchmark's three
// shapes (sphere r 0.05, ellipsoid (0.06, 0.04, 0.03), rounded box half 0.05 ε = 0.3), each pair
// stacked 1 mm into each other with a small tilt, as in a resting pile.
#include "contact/manifold.h"
#include "contact/mpr.h"
#include "contact/narrowphase.h"

#include <benchmark/benchmark.h>
#include <cmath>
#include <memory>
#include <vector>

namespace sm = supermodal;

namespace
{

struct Pair {
    sm::Collider collider;
    sm::BodyView a, b;
};

// Built in place: the views point at the collider.
std::unique_ptr<Pair> make_pair(int64_t shape_index)
{
    sm::ShapeDef s = sm::default_shape_def();
    if (shape_index == 0) {
        s.radii = {0.05, 0.05, 0.05};
    } else if (shape_index == 1) {
        s.radii = {0.06, 0.04, 0.03};
    } else {
        s.radii = {0.05, 0.05, 0.05};
        s.epsilon1 = s.epsilon2 = 0.3;
    }
    auto p = std::make_unique<Pair>(Pair{sm::make_collider(s, {}, 0.0, 4000), {}, {}});
    const sm::Quat tilt = sm::normalized(sm::Quat{1.0, 0.01, 0.0, 0.005});
    const double h = s.radii.y; // along y the pair stacks
    p->b = {&p->collider, {0, 0, 0}, sm::Quat{}, {}};
    p->a = {&p->collider, {0.002, 2.0 * h - 0.001, 0.001}, tilt, {}};
    p->b.box = sm::world_aabb(s, p->b.position, p->b.orientation);
    p->a.box = sm::world_aabb(s, p->a.position, p->a.orientation);
    return p;
}

void label(benchmark::State& st)
{
    static const char* names[] = {"sphere", "ellipsoid", "rounded_box"};
    st.SetLabel(names[st.range(0)]);
    st.SetItemsProcessed(int64_t(st.iterations())); // pairs
}

} // namespace

static void BM_Narrowphase_Mpr(benchmark::State& st)
{
    const std::unique_ptr<Pair> p = make_pair(st.range(0));
    for (auto _ : st) {
        const sm::MprResult r = sm::mpr_penetration(p->a, p->b);
        benchmark::DoNotOptimize(r.depth);
    }
    label(st);
}
BENCHMARK(BM_Narrowphase_Mpr)->DenseRange(0, 2)->Unit(benchmark::kNanosecond);

static void BM_Narrowphase_SupportMapManifold(benchmark::State& st)
{
    const std::unique_ptr<Pair> p = make_pair(st.range(0));
    sm::PairManifold m;
    std::vector<sm::ContactPoint> out;
    int points = 0;
    for (auto _ : st) {
        out.clear();
        points = sm::collide_manifold(p->a, p->b, m, out);
        benchmark::DoNotOptimize(out.data());
    }
    label(st);
    st.counters["points"] = points;
}
BENCHMARK(BM_Narrowphase_SupportMapManifold)->DenseRange(0, 2)->Unit(benchmark::kNanosecond);

static void BM_Narrowphase_Sampling(benchmark::State& st)
{
    const std::unique_ptr<Pair> p = make_pair(st.range(0));
    std::vector<sm::ContactPoint> out;
    int points = 0;
    for (auto _ : st) {
        out.clear();
        points = sm::collide_sampled(p->a, p->b, out);
        benchmark::DoNotOptimize(out.data());
    }
    label(st);
    st.counters["points"] = points;
    st.counters["samples_per_body"] = double(p->collider.samples->samples.size());
}
BENCHMARK(BM_Narrowphase_Sampling)->DenseRange(0, 2)->Unit(benchmark::kNanosecond);
