// SPDX-License-Identifier: MIT
// Pile: N bodies (density 1000 kg/m³) on a jittered grid (pitch 0.2 m, 10 layers) fall into an
// open box, dt = 1/240 s, 720 steps, μ = 0.5. Reported over the last 240 steps: ms per step (the
// benchmark's manual time, per step, and the process CPU time per step), the deepest penetration, the
// contacts at the end, the support-map evaluations per touching pair and substep (the candidate pairs'
// misses included), and the wall time per stage from the world's profile. free_cores_ms_per_step
// estimates the wall time on idle cores from thread CPU times: the serial CPU time plus, for each
// parallel loop, its busiest part (this machine is shared, so its wall times with two threads are not).
//
// The floor and the four walls are static half-spaces (planes) at the inner faces of the 0.1 m thick
// walls of the protocol: the same for everything inside the box, and nothing inside can tunnel
// through a half-space. rounded_box_stacked places the rounded boxes as a resting pile instead
// (columns of four, face on face): the narrowphase of a pile at rest. Arguments: N, threads,
// substeps per step. These runs keep every body awake (WorldDef::sleep off), so they measure the step
// itself.
//
// BM_PileSettled: the pile stepped k_settle_steps (10 s) with sleeping on or off, then timed over
// k_timed_steps: the cost of a pile at rest, awake against asleep. Arguments: N, sleep speed
// (SleepDef::linear_speed [mm/s]; 0: sleeping off).
#include "supermodal/body.h"
#include "supermodal/contact.h"
#include "supermodal/tasks.h"
#include "supermodal/world.h"

#include <benchmark/benchmark.h>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <memory>

namespace sm = supermodal;

namespace
{

constexpr double k_pitch = 0.2;      // grid pitch [m]
constexpr int k_layers = 10;         // grid layers [-]
constexpr double k_jitter = 0.02;    // ± jitter of each grid position [m], a tenth of the pitch
constexpr int k_steps = 720;         // whole run [-]
constexpr int k_timed_steps = 240;   // measured at the end [-]
constexpr int k_settle_steps = 2400; // BM_PileSettled: steps before the timed ones (10 s) [-]

// CPU time of the whole process [s]: on a shared machine the one-thread cost, unlike wall time, does
// not count the time other jobs held the core.
double process_cpu_seconds()
{
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The built-in pool seen through the host's side of the task interface, timing each part's thread CPU
// time: the sum over parts, and per loop its busiest part.
class TimedTasks final : public sm::TaskSystem
{
  public:
    explicit TimedTasks(int threads) : m_pool(sm::make_thread_pool(threads)), m_part_s(64, 0.0) {}
    [[nodiscard]] int concurrency() const override { return m_pool->concurrency(); }
    void run(int part_count, sm::TaskFn task, void* context) override
    {
        struct Timed {
            sm::TaskFn task;
            void* context;
            double* part_s;
        } timed{task, context, m_part_s.data()};
        m_pool->run(
            part_count,
            [](void* ctx, int part) {
                const auto& t = *static_cast<const Timed*>(ctx);
                const double start = thread_cpu_seconds();
                t.task(t.context, part);
                t.part_s[part] = thread_cpu_seconds() - start;
            },
            &timed);
        double busiest = 0.0;
        for (int p = 0; p < part_count; ++p) {
            parts_s += m_part_s[static_cast<size_t>(p)];
            busiest = std::max(busiest, m_part_s[static_cast<size_t>(p)]);
        }
        busiest_s += busiest;
    }
    double parts_s = 0.0, busiest_s = 0.0; ///< Thread CPU time of all parts, and of each loop's busiest [s].

  private:
    static double thread_cpu_seconds()
    {
        timespec t{};
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
        return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
    }
    std::shared_ptr<sm::TaskSystem> m_pool;
    std::vector<double> m_part_s;
};

// RoundedBoxStacked: the rounded boxes placed as a resting pile instead of dropped (stacked_pile).
enum class Shape { Sphere, Ellipsoid, RoundedBox, RoundedBoxStacked };

sm::ShapeDef pile_shape(Shape shape)
{
    sm::ShapeDef s = sm::default_shape_def();
    switch (shape) {
    case Shape::Sphere:
        s.radii = {0.05, 0.05, 0.05};
        break;
    case Shape::Ellipsoid:
        s.radii = {0.06, 0.04, 0.03};
        break;
    case Shape::RoundedBox:
    case Shape::RoundedBoxStacked:
        s.radii = {0.05, 0.05, 0.05};
        s.epsilon1 = s.epsilon2 = 0.3;
        break;
    }
    return s;
}

// A fixed LCG, so every run builds the same pile; uniform in [-1, 1).
struct Lcg {
    uint32_t state = 2026;
    double next()
    {
        state = state * 1664525u + 1013904223u;
        return static_cast<double>(state >> 8) / 8388608.0 - 1.0;
    }
};

void add_wall(sm::World& w, sm::Vec3 normal, double offset)
{
    sm::BodyDef d = sm::default_body_def();
    d.motion = sm::MotionType::Static;
    d.shape.type = sm::ShapeType::Plane;
    d.shape.plane_normal = normal;
    d.shape.plane_offset = offset;
    d.friction = 0.5;
    (void)sm::create_body(w, d);
}

constexpr int k_stacked_layers = 4;       // layers of the resting pile [-]
constexpr double k_stacked_pitch = 0.102; // its grid pitch: 2 mm between neighbouring columns [m]

// A resting pile: the rounded boxes in columns of k_stacked_layers, face on face, 0.1 mm apart, turned
// by up to ±0.01 rad and shifted by up to ±1 mm, in a box of planes 1 mm outside the outer columns.
void add_stacked_pile(sm::World& w, int n)
{
    const int per_layer = (n + k_stacked_layers - 1) / k_stacked_layers;
    const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(per_layer))));
    const double half = 0.5 * side * k_stacked_pitch;
    add_wall(w, {0, 1, 0}, 0.0);
    add_wall(w, {1, 0, 0}, -half);
    add_wall(w, {-1, 0, 0}, -half);
    add_wall(w, {0, 0, 1}, -half);
    add_wall(w, {0, 0, -1}, -half);
    Lcg rng;
    for (int i = 0; i < n; ++i) {
        const int layer = i / per_layer, cell = i % per_layer;
        sm::BodyDef d = sm::default_body_def();
        d.shape = pile_shape(Shape::RoundedBoxStacked);
        d.density = 1000.0;
        d.friction = 0.5;
        d.position = {-half + k_stacked_pitch * (cell % side + 0.5) + 1e-3 * rng.next(),
                      0.0501 + 0.1001 * layer,
                      -half + k_stacked_pitch * (cell / side + 0.5) + 1e-3 * rng.next()};
        d.orientation =
            sm::normalized(sm::Quat{1.0, 0.005 * rng.next(), 0.005 * rng.next(), 0.005 * rng.next()});
        (void)sm::create_body(w, d);
    }
}

