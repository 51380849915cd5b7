// SPDX-License-Identifier: MIT
// Modal bases: build time and frequency error against beam theory as the lattice refines (the free-free
// 2x4 board), build time of a sphere, and the cost of deforming points through the modes.
#include "modal/beam_reference.h"
#include "supermodal/modal.h"

#include <benchmark/benchmark.h>
#include <cmath>
#include <vector>

namespace sm = supermodal;
namespace modal = supermodal::modal;

namespace
{

// The 2x4 board of tests/modal/modal_scenes.h: length along x, thickness 0.038 m along y, width 0.089 m
// along z; E 11 GPa, ν 0.3, ρ 450 kg/m³, ε1 = ε2 = 0.05.
sm::ModalBasisDef board_def(int nx, int ny, int nz, int order)
{
    sm::ModalBasisDef def = sm::default_modal_basis_def();
    def.shape.radii = {0.5, 0.019, 0.0445};
    def.shape.epsilon1 = def.shape.epsilon2 = 0.05;
    def.density = 450.0;
    def.young = 11e9;
    def.poisson = 0.3;
    def.lattice.cells = {nx, ny, nz};
    def.lattice.element_order = order;
    def.mode_count = 6;
    return def;
}

modal::BeamSection board_section(double depth, double other)
{
    return {1.0,  depth * other, other * depth * depth * depth / 12.0,   450.0,
            11e9, 0.3,           modal::rectangle_shear_coefficient(0.3)};
}

/// Lowest mode whose tip (x = 0.5 m) moves mostly along `axis` (1: flatwise, 2: edgewise) [Hz].
double first_bending_hz(const sm::ModalBasis& b, int axis)
{
    for (int k = 0; k < b.mode_count; ++k) {
        std::vector<double> q(b.mode_count, 0.0);
        q[k] = 1.0;
        const sm::Vec3 u = sm::modal_displacement(b, sm::Vec3{0.5, 0.0, 0.0}, q);
        if (b.kinds[k] == sm::ModeKind::Bend && std::abs(u[axis]) > std::abs(u[3 - axis]))
            return b.frequencies_hz[k];
    }
    return 0.0;
}

void report_board(benchmark::State& st, const sm::ModalBasis& b)
{
    const modal::BeamSection flat = board_section(0.038, 0.089), edge = board_section(0.089, 0.038);
    const double f_flat = first_bending_hz(b, 1), f_edge = first_bending_hz(b, 2);
    st.counters["dofs"] = b.diagnostics.dof_count;
    st.counters["assembly_ms"] = 1e3 * b.diagnostics.assembly_seconds;
    st.counters["eigen_ms"] = 1e3 * b.diagnostics.eigen_seconds;
    st.counters["flat_hz"] = f_flat;
    st.counters["edge_hz"] = f_edge;
    st.counters["flat_err_timo_pct"] = 100.0 * (f_flat / modal::timoshenko_free_free_hz(flat, 1) - 1.0);
    st.counters["edge_err_timo_pct"] = 100.0 * (f_edge / modal::timoshenko_free_free_hz(edge, 1) - 1.0);
    st.counters["flat_err_eb_pct"] = 100.0 * (f_flat / modal::euler_bernoulli_free_free_hz(flat, 1) - 1.0);
    st.counters["edge_err_eb_pct"] = 100.0 * (f_edge / modal::euler_bernoulli_free_free_hz(edge, 1) - 1.0);
    st.counters["mass_kg"] = b.mass;
}

} // namespace

