// SPDX-License-Identifier: MIT
// Cost of the superquadric point queries (ns per call) across ε, with the accuracy each one reaches:
// the inside-outside function, the contact measure, the implicit normal, the support map and the
// closest-point projection (with its mean error bound), and the world box (cached vertex sets of
// deformed shapes and hyperquadrics against recomputing them).
#include "geometry/bounds_internal.h"
#include "supermodal/geometry.h"
#include "supermodal/shape.h"

#include <benchmark/benchmark.h>
#include <cmath>
#include <random>
#include <vector>

namespace sm = supermodal;

namespace
{

// Exponents by index: the box-like ε = 0.1, the ellipsoid, the octahedron and the concave ε = 4 star.
constexpr double k_epsilons[] = {0.1, 1.0, 2.0, 4.0};
// Queries cycle through this many prepared inputs, so branch predictors see a realistic mix.
constexpr int k_inputs = 1024;

sm::ShapeDef shape_for(int64_t epsilon_index)
{
    sm::ShapeDef s = sm::default_shape_def();
    s.radii = {0.1, 0.2, 0.3};
    s.epsilon1 = s.epsilon2 = k_epsilons[epsilon_index];
    return s;
}

// Points as contact produces them: within ±20% of the surface along random rays, a few far away.
std::vector<sm::Vec3> near_surface_points(const sm::ShapeDef& s)
{
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::vector<sm::Vec3> points;
    for (int i = 0; i < k_inputs; ++i) {
        const sm::Vec3 d{unit(rng), unit(rng), unit(rng)};
        const double scale = (i % 16 == 0 ? 10.0 : 1.0 + 0.2 * unit(rng)) / (sm::contact_measure(s, d) + 1.0);
        points.push_back(d * scale);
    }
    return points;
}

std::vector<sm::Vec3> unit_directions()
{
    std::mt19937_64 rng(2);
    std::normal_distribution<double> g;
    std::vector<sm::Vec3> dirs;
    for (int i = 0; i < k_inputs; ++i)
        dirs.push_back(sm::normalized(sm::Vec3{g(rng), g(rng), g(rng)}));
    return dirs;
}

template <class Query>
void run_point_query(benchmark::State& st, const std::vector<sm::Vec3>& inputs, Query&& query)
{
    size_t i = 0;
    for (auto _ : st) {
        benchmark::DoNotOptimize(query(inputs[i]));
        i = (i + 1) % inputs.size();
    }
    st.SetItemsProcessed(int64_t(st.iterations())); // queries
}

} // namespace

static void BM_Geometry_InsideOutside(benchmark::State& st)
{
    const sm::ShapeDef s = shape_for(st.range(0));
    run_point_query(st, near_surface_points(s), [&](const sm::Vec3& p) { return sm::inside_outside(s, p); });
}
BENCHMARK(BM_Geometry_InsideOutside)->DenseRange(0, 3);

static void BM_Geometry_ContactMeasure(benchmark::State& st)
{
    const sm::ShapeDef s = shape_for(st.range(0));
    run_point_query(st, near_surface_points(s), [&](const sm::Vec3& p) { return sm::contact_measure(s, p); });
}
BENCHMARK(BM_Geometry_ContactMeasure)->DenseRange(0, 3);

static void BM_Geometry_ContactMeasureGradient(benchmark::State& st)
{
    const sm::ShapeDef s = shape_for(st.range(0));
    run_point_query(st, near_surface_points(s),
                    [&](const sm::Vec3& p) { return sm::contact_measure_gradient(s, p); });
}
BENCHMARK(BM_Geometry_ContactMeasureGradient)->DenseRange(0, 3);

static void BM_Geometry_ImplicitNormal(benchmark::State& st)
{
    const sm::ShapeDef s = shape_for(st.range(0));
    run_point_query(st, near_surface_points(s), [&](const sm::Vec3& p) { return sm::implicit_normal(s, p); });
}
BENCHMARK(BM_Geometry_ImplicitNormal)->DenseRange(0, 3);

