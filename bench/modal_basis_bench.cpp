// SPDX-License-Identifier: MIT
// Modal basis build cost over lattice sizes: a rounded cube (ε = 0.1, 1 m side) of 20-node cells,
// 12 elastic modes, through the public build (assembly, factorization, eigen iteration, checks).
// Counter peak_mb is this process's peak resident set: run one size per process for a per-size figure
// (bench/modal_basis_report.py does, and writes docs/bench/modal_basis.csv and .png).
#include "supermodal/modal.h"

#include <benchmark/benchmark.h>
#include <sys/resource.h>

namespace sm = supermodal;

namespace
{

sm::ModalBasisDef cube_def(int cells)
{
    sm::ModalBasisDef def = sm::default_modal_basis_def();
    def.shape.epsilon1 = def.shape.epsilon2 = 0.1;
    def.lattice.cells = {cells, cells, cells};
    def.lattice.element_order = 2;
    def.mode_count = 12;
    return def;
}

double peak_resident_mb()
{
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<double>(usage.ru_maxrss) / 1024.0; // Linux: kilobytes
}

} // namespace

// Arg: cells per axis.
static void BM_ModalBasis_Cube(benchmark::State& st)
{
    const sm::ModalBasisDef def = cube_def(static_cast<int>(st.range(0)));
    sm::ModalBasis last;
    for (auto _ : st) {
        sm::Result<sm::ModalBasis> b = sm::build_modal_basis(def);
        if (!b) {
            st.SkipWithError(b.error().message().c_str());
            return;
        }
        last = std::move(*b);
    }
    const sm::ModalDiagnostics& d = last.diagnostics;
    st.counters["dofs"] = d.dof_count;
    st.counters["assembly_s"] = d.assembly_seconds;
    st.counters["eigen_s"] = d.eigen_seconds;
    st.counters["rounds"] = d.solver_rounds;
    st.counters["checked"] = d.inertia_checked ? 1.0 : 0.0;
    st.counters["f1_hz"] = last.frequencies_hz[0];
    st.counters["f12_hz"] = last.frequencies_hz[11];
    st.counters["peak_mb"] = peak_resident_mb();
}
BENCHMARK(BM_ModalBasis_Cube)
    ->Arg(4)
    ->Arg(6)
    ->Arg(8)
    ->Arg(10)
    ->Arg(12)
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);
