// SPDX-License-Identifier: MIT
// The modal trade (docs/modal.md "Full model and the modal trade"): cost per step of
// the full lattice (Newmark, sparse LDLᵀ) against the modal step with r modes, and the modal
// displacement error against the full model, for the 2x4 board and a soft ellipsoid struck by a
// half-sine load pulse, each at two lattice resolutions.
//
// Mode acceleration (static correction): the modal path plus, for the load's current size, the part of
// the full lattice's static response the kept modes miss, (K⁺ − Σ_k≤r φ_k φ_kᵀ/ω_k²) f, precomputed per
// (load point, probe) as one vector: 3 multiply-adds per probe per step on top of the modal step.
//
// Both paths solve the same damped model: Rayleigh damping with ζ = 0.02 at ω₁ and ω₆ in the full
// lattice, and each kept mode integrated exactly with its Rayleigh ratio. Step h = T₁/200.
#include "modal/full_model.h"
#include "modal/integrator.h"

#include <benchmark/benchmark.h>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <tuple>
#include <vector>

namespace sm = supermodal;
namespace mo = supermodal::modal;

namespace
{

constexpr int k_max_r = 48, k_steps = 200, k_division = 200; // one fundamental period at T₁/200
constexpr double k_zeta = 0.02;

struct Case {
    sm::ModalBasisDef def;
    sm::Vec3 struck, force, far;
};

// Args (body, resolution): body 0 board, 1 ellipsoid; resolution 0 coarse, 1 fine.
Case make_case(int body, int resolution)
{
    Case c;
    c.def = sm::default_modal_basis_def();
    c.def.mode_count = k_max_r;
    if (body == 0) { // the 2x4 board: 1.0 × 0.038 × 0.089 m, E 11 GPa, ρ 450 kg/m³
        c.def.shape.radii = {0.5, 0.019, 0.0445};
        c.def.shape.epsilon1 = c.def.shape.epsilon2 = 0.05;
        c.def.density = 450.0;
        c.def.young = 11e9;
        c.def.lattice.cells = resolution == 0 ? std::array<int, 3>{8, 1, 1} : std::array<int, 3>{16, 2, 2};
        c.struck = {0.31, 0.019, 0.02};
        c.force = {10.0, -100.0, 30.0};
        c.far = {-0.45, 0.0, 0.0};
    } else { // a soft ellipsoid: 0.6 × 0.4 × 0.3 m, E 1 MPa, ρ 1000 kg/m³
        c.def.shape.radii = {0.3, 0.2, 0.15};
        c.def.density = 1000.0;
        c.def.young = 1e6;
        c.def.lattice.cells = resolution == 0 ? std::array<int, 3>{6, 4, 3} : std::array<int, 3>{10, 7, 5};
        c.struck = {0.1, 0.0, 0.14};
        c.force = {5.0, 10.0, -100.0};
        c.far = {-0.25, 0.0, 0.0};
    }
    c.def.poisson = 0.3;
    return c;
}

double pulse(double t_mid, double tau)
{
    return t_mid < tau ? std::sin(std::numbers::pi * t_mid / tau) : 0.0;
}

/// Everything one (body, resolution) needs, built once: the basis, the full model and its response.
struct Setup {
    Case c;
    sm::ModalBasis basis;
    mo::RayleighDamping damping;
    std::unique_ptr<mo::FullModel> full;
    double h = 0.0, tau = 0.0;
    std::vector<sm::Vec3> full_struck, full_far;
};

const Setup& setup(int body, int resolution)
{
    static std::map<int, std::unique_ptr<Setup>> cache;
    auto& slot = cache[body * 2 + resolution];
    if (slot)
        return *slot;
    slot = std::make_unique<Setup>();
    Setup& s = *slot;
    s.c = make_case(body, resolution);
    auto basis = sm::build_modal_basis(s.c.def);
    if (!basis)
        std::abort();
    s.basis = std::move(*basis);
    const double w1 = 2 * std::numbers::pi * s.basis.frequencies_hz[0];
    const double w6 = 2 * std::numbers::pi * s.basis.frequencies_hz[5];
    s.damping = mo::fit_rayleigh(k_zeta, w1, w6);
    auto full = mo::FullModel::build(s.c.def, s.damping);
    if (!full)
        std::abort();
    s.full = std::move(*full);
    s.h = (2 * std::numbers::pi / w1) / k_division;
    s.tau = (2 * std::numbers::pi / w1) / 4;
    for (int i = 0; i < k_steps; ++i) {
        const double p = pulse((i + 0.5) * s.h, s.tau);
        const mo::PointLoad load{s.c.struck, {p * s.c.force.x, p * s.c.force.y, p * s.c.force.z}};
        if (!s.full->step(s.h, {&load, 1}).ok())
            std::abort();
        s.full_struck.push_back(s.full->displacement(s.c.struck));
        s.full_far.push_back(s.full->displacement(s.c.far));
    }
    s.full->reset();
    return s;
}

/// The modal path with r modes: generalized force through the weights at the struck point, one exact
/// step per mode, the displacement of one point.
struct ModalPath {
    const Setup& s;
    int r;
    sm::LatticeWeights at_load, at_probe;
    std::vector<mo::ModeStep> maps;
    std::vector<double> q, v;

