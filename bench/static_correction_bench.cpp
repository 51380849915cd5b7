// SPDX-License-Identifier: MIT
// Mode acceleration in the world (docs/modal.md "Static correction in the world"), on the soft ellipsoid
// of the modal trade (0.6 × 0.4 × 0.3 m, E 1 MPa, ν 0.3, ρ 1000 kg/m³, 6×4×3 lattice of 20-node cells):
//
// BM_StaticCorrection_Struck/r/corrected: a 100 N half-sine of T₁/4 at (0.1, 0, 0.14) m, h = T₁/200,
// two fundamental periods, no gravity. Error: max_t |u − u_ref| / max_t |u_ref| at the struck point, the
// reference being the same body with every elastic mode of its lattice ("dynamics": "full", the same
// integrator and damping: what is left is truncation). CPU per step of the r-mode body.
// BM_StaticCorrection_Resting/cells/corrected: the ellipsoid resting on a plane (1/60 s, 4 substeps, soft
// solver, kept awake): CPU per step and its stages, and the CPU to create the body (basis cached: the
// correction's factorisation of the full lattice is the difference).
#include "supermodal/body.h"
#include "supermodal/modal.h"
#include "supermodal/world.h"
#include "support/world_fixture.h"

#include <benchmark/benchmark.h>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <vector>

namespace sm = supermodal;

namespace
{

constexpr int k_steps = 400; // two fundamental periods at T₁/200
const sm::Vec3 k_struck{0.1, 0.0, 0.14}, k_force{5.0, 10.0, -100.0};

sm::BodyDef ellipsoid(int modes, bool correction, std::array<int, 3> cells = {6, 4, 3})
{
    return sm::test::soft_ellipsoid_def(modes, 0.02, correction, cells);
}

double seconds_since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

sm::Vec3 displacement(const sm::World& world, sm::Entity body, const sm::Vec3& rest)
{
    return sm::test::body_frame_displacement(world, body, rest);
}

struct Struck {
    std::unique_ptr<sm::World> world;
    sm::Entity body;
    double h = 0.0, tau = 0.0;
};

Struck make_struck(int modes, bool correction, double h, double tau,
                   const std::shared_ptr<sm::ModalBasisCache>& cache)
{
    sm::WorldDef wd = sm::default_world_def();
    wd.dt = h;
    wd.gravity = {};
    wd.modal_basis_cache = cache;
    Struck s{std::make_unique<sm::World>(wd), {}, h, tau};
    s.body = sm::create_body(*s.world, ellipsoid(modes, correction));
    return s;
}

// One step of the pulse: the load turns with the body.
void strike(Struck& s, int i)
{
    const double t = (i + 0.5) * s.h;
    const double p = t < s.tau ? std::sin(std::numbers::pi * t / s.tau) : 0.0;
    const sm::Quat turn = sm::body_orientation(*s.world, s.body);
    sm::apply_force(*s.world, s.body, sm::rotate(turn, p * k_force),
                    sm::body_position(*s.world, s.body) + sm::rotate(turn, k_struck));
    s.world->step();
}

struct Reference {
    std::shared_ptr<sm::ModalBasisCache> cache = std::make_shared<sm::ModalBasisCache>();
    double h = 0.0, tau = 0.0, peak = 0.0;
    std::vector<sm::Vec3> struck;
};

const Reference& reference()
{
    static const Reference ref = [] {
        Reference r;
        auto basis = sm::build_modal_basis([] {
            sm::ModalBasisDef d = sm::default_modal_basis_def();
            d.shape.radii = {0.3, 0.2, 0.15};
            d.young = 1e6;
            d.lattice.cells = {6, 4, 3};
            d.mode_count = 1;
            return d;
        }());
        const double period = 1.0 / basis->frequencies_hz[0];
        r.h = period / 200;
        r.tau = period / 4;
        Struck full = make_struck(sm::k_all_modes, false, r.h, r.tau, r.cache);
        for (int i = 0; i < k_steps; ++i) {
            strike(full, i);
            r.struck.push_back(displacement(*full.world, full.body, k_struck));
            r.peak = std::max(r.peak, std::sqrt(sm::dot(r.struck.back(), r.struck.back())));
        }
        return r;
    }();
    return ref;
}

void BM_StaticCorrection_Struck(benchmark::State& st)
{
    const int modes = static_cast<int>(st.range(0));
    const bool correction = st.range(1) != 0;
    const Reference& ref = reference();
    double error = 0.0, seconds = 0.0;
    for (auto _ : st) {
        st.PauseTiming();
        Struck s = make_struck(modes, correction, ref.h, ref.tau, ref.cache);
        st.ResumeTiming();
        error = 0.0;
        const auto t0 = std::chrono::steady_clock::now();
        for (int i = 0; i < k_steps; ++i) {
            strike(s, i);
            const sm::Vec3 d = displacement(*s.world, s.body, k_struck) - ref.struck[static_cast<size_t>(i)];
            error = std::max(error, std::sqrt(sm::dot(d, d)));
        }
        seconds += seconds_since(t0);
    }
    st.counters["error"] = error / ref.peak;
    st.counters["step_us"] = 1e6 * seconds / (static_cast<double>(st.iterations()) * k_steps);
}
BENCHMARK(BM_StaticCorrection_Struck)
    ->ArgsProduct({{6, 12, 24, 48, 96, 160, 256}, {0, 1}})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

void BM_StaticCorrection_Resting(benchmark::State& st)
{
    const std::array<int, 3> cells =
        st.range(0) == 0 ? std::array<int, 3>{6, 4, 3} : std::array<int, 3>{10, 7, 5};
    const bool correction = st.range(1) != 0;
    static const auto cache = std::make_shared<sm::ModalBasisCache>();
    sm::WorldDef wd = sm::default_world_def();
    wd.dt = 1.0 / 60.0;
    wd.substep_count = 4;
    wd.modal_basis_cache = cache;
    sm::World world(wd);
    (void)sm::test::add_ground(world);
    sm::destroy_body(world, sm::create_body(world, ellipsoid(12, false, cells))); // the basis, into the cache
    sm::BodyDef def = ellipsoid(12, correction, cells);
    def.position = {0.0, 0.16, 0.0};
    def.orientation = sm::Quat{0.7071068, 0.7071068, 0.0, 0.0};
    def.allow_sleep = false;
    const auto t0 = std::chrono::steady_clock::now();
    (void)sm::create_body(world, def);
    const double create_ms = 1e3 * seconds_since(t0);
    for (int i = 0; i < 120; ++i) // settle, 2 s
        world.step();
    double modal_ms = 0.0, surface_ms = 0.0;
    for (auto _ : st) {
        world.step();
        modal_ms += world.profile().stage_ms[static_cast<size_t>(sm::Stage::ModalUpdate)];
        surface_ms += world.profile().stage_ms[static_cast<size_t>(sm::Stage::UpdateSurfaces)];
    }
    const double n = static_cast<double>(st.iterations());
    st.counters["create_ms"] = create_ms;
    st.counters["modal_update_us"] = 1e3 * modal_ms / n;
    st.counters["update_surfaces_us"] = 1e3 * surface_ms / n;
}
BENCHMARK(BM_StaticCorrection_Resting)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMicrosecond);

} // namespace
