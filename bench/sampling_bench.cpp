// SPDX-License-Identifier: MIT
// Surface sampling (samples/s) and tessellation (triangles/s) of superquadrics across ε, with the
// accuracy each setting buys: the divergence-theorem volume from the samples (∮ p·n dA = 3V) and the
// mesh volume, both against the closed-form Beta-function volume.
#include "supermodal/geometry.h"
#include "supermodal/shape.h"

#include <benchmark/benchmark.h>
#include <cmath>

namespace sm = supermodal;

namespace
{

// Exponents by index: a box-like ε = 0.1, the ellipsoid, the octahedron and the concave ε = 4 star.
constexpr double k_epsilons[] = {0.1, 1.0, 2.0, 4.0};

sm::ShapeDef shape_for(int64_t epsilon_index)
{
    sm::ShapeDef s = sm::default_shape_def();
    s.radii = {0.1, 0.2, 0.3};
    s.epsilon1 = s.epsilon2 = k_epsilons[epsilon_index];
    return s;
}

double spacing_for(const sm::ShapeDef& s, int64_t count)
{
    double area = 0.0;
    for (const sm::SurfaceSample& x : sm::sample_surface(s, 1e9, 2))
        area += x.area;
    return std::sqrt(area / double(count));
}

} // namespace

// Arguments: ε index, wanted sample count.
static void BM_Sampling_SampleSurface(benchmark::State& st)
{
    const sm::ShapeDef s = shape_for(st.range(0));
    const double spacing = spacing_for(s, st.range(1));
    size_t count = 0;
    for (auto _ : st) {
        const std::vector<sm::SurfaceSample> v = sm::sample_surface(s, spacing, 1'000'000);
        count = v.size();
        benchmark::DoNotOptimize(v.data());
    }
    st.SetItemsProcessed(int64_t(st.iterations()) * int64_t(count)); // samples
    double three_v = 0.0;
    for (const sm::SurfaceSample& x : sm::sample_surface(s, spacing, 1'000'000))
        three_v += sm::dot(x.point, x.normal) * x.area;
    st.counters["epsilon"] = k_epsilons[st.range(0)];
    st.counters["samples"] = double(count);
    st.counters["div_volume_rel_err"] = std::abs(three_v / (3.0 * sm::superquadric_volume(s)) - 1.0);
}
BENCHMARK(BM_Sampling_SampleSurface)
    ->ArgsProduct({{0, 1, 2, 3}, {100, 1'000, 10'000, 100'000}})
    ->Unit(benchmark::kMicrosecond);

// Arguments: ε index, resolution (segments around the equator).
static void BM_Sampling_Tessellate(benchmark::State& st)
{
    const sm::ShapeDef s = shape_for(st.range(0));
    size_t triangles = 0;
    for (auto _ : st) {
        const sm::TriangleMesh m = sm::tessellate(s, int(st.range(1)));
        triangles = m.indices.size() / 3;
        benchmark::DoNotOptimize(m.positions.data());
    }
    st.SetItemsProcessed(int64_t(st.iterations()) * int64_t(triangles)); // triangles
    const double volume = sm::mesh_volume(sm::tessellate(s, int(st.range(1))));
    st.counters["epsilon"] = k_epsilons[st.range(0)];
    st.counters["triangles"] = double(triangles);
    st.counters["volume_rel_err"] = std::abs(volume / sm::superquadric_volume(s) - 1.0);
}
BENCHMARK(BM_Sampling_Tessellate)->ArgsProduct({{0, 1, 2, 3}, {16, 64, 256}})->Unit(benchmark::kMicrosecond);
