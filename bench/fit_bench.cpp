// SPDX-License-Identifier: MIT
// Cost of superquadric fitting (docs/pipeline.md): one fit of a tessellated, randomly posed superquadric per
// iteration, plain and with taper/bend, by mesh resolution; and mesh import of an OBJ. The accuracy each
// fit reached is reported as counters (radius and ε errors, rms relative to size).
#include "../tests/fit/fit_cases.h"
#include "supermodal/fit.h"
#include "supermodal/mesh_io.h"

#include <algorithm>
#include <benchmark/benchmark.h>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace sm = supermodal;

namespace
{

sm::ShapeDef bench_shape(int64_t kind)
{
    sm::ShapeDef s = sm::default_shape_def();
    s.radii = {0.15, 0.3, 0.6};
    s.epsilon1 = 0.4;
    s.epsilon2 = 0.9;
    if (kind >= 1)
        s.taper = {0.3, -0.2};
    if (kind >= 2)
        s.bend = {0.8, 0.5};
    return s;
}

void report(benchmark::State& state, const sm::FitResult& f, const sm::ShapeDef& truth)
{
    double got[3] = {f.shape.radii.x, f.shape.radii.y, f.shape.radii.z};
    double want[3] = {truth.radii.x, truth.radii.y, truth.radii.z};
    std::sort(got, got + 3);
    std::sort(want, want + 3);
    double radius_error = 0.0;
    for (int i = 0; i < 3; ++i)
        radius_error = std::max(radius_error, std::abs(got[i] / want[i] - 1.0));
    state.counters["radius_err"] = radius_error;
    state.counters["eps_err"] =
        std::max(std::abs(f.shape.epsilon1 - truth.epsilon1), std::abs(f.shape.epsilon2 - truth.epsilon2));
    state.counters["rms_rel"] = f.rms_relative;
    state.counters["lm_iterations"] = f.iterations;
}

/// Args: shape kind (0 plain, 1 tapered, 2 tapered + bent), tessellation resolution.
void BM_FitMesh(benchmark::State& state)
{
    const sm::test::PosedShape truth = sm::test::random_pose(bench_shape(state.range(0)), 5);
    const sm::TriangleMesh mesh = sm::test::posed_mesh(truth, int(state.range(1)));
    sm::FitDef def = sm::default_fit_def();
    def.taper = state.range(0) >= 1;
    def.bend = state.range(0) >= 2;
    sm::FitResult last;
    for (auto _ : state) {
        auto fit = sm::fit_superquadric(mesh, def);
        benchmark::DoNotOptimize(fit);
        last = *fit;
    }
    state.counters["vertices"] = double(mesh.positions.size());
    report(state, last, truth.shape);
}
BENCHMARK(BM_FitMesh)
    ->ArgsProduct({{0, 1, 2}, {24, 48, 96}})
    ->Unit(benchmark::kMillisecond)
    ->ArgNames({"kind", "res"});

/// OBJ import of a tessellated superquadric, by resolution.
void BM_ImportObj(benchmark::State& state)
{
    const sm::TriangleMesh mesh = sm::tessellate(bench_shape(0), int(state.range(0)));
    const auto path = std::filesystem::temp_directory_path() / "supermodal_fit_bench.obj";
    {
        std::ofstream out(path);
        char line[160];
        for (const sm::Vec3& p : mesh.positions) {
            std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", p.x, p.y, p.z);
            out << line;
        }
        for (size_t t = 0; t < mesh.indices.size(); t += 3)
            out << "f " << mesh.indices[t] + 1 << ' ' << mesh.indices[t + 1] + 1 << ' '
                << mesh.indices[t + 2] + 1 << '\n';
    }
    for (auto _ : state) {
        auto m = sm::import_mesh(path.string());
        benchmark::DoNotOptimize(m);
    }
    state.counters["triangles"] = double(mesh.indices.size() / 3);
}
BENCHMARK(BM_ImportObj)->Arg(48)->Arg(192)->Unit(benchmark::kMillisecond);

} // namespace