    ModalPath(const Setup& setup_, int r_, const sm::Vec3& probe)
        : s(setup_), r(r_), at_load(sm::modal_weights(s.basis, s.c.struck)),
          at_probe(sm::modal_weights(s.basis, probe)), q(static_cast<size_t>(r), 0.0), v(q)
    {
        for (int k = 0; k < r; ++k) {
            const double w = 2 * std::numbers::pi * s.basis.frequencies_hz[k];
            maps.push_back(mo::exact_mode_step(w, mo::rayleigh_zeta(s.damping, w), s.h));
        }
    }
    sm::Vec3 step(double p)
    {
        const sm::Vec3 f{p * s.c.force.x, p * s.c.force.y, p * s.c.force.z};
        const size_t n = static_cast<size_t>(s.basis.mode_count);
        for (int k = 0; k < r; ++k) {
            double force = 0.0;
            for (int a = 0; a < at_load.count; ++a) {
                const double* phi = &s.basis.mode_shapes[static_cast<size_t>(at_load.nodes[a]) * 3 * n + k];
                force += at_load.weights[a] * (phi[0] * f.x + phi[n] * f.y + phi[2 * n] * f.z);
            }
            mo::apply_mode_step(maps[k], force, q[k], v[k]);
        }
        return sm::modal_displacement(s.basis, at_probe, std::span<const double>(q.data(), q.size()));
    }
};

// correction: the static correction per unit pulse at the probe (zero: the plain modal path).
double error_against(const Setup& s, int r, const sm::Vec3& probe, const std::vector<sm::Vec3>& full,
                     const sm::Vec3& correction = {})
{
    ModalPath path(s, r, probe);
    double diff = 0.0, peak = 0.0;
    for (int i = 0; i < k_steps; ++i) {
        const double p = pulse((i + 0.5) * s.h, s.tau);
        const sm::Vec3 m = path.step(p);
        const sm::Vec3 u{m.x + p * correction.x, m.y + p * correction.y, m.z + p * correction.z};
        const sm::Vec3 d{u.x - full[i].x, u.y - full[i].y, u.z - full[i].z};
        diff = std::max(diff, std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z));
        peak =
            std::max(peak, std::sqrt(full[i].x * full[i].x + full[i].y * full[i].y + full[i].z * full[i].z));
    }
    return diff / peak;
}

struct StaticPair {
    sm::Vec3 full, modal; // at the probe, for the struck load at full size
};

// The struck load held constant: u from K u = f_e on the full lattice, u_r = Σ_k≤r φ_k φ_kᵀ f / ω_k².
StaticPair static_pair(const Setup& s, int r, const sm::Vec3& probe)
{
    const mo::PointLoad load{s.c.struck, s.c.force};
    const std::vector<double> u = s.full->static_solution({&load, 1});
    ModalPath path(s, r, probe); // its weights and φᵀ f
    const sm::LatticeWeights w = sm::modal_weights(s.basis, probe);
    sm::Vec3 full{};
    for (int a = 0; a < w.count; ++a) {
        const size_t dof = static_cast<size_t>(w.nodes[a]) * 3;
        full = {full.x + w.weights[a] * u[dof], full.y + w.weights[a] * u[dof + 1],
                full.z + w.weights[a] * u[dof + 2]};
    }
    const size_t n = static_cast<size_t>(s.basis.mode_count);
    for (int k = 0; k < r; ++k) {
        double force = 0.0;
        for (int a = 0; a < path.at_load.count; ++a) {
            const double* phi = &s.basis.mode_shapes[static_cast<size_t>(path.at_load.nodes[a]) * 3 * n + k];
            force += path.at_load.weights[a] *
                     (phi[0] * s.c.force.x + phi[n] * s.c.force.y + phi[2 * n] * s.c.force.z);
        }
        const double w_k = 2 * std::numbers::pi * s.basis.frequencies_hz[k];
        path.q[static_cast<size_t>(k)] = force / (w_k * w_k);
    }
    return {full, sm::modal_displacement(s.basis, w, path.q)};
}