sm::World make_pile(Shape shape, int n, const std::shared_ptr<TimedTasks>& tasks, int substeps,
                    double sleep_speed = 0.0, sm::ContactSolver solver = sm::ContactSolver::Penalty)
{
    sm::WorldDef def = sm::default_world_def();
    def.contact.solver = solver; // penalty: the solver of docs/bench/pile.csv
    def.sleep.enabled = sleep_speed > 0.0;
    def.sleep.linear_speed = sleep_speed;
    def.dt = 1.0 / 240.0;
    def.substep_count = substeps;
    def.task_system = tasks;
    sm::World w(def);
    if (shape == Shape::RoundedBoxStacked) {
        add_stacked_pile(w, n);
        return w;
    }
    const int per_layer = (n + k_layers - 1) / k_layers;
    const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(per_layer))));
    const double half = 0.5 * side * k_pitch; // inner half-width of the box [m]
    add_wall(w, {0, 1, 0}, 0.0);
    add_wall(w, {1, 0, 0}, -half);
    add_wall(w, {-1, 0, 0}, -half);
    add_wall(w, {0, 0, 1}, -half);
    add_wall(w, {0, 0, -1}, -half);
    Lcg rng;
    for (int i = 0; i < n; ++i) {
        const int layer = i / per_layer, cell = i % per_layer;
        sm::BodyDef d = sm::default_body_def();
        d.shape = pile_shape(shape);
        d.density = 1000.0;
        d.friction = 0.5;
        d.position = {-half + k_pitch * (cell % side + 0.5) + k_jitter * rng.next(),
                      k_pitch * (layer + 0.5) + k_jitter * rng.next(),
                      -half + k_pitch * (cell / side + 0.5) + k_jitter * rng.next()};
        // A random orientation: a normalised 4-vector of uniform components (enough spread for a pile).
        const sm::Quat q{rng.next(), rng.next(), rng.next(), rng.next()};
        const double len = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
        d.orientation = {q.w / len, q.x / len, q.y / len, q.z / len};
        (void)sm::create_body(w, d);
    }
    return w;
}