static void BM_Geometry_SupportPoint(benchmark::State& st)
{
    const sm::ShapeDef s = shape_for(st.range(0));
    const std::vector<sm::Vec3> dirs = unit_directions();
    run_point_query(st, dirs, [&](const sm::Vec3& d) { return sm::support_point(s, d); });
    double worst = 0.0; // |measure| of the support points: how far off the surface they land
    for (const sm::Vec3& d : dirs)
        worst = std::max(worst, std::abs(sm::contact_measure(s, sm::support_point(s, d))));
    st.counters["max_abs_measure"] = worst;
}
BENCHMARK(BM_Geometry_SupportPoint)->DenseRange(0, 3);

static void BM_Geometry_ClosestPoint(benchmark::State& st)
{
    const sm::ShapeDef s = shape_for(st.range(0));
    const std::vector<sm::Vec3> points = near_surface_points(s);
    run_point_query(st, points, [&](const sm::Vec3& p) { return sm::closest_point(s, p).distance; });
    double bound_sum = 0.0, bound_max = 0.0, iterations = 0.0;
    for (const sm::Vec3& p : points) {
        const sm::SurfaceProjection r = sm::closest_point(s, p);
        bound_sum += r.error_bound;
        bound_max = std::max(bound_max, r.error_bound);
        iterations += r.iterations;
    }
    // Error bounds relative to the largest radius (0.3 m), and Newton iterations per call.
    st.counters["mean_bound_rel"] = bound_sum / double(points.size()) / 0.3;
    st.counters["max_bound_rel"] = bound_max / 0.3;
    st.counters["iterations"] = iterations / double(points.size());
}
BENCHMARK(BM_Geometry_ClosestPoint)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);

namespace
{

// Shapes whose world box bounds a tessellation: 0 tapered + bent superquadric, 1 four-term hyperquadric.
sm::ShapeDef tessellated_shape(int64_t index)
{
    sm::ShapeDef s = shape_for(1);
    if (index == 0) {
        s.taper = {0.5, -0.3};
        s.bend = {2.0, 0.4};
        return s;
    }
    s.type = sm::ShapeType::Hyperquadric;
    s.terms = {{{10, 0, 0}, 0, 4}, {{0, 5, 0}, 0, 4}, {{0, 0, 3.3}, 0, 4}, {{4, 4, 4}, 0.1, 2}};
    return s;
}

std::vector<sm::Quat> random_orientations()
{
    std::mt19937_64 rng(3);
    std::normal_distribution<double> g;
    std::vector<sm::Quat> qs;
    for (int i = 0; i < k_inputs; ++i)
        qs.push_back(sm::normalized(sm::Quat{g(rng), g(rng), g(rng), g(rng)}));
    return qs;
}

} // namespace

// World box as the broadphase asks for it every step; arg 0 as shape_for (undeformed, support map).
static void BM_Geometry_WorldAabb(benchmark::State& st)
{
    const sm::ShapeDef s = shape_for(st.range(0));
    const std::vector<sm::Quat> qs = random_orientations();
    size_t i = 0;
    for (auto _ : st) {
        benchmark::DoNotOptimize(sm::world_aabb(s, {1, 2, 3}, qs[i]));
        i = (i + 1) % qs.size();
    }
    st.SetItemsProcessed(int64_t(st.iterations()));
}
BENCHMARK(BM_Geometry_WorldAabb)->DenseRange(0, 3);

// Deformed (0) and hyperquadric (1) shapes: the cached vertex set against recomputing it per call.
static void BM_Geometry_WorldAabbTessellated(benchmark::State& st)
{
    const sm::ShapeDef s = tessellated_shape(st.range(0));
    const bool cached = st.range(1) != 0;
    const std::vector<sm::Quat> qs = random_orientations();
    size_t i = 0;
    for (auto _ : st) {
        benchmark::DoNotOptimize(cached ? sm::world_aabb(s, {1, 2, 3}, qs[i])
                                        : sm::world_aabb_uncached(s, {1, 2, 3}, qs[i]));
        i = (i + 1) % qs.size();
    }
    st.SetItemsProcessed(int64_t(st.iterations()));
}
BENCHMARK(BM_Geometry_WorldAabbTessellated)
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->ArgNames({"shape", "cached"})
    ->Unit(benchmark::kMicrosecond);