// Static truncation: |u_r − u| / |u| at probe: how many modes the load's shape itself needs.
double static_error(const Setup& s, int r, const sm::Vec3& probe)
{
    const StaticPair p = static_pair(s, r, probe);
    const sm::Vec3 d{p.modal.x - p.full.x, p.modal.y - p.full.y, p.modal.z - p.full.z};
    return std::sqrt((d.x * d.x + d.y * d.y + d.z * d.z) /
                     (p.full.x * p.full.x + p.full.y * p.full.y + p.full.z * p.full.z));
}

// One full-model step: nodal loads (rigid part removed), Newmark right-hand side, LDLᵀ solve.
void BM_FullModel_Step(benchmark::State& st)
{
    const Setup& s = setup(static_cast<int>(st.range(0)), static_cast<int>(st.range(1)));
    int i = 0;
    for (auto _ : st) {
        const double p = pulse((i++ % k_steps + 0.5) * s.h, s.tau);
        const mo::PointLoad load{s.c.struck, {p * s.c.force.x, p * s.c.force.y, p * s.c.force.z}};
        benchmark::DoNotOptimize(s.full->step(s.h, {&load, 1}).ok());
        benchmark::DoNotOptimize(s.full->displacement(s.c.far));
    }
    st.counters["dofs"] = s.full->dof_count();
    st.counters["factor_nnz"] = static_cast<double>(s.full->factor_nonzeros());
    st.counters["f1_hz"] = s.basis.frequencies_hz[0];
    st.counters["f6_hz"] = s.basis.frequencies_hz[5];
}
BENCHMARK(BM_FullModel_Step)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMicrosecond);

// One modal step with r modes, and its displacement error against the full model (counters, relative
// to the peak displacement over one fundamental period; at the struck point and at a far point).
void BM_Modal_Step(benchmark::State& st)
{
    const Setup& s = setup(static_cast<int>(st.range(0)), static_cast<int>(st.range(1)));
    const int r = static_cast<int>(st.range(2));
    ModalPath path(s, r, s.c.far);
    int i = 0;
    for (auto _ : st)
        benchmark::DoNotOptimize(path.step(pulse((i++ % k_steps + 0.5) * s.h, s.tau)));
    st.counters["err_struck"] = error_against(s, r, s.c.struck, s.full_struck);
    st.counters["err_far"] = error_against(s, r, s.c.far, s.full_far);
    st.counters["static_struck"] = static_error(s, r, s.c.struck);
    st.counters["static_far"] = static_error(s, r, s.c.far);
    // Mode acceleration: the same modes plus the static correction of the truncated ones.
    for (const auto& [name, probe, full] :
         {std::tuple{"ma_struck", s.c.struck, &s.full_struck}, std::tuple{"ma_far", s.c.far, &s.full_far}}) {
        const StaticPair p = static_pair(s, r, probe);
        st.counters[name] = error_against(s, r, probe, *full,
                                          {p.full.x - p.modal.x, p.full.y - p.modal.y, p.full.z - p.modal.z});
    }
}
BENCHMARK(BM_Modal_Step)->ArgsProduct({{0, 1}, {0, 1}, {1, 3, 6, 12, 24, 48}})->Unit(benchmark::kMicrosecond);

// The modal step with the static correction added at the probe (mode acceleration): its cost.
void BM_ModeAcceleration_Step(benchmark::State& st)
{
    const Setup& s = setup(static_cast<int>(st.range(0)), static_cast<int>(st.range(1)));
    const int r = static_cast<int>(st.range(2));
    const StaticPair sp = static_pair(s, r, s.c.far);
    const sm::Vec3 c{sp.full.x - sp.modal.x, sp.full.y - sp.modal.y, sp.full.z - sp.modal.z};
    ModalPath path(s, r, s.c.far);
    int i = 0;
    for (auto _ : st) {
        const double p = pulse((i++ % k_steps + 0.5) * s.h, s.tau);
        const sm::Vec3 m = path.step(p);
        benchmark::DoNotOptimize(sm::Vec3{m.x + p * c.x, m.y + p * c.y, m.z + p * c.z});
    }
}
BENCHMARK(BM_ModeAcceleration_Step)
    ->ArgsProduct({{0, 1}, {0, 1}, {1, 3, 6, 12, 24, 48}})
    ->Unit(benchmark::kMicrosecond);

} // namespace