void BM_Pile(benchmark::State& st, Shape shape, sm::ContactSolver solver = sm::ContactSolver::Penalty)
{
    const int n = static_cast<int>(st.range(0));
    const int threads = static_cast<int>(st.range(1));
    const int substeps = static_cast<int>(st.range(2));
    double max_pen = 0.0, ms = 0.0, cpu_ms = 0.0, free_cores_ms = 0.0;
    size_t contacts = 0, pairs = 0;
    uint64_t support_calls = 0, touching_pairs = 0, touching_calls = 0;
    std::array<double, static_cast<size_t>(sm::Stage::Count)> stage_ms{};
    for (auto _ : st) {
        auto tasks = std::make_shared<TimedTasks>(threads);
        sm::World w = make_pile(shape, n, tasks, substeps, 0.0, solver);
        max_pen = 0.0;
        stage_ms.fill(0.0);
        support_calls = touching_pairs = touching_calls = 0;
        for (int i = 0; i < k_steps - k_timed_steps; ++i)
            w.step();
        const auto start = std::chrono::steady_clock::now();
        const double cpu_start = process_cpu_seconds();
        const double parts_start = tasks->parts_s, busiest_start = tasks->busiest_s;
        for (int i = 0; i < k_timed_steps; ++i) {
            w.step();
            max_pen = std::max(max_pen, sm::world_max_penetration(w));
            for (size_t s = 0; s < stage_ms.size(); ++s)
                stage_ms[s] += w.profile().stage_ms[s];
            support_calls += w.profile().support_calls;
            touching_pairs += w.profile().touching_pairs;
            touching_calls += w.profile().touching_support_calls;
        }
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        st.SetIterationTime(seconds);
        ms = 1e3 * seconds / k_timed_steps;
        cpu_ms = 1e3 * (process_cpu_seconds() - cpu_start) / k_timed_steps;
        // On free cores the loops take as long as their busiest part; everything else is serial.
        const double parts_ms = 1e3 * (tasks->parts_s - parts_start) / k_timed_steps;
        const double busiest_ms = 1e3 * (tasks->busiest_s - busiest_start) / k_timed_steps;
        free_cores_ms = cpu_ms - parts_ms + busiest_ms;
        contacts = sm::world_contacts(w).size();
        pairs = w.profile().pair_count;
    }
    st.SetItemsProcessed(st.iterations() * k_timed_steps * n); // body-steps
    st.counters["ms_per_step"] = ms;
    st.counters["cpu_ms_per_step"] = cpu_ms;
    st.counters["free_cores_ms_per_step"] = free_cores_ms;
    st.counters["max_penetration_mm"] = 1e3 * max_pen;
    st.counters["contacts"] = static_cast<double>(contacts);
    st.counters["pairs"] = static_cast<double>(pairs); // broadphase candidates
    // Support-map evaluations (one body each) per touching pair and substep, misses included.
    // The second counts only the touching pairs' own queries.
    const double touching = touching_pairs > 0 ? static_cast<double>(touching_pairs) : 1.0;
    st.counters["supports_per_touching_pair"] = static_cast<double>(support_calls) / touching;
    st.counters["touching_pairs_own_supports"] = static_cast<double>(touching_calls) / touching;
    for (size_t s = 0; s < stage_ms.size(); ++s) {
        const double per_step = stage_ms[s] / k_timed_steps;
        if (per_step > 0.0)
            st.counters["ms_" + std::string(sm::stage_name(static_cast<sm::Stage>(s)))] = per_step;
    }
}

// N, threads, substeps. Each run is one iteration: building and settling the pile is the protocol.
void pile_args(benchmark::internal::Benchmark* b)
{
    for (int threads : {1, 2})
        for (int n : {250, 1000, 4000})
            b->Args({n, threads, 1});
    b->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
}

// Penetration against cost: the penalty frequency is capped at a tenth of the substep rate, so k
struct TimedSteps {
    double seconds = 0.0; // wall time of the steps [s]
    double ms = 0.0;      // wall time per step [ms]
    double cpu_ms = 0.0;  // process CPU time per step [ms]
};

// Runs `steps` steps of w and times them.
TimedSteps time_steps(sm::World& w, int steps)
{
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = process_cpu_seconds();
    for (int i = 0; i < steps; ++i)
        w.step();
    TimedSteps t;
    t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    t.ms = 1e3 * t.seconds / steps;
    t.cpu_ms = 1e3 * (process_cpu_seconds() - cpu_start) / steps;
    return t;
}

