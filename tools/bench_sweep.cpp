// SPDX-License-Identifier: MIT
#include "bench_sweep.h"

#include "supermodal/constraint.h"
#include "supermodal/geometry.h"
#include "supermodal/modal.h"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <limits>

namespace supermodal::cli
{
namespace
{

/// Process CPU time [ms]: other jobs on a shared machine slow it far less than they slow wall time.
double cpu_ms()
{
    timespec ts{};
    ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

std::string factor_label(double f)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "x%g", f);
    return buf;
}

BenchConfig config(const Scene& scene, std::string knob, std::string value)
{
    return {std::move(knob), std::move(value), scene};
}

void for_modal(Scene& s, const BenchBase& base, auto&& fn)
{
    for (size_t i = 0; i < base.modal_bodies.size(); ++i)
        fn(s.bodies[base.modal_indices[i]].def.modal, i);
}

bool finite(const Vec3& v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Every elastic mode of each modal body's lattice ("type": "full"), fixed, all the time.
void use_every_mode(Scene& s, const BenchBase& base)
{
    for (size_t i : base.modal_indices) {
        s.bodies[i].dynamics = DynamicsType::Full;
        s.bodies[i].def.modal.mode_count = k_all_modes;
        s.bodies[i].def.modal.adaptive_tolerance = 0.0;
    }
}

// Kinetic, potential and modal energy of the bodies [J].
double total_energy(const World& world, const std::vector<Entity>& bodies)
{
    double sum = 0.0;
    for (Entity e : bodies)
        sum += body_kinetic_energy(world, e) + body_potential_energy(world, e) + body_modal_energy(world, e);
    return sum;
}

std::vector<Vec3> centres_of_mass(const World& world, const std::vector<Entity>& bodies)
{
    std::vector<Vec3> p;
    p.reserve(bodies.size());
    for (Entity e : bodies)
        p.push_back(body_center_of_mass(world, e));
    return p;
}

// Centres of mass at the fixed sample times k·every, from the states at the ends of each step.
struct ComSampler {
    double every = 0.0;  ///< Sample spacing [s].
    long long count = 0; ///< Samples wanted over the run.
    std::vector<Vec3> previous;
    double previous_time = 0.0;

    // Samples that fall inside the step that ended at `now`: linear between its ends, so every dt sees
    // the same times.
    void add(double now, std::vector<Vec3> current, std::vector<std::vector<Vec3>>& com)
    {
        while (static_cast<long long>(com.size()) < count) {
            const double ts = static_cast<double>(com.size()) * every;
            if (ts > now + 1e-12 * every)
                break;
            const double alpha = now > previous_time
                                     ? std::clamp((ts - previous_time) / (now - previous_time), 0.0, 1.0)
                                     : 1.0;
            std::vector<Vec3> s(current.size());
            for (size_t b = 0; b < s.size(); ++b)
                s[b] = previous[b] + alpha * (current[b] - previous[b]);
            com.push_back(std::move(s));
        }
        previous = std::move(current);
        previous_time = now;
    }
};

void sweep_dt(const Scene& scene, const BenchBase&, std::vector<BenchConfig>& out)
{
    for (double f : {4.0, 2.0, 1.0, 0.5, 0.25}) {
        BenchConfig c = config(scene, "dt", factor_label(f));
        c.scene.world.dt = scene.world.dt * f;
        out.push_back(std::move(c));
    }
}

void sweep_substeps(const Scene& scene, const BenchBase&, std::vector<BenchConfig>& out)
{
    for (int n : {1, 2, 4}) {
        BenchConfig c = config(scene, "substeps", std::to_string(n));
        c.scene.world.substep_count = n;
        out.push_back(std::move(c));
    }
}

void sweep_modes(const Scene& scene, const BenchBase& base, std::vector<BenchConfig>& out)
{
    for (int r : {1, 2, 4, 8, 16}) {
        BenchConfig c = config(scene, "modes", std::to_string(r));
        for_modal(c.scene, base, [&](ModalBodyDef& m, size_t) { m.mode_count = r; });
        out.push_back(std::move(c));
    }
    // Every mode of the lattice: "full" (refused above 1536 dofs).
    BenchConfig c = config(scene, "modes", "full");
    use_every_mode(c.scene, base);
    out.push_back(std::move(c));
}

void sweep_lattice(const Scene& scene, const BenchBase& base, std::vector<BenchConfig>& out)
{
    for (double f : {0.5, 1.0, 1.5}) {
        BenchConfig c = config(scene, "lattice", factor_label(f));
        for_modal(c.scene, base, [&](ModalBodyDef& m, size_t i) {
            for (int a = 0; a < 3; ++a)
                m.lattice[a] = std::max(1, static_cast<int>(std::lround(base.modal_cells[i][a] * f)));
        });
        out.push_back(std::move(c));
    }
}

void sweep_spacing(const Scene& scene, const BenchBase& base, std::vector<BenchConfig>& out)
{
    if (!(base.spacing > 0.0))
        return;
    for (double f : {2.0, 1.0, 0.5}) {
        BenchConfig c = config(scene, "spacing", factor_label(f));
        c.scene.world.contact.sample_spacing = base.spacing * f;
        out.push_back(std::move(c));
    }
}

void sweep_path(const Scene& scene, const BenchBase&, std::vector<BenchConfig>& out)
{
    for (auto [path, name] :
         {std::pair{ContactPath::Auto, "auto"}, std::pair{ContactPath::Sampling, "sampling"},
          std::pair{ContactPath::SupportMap, "support_map"}}) {
        BenchConfig c = config(scene, "path", name);
        c.scene.world.contact.path = path;
        out.push_back(std::move(c));
    }
}

void sweep_integrator(const Scene& scene, const BenchBase& base, std::vector<BenchConfig>& out)
{
    for (const auto& [integrator, name] :
         {std::pair{ModalIntegrator::Exact, "exact"},
          std::pair{ModalIntegrator::CentralDifference, "central_difference"}}) {
        BenchConfig c = config(scene, "integrator", name);
        const ModalIntegrator chosen = integrator; // clang 14 cannot capture a structured binding
        for_modal(c.scene, base, [&](ModalBodyDef& m, size_t) { m.integrator = chosen; });
        out.push_back(std::move(c));
    }
}

void sweep_frequency(const Scene& scene, const BenchBase&, std::vector<BenchConfig>& out)
{
    for (double f : {0.25, 0.5, 1.0}) {
        BenchConfig c = config(scene, "frequency", factor_label(f) + "cap");
        const double h = scene.world.dt / scene.world.substep_count;
        c.scene.world.contact.frequency_hz = f / (10.0 * h);
        out.push_back(std::move(c));
    }
}

/// A knob of the sweep: its configurations, in the order they run; `modal` knobs need a modal body.
struct Knob {
    const char* name;
    bool modal;
    void (*sweep)(const Scene&, const BenchBase&, std::vector<BenchConfig>&);
};
constexpr Knob k_knobs[] = {
    {"dt", false, sweep_dt},
    {"substeps", false, sweep_substeps},
    {"modes", true, sweep_modes},
    {"lattice", true, sweep_lattice},
    {"spacing", false, sweep_spacing},
    {"path", false, sweep_path},
    {"integrator", true, sweep_integrator},
    {"frequency", false, sweep_frequency},
};

} // namespace

const std::vector<std::string>& bench_knobs()
{
    static const std::vector<std::string> names = [] {
        std::vector<std::string> out;
        for (const Knob& k : k_knobs)
            out.emplace_back(k.name);
        return out;
    }();
    return names;
}

std::string resolve_base(const Scene& scene, BenchBase& base)
{
    Result<World> world = build_world(scene);
    if (!world)
        return world.error().message();
    const std::vector<Entity> bodies = world_bodies(*world);
    double finest = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < scene.bodies.size() && i < bodies.size(); ++i) {
        const ShapeDef& shape = scene.bodies[i].def.shape;
        if (shape.type != ShapeType::Plane) {
            // The engine's per-body default: a quarter of the smallest half-extent of the shape's box.
            const Aabb box = world_aabb(shape, {}, Quat::identity());
            const Vec3 half = 0.5 * (box.max - box.min);
            finest = std::min(finest, 0.25 * std::min({half.x, half.y, half.z}));
        }
        if (!scene.bodies[i].def.modal.enabled)
            continue;
        const ModalBasis* basis = body_modal_basis(*world, bodies[i]);
        if (basis == nullptr)
            continue;
        base.modal_bodies.push_back(scene.bodies[i].def.name);
        base.modal_indices.push_back(i);
        base.modal_cells.push_back(basis->cells);
    }
    base.spacing = scene.world.contact.sample_spacing > 0.0 ? scene.world.contact.sample_spacing
                   : std::isfinite(finest)                  ? finest
                                                            : 0.0;
    return {};
}

