// SPDX-License-Identifier: MIT
#include "stability/stability_cells.h"

#include "supermodal/body.h"
#include "supermodal/contact.h"
#include "supermodal/geometry.h"
#include "supermodal/modal.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <vector>

namespace supermodal::stability
{
namespace
{

constexpr double k_g = 9.81;
constexpr double k_stack_frequency_hz = 50.0; // Stack: fixed penalty frequency; its limit is 1/(10 f)
constexpr double k_impact_dt = 0.002;         // Drop and Impact: the default step [s]
constexpr double k_max_settle_seconds = 30.0; // Stack: longest settling of the bottom body [s]

struct Scratch {
    World world;
    std::vector<Entity> bodies;
    double e_ref = 0.0; // energy the scene can dissipate [J]
    double min_radius = 0.0;
};

double smallest_radius(const ShapeDef& s)
{
    return std::min({s.radii.x, s.radii.y, s.radii.z});
}

// Lowest height of the centre over a plane the shape can rest at [m]: min over directions of the
// support function (that of the convex hull for ε > 2), over 2000 Fibonacci directions plus the axes.
double lowest_rest_height(const ShapeDef& s)
{
    double best = smallest_radius(s);
    const int n = 2000;
    for (int i = 0; i < n; ++i) {
        const double z = 1.0 - (2.0 * i + 1.0) / n;
        const double rho = std::sqrt(std::max(0.0, 1.0 - z * z));
        const double phi = i * std::numbers::pi * (3.0 - std::sqrt(5.0));
        const Vec3 d{rho * std::cos(phi), rho * std::sin(phi), z};
        best = std::min(best, dot(d, support_point(s, d)));
    }
    return best;
}

BodyDef plane_def()
{
    BodyDef d = default_body_def();
    d.motion = MotionType::Static;
    d.shape.type = ShapeType::Plane;
    return d;
}

// 2/ω_max of central difference for a modal def, per epsilon (a probe world builds the basis once).
double modal_limit_dt(const BodyDef& def)
{
    static std::map<double, double> cache;
    const auto it = cache.find(def.shape.epsilon1);
    if (it != cache.end())
        return it->second;
    World probe;
    const auto basis = modal_basis_for(probe, def);
    double limit = 0.0;
    if (basis.has_value() && !(*basis)->frequencies_hz.empty())
        limit = 2.0 / (2.0 * std::numbers::pi * (*basis)->frequencies_hz.back());
    cache[def.shape.epsilon1] = limit;
    return limit;
}

// Modal energy as the integrator conserves it [J]. Central difference keeps q̇ = v_{n+½} half a step
// behind q = q_{n+1}; what it conserves in free vibration is ½(v_{n+½}² + ω²·q_n·q_{n+1}) =
// ½(v² + ω²q² − h·ω²·v·q), not body_modal_energy's ½(v² + ω²q²), which swings about it by ±ω·h/2
// (measured ±12% of the modal energy of a soft sphere at ω_max·h = 0.2). Modes with ω·h ≥ 2 are stepped
// exactly (the guard) and keep ½(v² + ω²q²). The bodies here are elastic (no plastic offsets).
double modal_energy(const World& w, Entity b, bool central_difference, double h)
{
    const ModalBasis* basis = body_modal_basis(w, b);
    if (basis == nullptr)
        return 0.0;
    double e = body_modal_energy(w, b);
    if (!central_difference)
        return e;
    const BodyModalState st = body_modal_state(w, b);
    for (size_t k = 0; k < st.amplitudes.size(); ++k) {
        const double omega = 2.0 * std::numbers::pi * basis->frequencies_hz[k];
        if (omega * h < 2.0)
            e -= 0.5 * h * omega * omega * st.velocities[k] * st.amplitudes[k];
    }
    return e;
}

double total_energy(const World& w, const std::vector<Entity>& bodies, bool central_difference, double h)
{
    double e = 0.0;
    for (const Entity b : bodies)
        e += body_kinetic_energy(w, b) + body_potential_energy(w, b) +
             modal_energy(w, b, central_difference, h);
    return e;
}

bool bodies_finite(const World& w, const std::vector<Entity>& bodies)
{
    for (const Entity b : bodies)
        if (!is_finite(body_position(w, b)) || !is_finite(body_linear_velocity(w, b)) ||
            !is_finite(body_angular_velocity(w, b)) || !is_finite(body_orientation(w, b)))
            return false;
    return true;
}

bool refuse(CellResult& out, const Status& s)
{
    if (s.ok())
        return false;
    out.accepted = false;
    out.refusal = s.error().message();
    return true;
}

Entity make_body(World& w, const BodyDef& d, CellResult& out)
{
    if (refuse(out, validate(d)))
        return {};
    const Entity e = create_body(w, d);
    if (!world_valid(w, e)) {
        out.accepted = false;
        out.refusal = "create_body refused the def";
    }
    return e;
}

} // namespace

const char* scene_name(Scene scene)
{
    switch (scene) {
    case Scene::Drop:
        return "drop";
    case Scene::Stack:
        return "stack";
    case Scene::Impact:
        return "impact";
    case Scene::ModalDrop:
        return "modal_drop";
    }
    return "?";
}

CellResult run_cell(const CellDef& def)
{
    const auto start = std::chrono::steady_clock::now();
    CellResult out;
    out.accepted = true;
    WorldDef wd = default_world_def();
    wd.contact.solver = def.solver;
    // The map measures the step's energy balance: a body put to sleep mid-ring (zero velocity, a
    // spring not at rest) reads as a gain once woken.
    wd.sleep.enabled = false;
    BodyDef body = default_body_def();
    body.restitution = def.restitution;
    double settle_seconds = 0.0;

    switch (def.scene) {
    case Scene::Drop:
        wd.dt = k_impact_dt;
        body.shape.radii = {0.2, 0.2, 0.2 / def.aspect};
        body.shape.epsilon1 = body.shape.epsilon2 = def.epsilon;
        // Thin axis (shape z) up, then tilted so that the rim or a corner lands first.
        body.orientation = quat_from_rotation_vector({0.3, 0.0, 0.2}) *
                           quat_from_rotation_vector({-0.5 * std::numbers::pi, 0.0, 0.0});
        break;
    case Scene::Stack:
        out.limit_dt = 1.0 / (10.0 * k_stack_frequency_hz);
        wd.dt = def.dt_ratio * out.limit_dt;
        wd.contact.frequency_hz = k_stack_frequency_hz;
        body.shape.radii = {0.1, 0.1, 0.1};
        body.shape.epsilon1 = body.shape.epsilon2 = 0.5;
        body.position = {0.0, 0.1, 0.0};
        settle_seconds = 1.0;
        break;
    case Scene::Impact:
        wd.dt = k_impact_dt;
        wd.contact.frequency_hz = def.frequency_hz;
        wd.contact.soft.frequency_hz = def.frequency_hz;
        body.shape.radii = {0.1, 0.1, 0.1};
        body.position = {0.0, 0.15, 0.0};
        body.linear_velocity = {0.0, -def.speed, 0.0};
        break;
    case Scene::ModalDrop:
        body.shape.radii = {0.1, 0.1, 0.1};
        body.shape.epsilon1 = body.shape.epsilon2 = def.epsilon;
        body.modal.enabled = true;
        body.modal.mode_count = 8;
        body.modal.integrator = def.exact_modal ? ModalIntegrator::Exact : ModalIntegrator::CentralDifference;
        body.modal.static_correction = def.static_correction;
        body.young = 2e6;
        if (refuse(out, validate(body)))
            return out;
        out.limit_dt = modal_limit_dt(body);
        if (!(out.limit_dt > 0.0)) {
            out.accepted = false;
            out.refusal = "modal basis build failed";
            return out;
        }
        wd.dt = def.dt_ratio * out.limit_dt;
        break;
    }
    out.dt = wd.dt;
    if (refuse(out, validate(wd)))
        return out;
    if (def.scene == Scene::Drop || def.scene == Scene::ModalDrop) { // lowest point 0.1 / 0.05 m up
        const double gap = def.scene == Scene::Drop ? 0.1 : 0.05;
        body.position = {0.0, gap - world_aabb(body.shape, {}, body.orientation).min.y, 0.0};
    }

    Scratch s{World(wd), {}, 0.0, smallest_radius(body.shape)};
    (void)make_body(s.world, plane_def(), out);
    const Entity first = make_body(s.world, body, out);
    if (!out.accepted)
        return out;
    s.bodies.push_back(first);
    const double mass = body_mass_properties(s.world, first).mass;
    if (def.scene == Scene::Stack) {
        // Settle the bottom body until its oscillation on the plane holds under 1e-3 of the top body's
        // E_ref (the largest kinetic energy over the last 0.25 s, more than one period at the slowest,
        // clamped 5 Hz, spring) and its energy no longer moves by more than that over the window (a soft
        // contact pushes a body out of its landing overlap at a speed that reads as no kinetic energy):
        // else its leftover ringing or rise reads as a gain of the light top body.
        BodyDef top = body;
        top.density = 1000.0 * def.mass_ratio;
        const double drop = 0.05;
        const double top_e_ref = compute_mass_properties(top.shape, top.density).mass * k_g * drop;
        std::vector<double> ke, energy;
        const size_t window = static_cast<size_t>(std::ceil(0.25 / wd.dt));
        const std::vector<Entity> bottom{first};
        auto settled = [&] {
            if (s.world.time() < settle_seconds || ke.size() < window)
                return false;
            const auto from = static_cast<std::ptrdiff_t>(ke.size() - window);
            const auto [lo, hi] = std::minmax_element(energy.begin() + from, energy.end());
            return *std::max_element(ke.begin() + from, ke.end()) <= 1e-3 * top_e_ref &&
                   *hi - *lo <= 1e-3 * top_e_ref;
        };
        while (s.world.time() < k_max_settle_seconds) {
            s.world.step();
            ke.push_back(body_kinetic_energy(s.world, first));
            energy.push_back(total_energy(s.world, bottom, false, wd.dt));
            if (settled())
                break;
        }
        top.position = {0.0, body_position(s.world, first).y + 0.2 + drop, 0.0};
        const Entity e = make_body(s.world, top, out);
        if (!out.accepted)
            return out;
        s.bodies.push_back(e);
        s.e_ref = body_mass_properties(s.world, e).mass * k_g * drop;
    } else {
        const double rest = lowest_rest_height(body.shape);
        s.e_ref = mass * k_g * (body.position.y - rest) + 0.5 * mass * def.speed * def.speed;
    }

    // The modal drop runs one substep per step (its map shows no speculative substeps), so h = dt.
    const bool cd = def.scene == Scene::ModalDrop && !def.exact_modal;
    const double h = wd.dt;
    const double e0 = total_energy(s.world, s.bodies, cd, h);
    const double ninf = -std::numeric_limits<double>::infinity();
    out.gain_all = ninf;
    out.gain_free = ninf;
    double pending = ninf; // energy of the last contact-free step, counted once the next is free too
    const double t_end = s.world.time() + def.seconds;
    while (s.world.time() < t_end - 0.5 * wd.dt) {
        s.world.step();
        const double e = total_energy(s.world, s.bodies, cd, h);
        if (!std::isfinite(e) || !bodies_finite(s.world, s.bodies)) {
            out.non_finite = true;
            break;
        }
        const double gain = (e - e0) / s.e_ref;
        out.gain_all = std::max(out.gain_all, gain);
        const bool free = world_contacts(s.world).empty() && world_contact_events(s.world).empty();
        if (free && pending > ninf) {
            out.gain_free = std::max(out.gain_free, pending);
            ++out.free_steps;
        }
        pending = free ? gain : ninf;
        // The deepest penetration of any substep: the events carry it, the last substep's contacts may not.
        double pen = world_max_penetration(s.world);
        for (const ContactEvent& ev : world_contact_events(s.world))
            pen = std::max(pen, ev.depth);
        if (def.trace != nullptr)
            std::fprintf(def.trace, "%.6f,%.9g,%.9g,%zu,%.6g\n", s.world.time(), gain,
                         modal_energy(s.world, s.bodies.back(), cd, h) / s.e_ref,
                         world_contacts(s.world).size(), pen);
        if (std::isfinite(pen))
            out.max_penetration = std::max(out.max_penetration, pen);
        else
            out.non_finite = true;
    }
    out.max_penetration_rel = out.max_penetration / s.min_radius;
    out.warnings = s.world.warnings();
    if (out.warnings.non_finite_bodies > 0 || out.warnings.modal_non_finite > 0)
        out.non_finite = true;
    out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

std::string csv_header()
{
    return "slice,scene,epsilon,aspect,mass_ratio,dt_ratio,dt,limit_dt,frequency_hz,speed,accepted,"
           "non_finite,gain_all,gain_free,free_steps,max_penetration,max_penetration_rel,"
           "contact_frequency_clamps,speculative_substeps,modal_integrator_switches,gyroscopic_fallbacks,"
           "non_finite_bodies,modal_non_finite,guard,wall_s,refusal";
}

std::string csv_row(const std::string& slice, const CellDef& d, const CellResult& r)
{
    char buf[1024];
    const StepWarnings& w = r.warnings;
    std::snprintf(buf, sizeof buf,
                  "%s,%s,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%d,%.6g,%.6g,%d,%.6g,%.6g,%llu,%llu,%llu,"
                  "%llu,%llu,%llu,%d,%.4f,",
                  slice.c_str(), scene_name(d.scene), d.epsilon, d.aspect, d.mass_ratio, d.dt_ratio, r.dt,
                  r.limit_dt, d.frequency_hz, d.speed, r.accepted ? 1 : 0, r.non_finite ? 1 : 0, r.gain_all,
                  r.gain_free, r.free_steps, r.max_penetration, r.max_penetration_rel,
                  static_cast<unsigned long long>(w.contact_frequency_clamps),
                  static_cast<unsigned long long>(w.speculative_substeps),
                  static_cast<unsigned long long>(w.modal_integrator_switches),
                  static_cast<unsigned long long>(w.gyroscopic_fallbacks),
                  static_cast<unsigned long long>(w.non_finite_bodies),
                  static_cast<unsigned long long>(w.modal_non_finite), r.guard() ? 1 : 0, r.wall_seconds);
    std::string row = buf;
    for (const char c : r.refusal) // keep the row one CSV field: no commas or newlines
        row += (c == ',' || c == '\n') ? ';' : c;
    return row;
}

} // namespace supermodal::stability