// grows with the square of the substeps and the overlap under a load shrinks with it.
void substep_args(benchmark::internal::Benchmark* b)
{
    for (int n : {250, 1000})
        for (int substeps : {2, 3, 4})
            b->Args({n, 1, substeps});
    b->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
}

void BM_PileSettled(benchmark::State& st, Shape shape)
{
    const int n = static_cast<int>(st.range(0));
    const double sleep_speed = 1e-3 * static_cast<double>(st.range(1));
    double ms = 0.0, cpu_ms = 0.0, sleeping = 0.0, pairs = 0.0;
    for (auto _ : st) {
        sm::World w = make_pile(shape, n, std::make_shared<TimedTasks>(1), 1, sleep_speed);
        for (int i = 0; i < k_settle_steps; ++i)
            w.step();
        const TimedSteps t = time_steps(w, k_timed_steps);
        st.SetIterationTime(t.seconds);
        ms = t.ms;
        cpu_ms = t.cpu_ms;
        sleeping = static_cast<double>(sm::world_sleeping_count(w));
        pairs = static_cast<double>(w.profile().pair_count);
    }
    st.counters["ms_per_step"] = ms;
    st.counters["cpu_ms_per_step"] = cpu_ms;
    st.counters["sleeping"] = sleeping; // bodies asleep at the end
    st.counters["pairs"] = pairs;
}

// N rounded boxes (0.05 m) resting apart on the floor, one island each: 2 s to settle and sleep, then
// 240 steps timed. What a body at rest costs awake against asleep. Arguments: N, sleep (0/1).
void BM_RestingGrid(benchmark::State& st)
{
    const int n = static_cast<int>(st.range(0));
    double ms = 0.0, cpu_ms = 0.0, sleeping = 0.0;
    for (auto _ : st) {
        sm::WorldDef def = sm::default_world_def();
        def.contact.solver = sm::ContactSolver::Penalty; // as when it was measured (docs/sleeping.md)
        def.dt = 1.0 / 240.0;
        def.sleep.enabled = st.range(1) != 0;
        sm::World w(def);
        add_wall(w, {0, 1, 0}, 0.0);
        const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
        for (int i = 0; i < n; ++i) {
            sm::BodyDef d = sm::default_body_def();
            d.shape = pile_shape(Shape::RoundedBox);
            d.position = {0.15 * (i % side), 0.05, 0.15 * (i / side)};
            (void)sm::create_body(w, d);
        }
        for (int i = 0; i < 480; ++i)
            w.step();
        const TimedSteps t = time_steps(w, k_timed_steps);
        st.SetIterationTime(t.seconds);
        ms = t.ms;
        cpu_ms = t.cpu_ms;
        sleeping = static_cast<double>(sm::world_sleeping_count(w));
    }
    st.counters["ms_per_step"] = ms;
    st.counters["cpu_ms_per_step"] = cpu_ms;
    st.counters["sleeping"] = sleeping;
}

void settled_args(benchmark::internal::Benchmark* b)
{
    for (int speed_mm_s : {0, 50, 150})
        b->Args({1000, speed_mm_s});
    b->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
}

} // namespace

BENCHMARK_CAPTURE(BM_PileSettled, ellipsoid, Shape::Ellipsoid)->Apply(settled_args);
BENCHMARK(BM_RestingGrid)
    ->Args({1000, 0})
    ->Args({1000, 1})
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Pile, sphere, Shape::Sphere)->Apply(pile_args);
BENCHMARK_CAPTURE(BM_Pile, ellipsoid, Shape::Ellipsoid)->Apply(pile_args);
BENCHMARK_CAPTURE(BM_Pile, rounded_box, Shape::RoundedBox)->Apply(pile_args);
BENCHMARK_CAPTURE(BM_Pile, ellipsoid_substeps, Shape::Ellipsoid)->Apply(substep_args);
BENCHMARK_CAPTURE(BM_Pile, rounded_box_stacked, Shape::RoundedBoxStacked)->Apply(pile_args);
// The rounded boxes on the soft solver (the default; bench/peer_pile's soft rows), one thread.
BENCHMARK_CAPTURE(BM_Pile, rounded_box_soft, Shape::RoundedBox, sm::ContactSolver::Soft)
    ->Args({1000, 1, 1})
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