Scene reference_scene(const Scene& scene, const BenchBase& base, ReferenceModes modes)
{
    Scene s = scene;
    s.world.dt = scene.world.dt / 8.0;
    s.world.contact.sample_spacing = 0.5 * base.spacing;
    if (modes == ReferenceModes::All)
        use_every_mode(s, base);
    for_modal(s, base, [&](ModalBodyDef& m, size_t) {
        if (modes == ReferenceModes::Doubled)
            m.mode_count = std::min(2 * m.mode_count, k_max_modes);
        m.integrator = ModalIntegrator::Exact;
    });
    return s;
}

std::vector<BenchConfig> make_sweep(const Scene& scene, const BenchBase& base,
                                    const std::vector<std::string>& knobs)
{
    std::vector<BenchConfig> out;
    const bool modal = !base.modal_bodies.empty();
    for (const Knob& k : k_knobs)
        if ((knobs.empty() || std::find(knobs.begin(), knobs.end(), k.name) != knobs.end()) &&
            (modal || !k.modal))
            k.sweep(scene, base, out);
    return out;
}

BenchTrace run_bench(const Scene& scene, const BenchBase& base, double seconds, double sample_every,
                     bool record)
{
    BenchTrace t;
    const double setup_start = cpu_ms();
    Result<World> built = build_world(scene);
    t.setup_ms = cpu_ms() - setup_start;
    if (!built) {
        t.refused = built.error().message();
        return t;
    }
    World& world = *built;
    const std::vector<Entity> all = world_bodies(world);
    std::vector<Entity> dynamic;
    for (Entity e : all)
        if (body_motion(world, e) == MotionType::Dynamic) {
            dynamic.push_back(e);
            t.body_names.push_back(body_name(world, e));
        }
    const double dt = scene.world.dt;
    t.steps = std::max(1LL, static_cast<long long>(std::ceil(seconds / dt - 1e-9)));
    ComSampler sampler;
    sampler.every = sample_every;
    sampler.count = static_cast<long long>(std::floor(seconds / sample_every + 1e-9)) + 1;
    const bool has_constraints = !world_constraints(world).empty();
    if (record) {
        t.energy_start = total_energy(world, dynamic);
        sampler.previous = centres_of_mass(world, dynamic);
        sampler.previous_time = world.time();
        t.com.push_back(sampler.previous);
    }
    double step_ms = 0.0;
    for (long long n = 0; n < t.steps; ++n) {
        const double c0 = cpu_ms();
        world.step();
        step_ms += cpu_ms() - c0;
        if (!record)
            continue;
        t.max_penetration = std::max(t.max_penetration, world_max_penetration(world));
        if (has_constraints)
            t.max_constraint_error = std::max(t.max_constraint_error, world_max_constraint_error(world));
        sampler.add(world.time(), centres_of_mass(world, dynamic), t.com);
    }
    t.cpu_ms_per_step = step_ms / static_cast<double>(t.steps);
    if (!record)
        return t;
    t.energy_end = total_energy(world, dynamic);
    t.non_finite = world.warnings().non_finite_bodies > 0 || world.warnings().modal_non_finite > 0 ||
                   !std::isfinite(t.energy_end);
    for (size_t index : base.modal_indices) {
        const ModalBasis* basis = index < all.size() ? body_modal_basis(world, all[index]) : nullptr;
        t.modal_frequencies_hz.push_back(basis ? basis->frequencies_hz : std::vector<double>{});
    }
    return t;
}