// Args: cells along x, y, z, element order.
static void BM_Modal_BoardBuild(benchmark::State& st)
{
    const sm::ModalBasisDef def = board_def(static_cast<int>(st.range(0)), static_cast<int>(st.range(1)),
                                            static_cast<int>(st.range(2)), static_cast<int>(st.range(3)));
    sm::ModalBasis last;
    for (auto _ : st) {
        sm::Result<sm::ModalBasis> b = sm::build_modal_basis(def);
        if (!b) {
            st.SkipWithError(b.error().message().c_str());
            return;
        }
        last = std::move(*b);
    }
    report_board(st, last);
}
BENCHMARK(BM_Modal_BoardBuild)
    ->Args({4, 1, 1, 2})
    ->Args({8, 1, 1, 2})
    ->Args({16, 1, 1, 2})
    ->Args({32, 1, 1, 2})
    ->Args({16, 2, 4, 2})
    ->Args({32, 2, 4, 2})
    ->Args({64, 2, 4, 2})
    ->Args({16, 2, 2, 1})
    ->Args({32, 2, 4, 1})
    ->Args({64, 4, 8, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Arg: cells per axis (20-node cells, 12 modes). Error against Lamb's torsional mode ₀T₂.
static void BM_Modal_SphereBuild(benchmark::State& st)
{
    sm::ModalBasisDef def = sm::default_modal_basis_def();
    const int n = static_cast<int>(st.range(0));
    def.lattice.cells = {n, n, n};
    sm::ModalBasis last;
    for (auto _ : st) {
        sm::Result<sm::ModalBasis> b = sm::build_modal_basis(def);
        if (!b) {
            st.SkipWithError(b.error().message().c_str());
            return;
        }
        last = std::move(*b);
    }
    const double c_s = std::sqrt(def.young / (2.0 * (1.0 + def.poisson)) / def.density);
    const double t2 = 2.5011326 * c_s / (2.0 * 3.14159265358979 * def.shape.radii.x);
    st.counters["dofs"] = last.diagnostics.dof_count;
    st.counters["assembly_ms"] = 1e3 * last.diagnostics.assembly_seconds;
    st.counters["eigen_ms"] = 1e3 * last.diagnostics.eigen_seconds;
    st.counters["t2_err_pct"] = 100.0 * (last.frequencies_hz[0] / t2 - 1.0);
    st.counters["aggregated"] = last.diagnostics.aggregated_cell_count;
}
BENCHMARK(BM_Modal_SphereBuild)->DenseRange(3, 8)->Unit(benchmark::kMillisecond)->UseRealTime();

// The board with r modes and 10k points spread over it (rest positions and their lattice weights),
// amplitudes 1e-3/(k+1): what both deformation benchmarks deform. False (and the benchmark skipped)
// when the basis cannot be built.
struct DeformCase {
    sm::ModalBasis basis;
    std::vector<sm::Vec3> rest;
    std::vector<sm::LatticeWeights> weights;
    std::vector<double> q;
};
constexpr int k_deform_points = 10'000;

static bool make_deform_case(benchmark::State& st, DeformCase& c)
{
    sm::ModalBasisDef def = board_def(16, 1, 1, 2);
    def.mode_count = static_cast<int>(st.range(0));
    sm::Result<sm::ModalBasis> b = sm::build_modal_basis(def);
    if (!b) {
        st.SkipWithError(b.error().message().c_str());
        return false;
    }
    c.basis = std::move(*b);
    for (int i = 0; i < k_deform_points; ++i) {
        const double t = (i + 0.5) / k_deform_points;
        c.rest.push_back({0.5 * std::cos(9.0 * t), 0.019 * std::sin(37.0 * t), 0.0445 * std::cos(53.0 * t)});
        c.weights.push_back(sm::modal_weights(c.basis, c.rest.back()));
    }
    c.q.resize(static_cast<size_t>(c.basis.mode_count));
    for (int k = 0; k < c.basis.mode_count; ++k)
        c.q[k] = 1e-3 / (k + 1);
    return true;
}

// Arg: mode count. Deforms 10k points with precomputed weights (the per-step cost of a surface).
static void BM_Modal_DeformPoints(benchmark::State& st)
{
    DeformCase c;
    if (!make_deform_case(st, c))
        return;
    std::vector<sm::Vec3> out(k_deform_points);
    for (auto _ : st) {
        for (int i = 0; i < k_deform_points; ++i)
            out[i] = sm::modal_displacement(c.basis, c.weights[i], c.q);
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    st.SetItemsProcessed(st.iterations() * k_deform_points);
}
BENCHMARK(BM_Modal_DeformPoints)->Arg(6)->Arg(12)->Arg(30)->Unit(benchmark::kMicrosecond);

// A 10k-vertex render mesh on the board, the way the renderer deforms it: the modes summed once per
// lattice node (modal_nodal_displacements), then each vertex from its 20 weights (interpolate_nodal)
// added to its rest position. Counter GB/s: the bytes a vertex must move (its LatticeWeights, rest
// position in, position out) per second; compare with BM_Modal_MeshStreamFloor.
static void BM_Modal_DeformMesh(benchmark::State& st)
{
    DeformCase c;
    if (!make_deform_case(st, c))
        return;
    std::vector<sm::Vec3> out(k_deform_points), nodal;
    for (auto _ : st) {
        sm::modal_nodal_displacements(c.basis, c.q, nodal);
        for (int i = 0; i < k_deform_points; ++i)
            out[i] = c.rest[i] + sm::interpolate_nodal(c.weights[i], nodal);
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    const double bytes = k_deform_points * (sizeof(sm::LatticeWeights) + 2 * sizeof(sm::Vec3));
    st.counters["GB"] = benchmark::Counter(bytes * 1e-9, benchmark::Counter::kIsIterationInvariantRate);
    st.counters["nodes"] = static_cast<double>(nodal.size());
    st.SetItemsProcessed(st.iterations() * k_deform_points);
}
BENCHMARK(BM_Modal_DeformMesh)->Arg(6)->Arg(12)->Arg(30)->Unit(benchmark::kMicrosecond);

// The floor for the same bytes: read every vertex's LatticeWeights and rest position, write a position
// (the sum of a few of the bytes read, so nothing is optimised away), no modal work.
static void BM_Modal_MeshStreamFloor(benchmark::State& st)
{
    std::vector<sm::LatticeWeights> weights(k_deform_points);
    std::vector<sm::Vec3> rest(k_deform_points), out(k_deform_points);
    for (int i = 0; i < k_deform_points; ++i) {
        weights[i].count = 20;
        for (int a = 0; a < 20; ++a) {
            weights[i].nodes[a] = a;
            weights[i].weights[a] = 0.05;
        }
        rest[i] = {1.0 * i, 2.0, 3.0};
    }
    for (auto _ : st) {
        for (int i = 0; i < k_deform_points; ++i) {
            const sm::LatticeWeights& w = weights[i];
            double s = 0.0;
            for (int a = 0; a < 20; ++a)
                s += w.weights[a] + w.nodes[a];
            out[i] = rest[i] + sm::Vec3{s, 0.0, 0.0};
        }
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    const double bytes = k_deform_points * (sizeof(sm::LatticeWeights) + 2 * sizeof(sm::Vec3));
    st.counters["GB"] = benchmark::Counter(bytes * 1e-9, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_Modal_MeshStreamFloor)->Unit(benchmark::kMicrosecond);