std::optional<double> energy_drift(const BenchTrace& trace)
{
    const double scale = std::abs(trace.energy_start);
    if (!(scale > 1e-12) || !std::isfinite(trace.energy_end))
        return std::nullopt;
    return (trace.energy_end - trace.energy_start) / scale;
}

BenchErrors compare_to_reference(const BenchTrace& run, const BenchTrace& reference)
{
    BenchErrors e;
    double sum = 0.0;
    long long count = 0;
    const size_t samples = std::min(run.com.size(), reference.com.size());
    for (size_t k = 0; k < samples; ++k) {
        const size_t bodies = std::min(run.com[k].size(), reference.com[k].size());
        for (size_t b = 0; b < bodies; ++b) {
            if (!finite(run.com[k][b]) || !finite(reference.com[k][b]))
                continue; // a frozen body is flagged by non_finite; its error is not a number
            const double d = length(run.com[k][b] - reference.com[k][b]);
            sum += d * d;
            e.trajectory_max = std::max(e.trajectory_max, d);
            ++count;
        }
    }
    e.trajectory_rms = count > 0 ? std::sqrt(sum / static_cast<double>(count)) : 0.0;
    e.energy_drift = energy_drift(run);
    const size_t modal = std::min(run.modal_frequencies_hz.size(), reference.modal_frequencies_hz.size());
    for (size_t i = 0; i < modal; ++i) {
        const std::vector<double>& f = run.modal_frequencies_hz[i];
        const std::vector<double>& fr = reference.modal_frequencies_hz[i];
        for (size_t k = 0; k < std::min(f.size(), fr.size()); ++k)
            if (fr[k] > 0.0)
                e.frequency_error = std::max(e.frequency_error.value_or(0.0), std::abs(f[k] - fr[k]) / fr[k]);
    }
    return e;
}

} // namespace supermodal::cli
