// SPDX-License-Identifier: MIT
#include "world/modal_system.h"

#include "core/assert.h"
#include "modal/accuracy.h"
#include "modal/adaptive.h"
#include "modal/stress.h"
#include "world/integrate.h"
#include "world/world_impl.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace supermodal
{
namespace
{

// Per rest sample, the body-frame displacement of each unit amplitude: D_s = Σ_nodes w_n φ_n (3 × r),
// so deforming a sample costs 3r multiply-adds instead of 3·20·r.
std::shared_ptr<const ModalSurface> make_surface(std::shared_ptr<const Collider> rest,
                                                 std::shared_ptr<const ModalBasis> basis)
{
    auto surface = std::make_shared<ModalSurface>();
    const size_t r = static_cast<size_t>(basis->mode_count);
    const std::vector<SurfaceSample>& samples = rest->samples->samples;
    surface->sample_modes.assign(samples.size() * 3 * r, 0.0);
    for (size_t i = 0; i < samples.size(); ++i) {
        const LatticeWeights lw = modal_weights(*basis, samples[i].point + rest->com_shape);
        double* d = &surface->sample_modes[i * 3 * r];
        for (int j = 0; j < lw.count; ++j) {
            const double* phi = &basis->mode_shapes[static_cast<size_t>(lw.nodes[j]) * 3 * r];
            for (size_t a = 0; a < 3 * r; ++a)
                d[a] += lw.weights[j] * phi[a];
        }
    }
    surface->mode_reach.assign(r, 0.0);
    for (size_t i = 0; i < samples.size(); ++i) {
        const double* d = &surface->sample_modes[i * 3 * r];
        for (size_t k = 0; k < r; ++k)
            surface->mode_reach[k] =
                std::max(surface->mode_reach[k],
                         std::sqrt(d[k] * d[k] + d[r + k] * d[r + k] + d[2 * r + k] * d[2 * r + k]));
    }
    surface->stress =
        std::make_shared<const modal::StressModel>(modal::build_stress_model(*basis, rest->shape));
    surface->accuracy = std::make_shared<modal::AccuracyCache>();
    ModalBasisDef& def = surface->accuracy->def; // what modal_basis_def() gave the basis, from the basis
    def.shape = rest->shape;
    def.density = basis->density;
    def.young = basis->young;
    def.poisson = basis->poisson;
    def.lattice.cells = basis->cells;
    def.lattice.element_order = basis->element_order;
    def.mode_count = basis->mode_count;
    surface->rest = std::move(rest);
    surface->basis = std::move(basis);
    return surface;
}

std::shared_ptr<const ModalSurface> surface_for(World::Impl& w, const std::shared_ptr<const Collider>& rest,
                                                const std::shared_ptr<const ModalBasis>& basis)
{
    for (const auto& s : w.modal_surfaces)
        if (s->rest == rest && s->basis == basis)
            return s;
    w.modal_surfaces.push_back(make_surface(rest, basis));
    return w.modal_surfaces.back();
}

// Q_k += φ_k(x_local) · Rᵀ f: the lattice field at the point, projected on the body-frame force.
void add_load(const ModalBody& b, const BodyModel& m, const Pose& p, const Vec3& x, const Vec3& f,
              std::vector<double>& io_q)
{
    const Vec3 local = inv_rotate(p.orientation, x - p.position) + m.mass.center_of_mass;
    const Vec3 fl = inv_rotate(p.orientation, f);
    if (!is_finite(local) || !is_finite(fl))
        return;
    const ModalBasis& basis = *b.basis;
    const size_t r = static_cast<size_t>(basis.mode_count);
    const LatticeWeights lw = modal_weights(basis, local);
    for (int j = 0; j < lw.count; ++j) {
        const double* phi = &basis.mode_shapes[static_cast<size_t>(lw.nodes[j]) * 3 * r];
        const double wx = lw.weights[j] * fl.x, wy = lw.weights[j] * fl.y, wz = lw.weights[j] * fl.z;
        for (size_t k = 0; k < r; ++k)
            io_q[k] += wx * phi[k] + wy * phi[r + k] + wz * phi[2 * r + k];
    }
}

// f [N] at world point x lumped on the lattice nodes of x's cell, body frame: F_node += w_node Rᵀf.
bool lump_load(const ModalBody& b, const BodyModel& m, const Pose& p, const Vec3& x, const Vec3& f,
               std::vector<double>& io_nodal)
{
    const Vec3 local = inv_rotate(p.orientation, x - p.position) + m.mass.center_of_mass;
    const Vec3 fl = inv_rotate(p.orientation, f);
    if (!is_finite(local) || !is_finite(fl))
        return false;
    const LatticeWeights lw = modal_weights(*b.basis, local);
    for (int j = 0; j < lw.count; ++j) {
        double* out = &io_nodal[static_cast<size_t>(lw.nodes[j]) * 3];
        out[0] += lw.weights[j] * fl.x;
        out[1] += lw.weights[j] * fl.y;
        out[2] += lw.weights[j] * fl.z;
    }
    return lw.count > 0;
}

bool all_finite(const std::vector<double>& v)
{
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

} // namespace

ModalBasisDef modal_basis_def(const BodyDef& def)
{
    ModalBasisDef out = default_modal_basis_def();
    out.shape = def.shape;
    out.density = def.density;
    out.young = def.young;
    out.poisson = def.poisson;
    out.lattice.cells = def.modal.lattice;
    out.mode_count = def.modal.mode_count;
    return out;
}

Result<modal::LatticeChoice> find_or_build_modal_basis(World::Impl& w, const BodyDef& def)
{
    const ModalBasisDef basis_def = modal_basis_def(def);
    if (def.modal.adaptive_tolerance > 0.0 && basis_def.lattice.cells == std::array<int, 3>{})
        return modal::choose_lattice(*w.modal_bases, basis_def);
    Result<std::shared_ptr<const ModalBasis>> built = w.modal_bases->get_or_build(basis_def);
    if (!built)
        return built.error();
    modal::LatticeChoice choice;
    choice.basis = *built;
    return choice;
}

void attach_modal_body(World::Impl& w, Entity e, const modal::LatticeChoice& choice, const BodyDef& def)
{
    std::shared_ptr<const ModalBasis> basis = choice.basis;
    BodyModel& m = w.reg.get<BodyModel>(e);
    ModalBody b;
    const size_t r = static_cast<size_t>(basis->mode_count);
    b.omega.resize(r);
    for (size_t k = 0; k < r; ++k)
        b.omega[k] = 2.0 * std::numbers::pi * basis->frequencies_hz[k];
    b.damping_ratio = def.modal.damping_ratio;
    b.integrator = def.modal.integrator;
    b.q.assign(r, 0.0);
    b.q_dot.assign(r, 0.0);
    b.host_force.assign(r, 0.0);
    b.load.assign(r, 0.0);
    b.nodal_load.assign(basis->node_positions.size() * 3, 0.0);
    b.host_nodal_load.assign(b.nodal_load.size(), 0.0);
    b.last_nodal_load.assign(b.nodal_load.size(), 0.0);
    b.last_load.assign(r, 0.0);
    b.q_plastic.assign(r, 0.0);
    b.plastic.yield_stress = def.modal.yield_stress;
    b.plastic.hardening = def.modal.hardening;
    b.plastic.max_plastic_strain = def.modal.max_plastic_strain;
    b.surface = surface_for(w, m.collider, basis);
    b.basis = std::move(basis);
    // Its own collider and samples: the deformed surface belongs to this body alone. The rest shape's
    // support point would ignore the deformation, so the body counts as non-convex (samples only).
    b.samples = std::make_shared<SampleSet>(*m.collider->samples);
    b.collider = std::make_shared<Collider>(*m.collider);
    b.collider->samples = b.samples;
    b.collider->convex = false;
    b.adaptive_tolerance = def.modal.adaptive_tolerance;
    b.lattice_changes = choice.frequency_changes;
    b.active = b.adaptive_tolerance > 0.0 ? 0 : r; // adaptive bodies start rigid
    b.most_active = b.active;
    // Adaptive bodies too: swapping to the rest collider (support-map contact) while rigid changed the
    // strike itself: the 2x4 board of ball_on_board bent 18% less when its contact path switched as
    // the ball struck (measured against the all-modes board, docs/modal.md "Adaptive modes").
    m.collider = b.collider;
    w.reg.emplace(e, std::move(b));
}

void set_active_modes(ModalBody& b, size_t active)
{
    if (active != b.active)
        ++b.active_changes;
    b.active = std::min(active, b.q.size());
    b.most_active = std::max(b.most_active, b.active);
    b.surface_stale = true;
}

void modal_add_point_load(Registry& reg, Entity e, const Vec3& world_point, const Vec3& world_force)
{
    // Lumped on the lattice nodes (3·count multiply-adds) rather than projected on the modes
    // (3·count·r): a resting body has hundreds of contact points per substep.
    ModalBody* b = reg.find<ModalBody>(e);
    if (b == nullptr)
        return;
    if (lump_load(*b, reg.get<BodyModel>(e), reg.get<Pose>(e), world_point, world_force, b->nodal_load))
        b->has_nodal_load = true;
}

void modal_add_host_load(Registry& reg, Entity e, const Vec3& world_point, const Vec3& world_force)
{
    if (ModalBody* b = reg.find<ModalBody>(e)) {
        add_load(*b, reg.get<BodyModel>(e), reg.get<Pose>(e), world_point, world_force, b->host_force);
        // Also lumped, for the accuracy report's F (the projection above keeps the exact point's field).
        if (lump_load(*b, reg.get<BodyModel>(e), reg.get<Pose>(e), world_point, world_force,
                      b->host_nodal_load))
            b->has_host_nodal_load = true;
    }
}

void prepare_modal_contact(Registry& reg, double h)
{
    reg.each<ModalBody>([&](Entity, ModalBody& b) {
        if (b.contact_h == h)
            return;
        b.contact_sinc.resize(b.omega.size());
        for (size_t k = 0; k < b.omega.size(); ++k)
            b.contact_sinc[k] = modal::half_step_sinc(b.omega[k], h);
        b.contact_h = h;
    });
}

double modal_inverse_mass(const Registry& reg, Entity e, const Vec3& world_point, const Vec3& d,
                          std::vector<double>& scratch_phi)
{
    const ModalBody* b = reg.find<ModalBody>(e);
    if (b == nullptr)
        return 0.0;
    const Pose& p = reg.get<Pose>(e);
    const Vec3 local =
        inv_rotate(p.orientation, world_point - p.position) + reg.get<BodyModel>(e).mass.center_of_mass;
    const Vec3 dl = inv_rotate(p.orientation, d);
    if (!is_finite(local) || !is_finite(dl))
        return 0.0;
    const ModalBasis& basis = *b->basis;
    const size_t r = static_cast<size_t>(basis.mode_count);
    const LatticeWeights lw = modal_weights(basis, local);
    SM_ASSERT(b->contact_sinc.size() == r, "prepare_modal_contact() runs before the contact forces");
    // φ_k at the point for every k, nodes outer (rows of mode_shapes are contiguous): per k the same sum
    // in the same order as node by node.
    std::vector<double>& phi = scratch_phi; // per thread: a full body has more than k_max_modes
    phi.assign(3 * r, 0.0);
    for (int j = 0; j < lw.count; ++j) {
        const double* node = &basis.mode_shapes[static_cast<size_t>(lw.nodes[j]) * 3 * r];
        const double w = lw.weights[j];
        for (size_t a = 0; a < 3 * r; ++a)
            phi[a] += w * node[a];
    }
    double sum = 0.0;
    // Every mode, active or not: the contact spring is tuned as for the fully modal body, so an adaptive
    // body's contact forces do not change with its active count (only what the modes do with them).
    for (size_t k = 0; k < r; ++k) {
        const Vec3 phi_k{phi[k], phi[r + k], phi[2 * r + k]};
        const double sinc = b->contact_sinc[k];
        sum += (d == Vec3{} ? dot(phi_k, phi_k) : dot(phi_k, dl) * dot(phi_k, dl)) * sinc * sinc;
    }
    return sum;
}

void modal_add_point_impulse(Registry& reg, Entity e, const Vec3& world_point, const Vec3& impulse)
{
    if (ModalBody* b = reg.find<ModalBody>(e))
        add_load(*b, reg.get<BodyModel>(e), reg.get<Pose>(e), world_point, impulse, b->q_dot);
}

namespace
{

constexpr uint8_t k_switched = 1;   // central difference was unstable for some modes, stepped exactly
constexpr uint8_t k_non_finite = 2; // amplitudes turned NaN/Inf: reset to rest

// One modal body's amplitudes over h [s] under this substep's loads; returns k_switched / k_non_finite.
uint8_t step_modal_body(double h, ModalBody& b)
{
    uint8_t flags = 0;
    const size_t r = b.q.size();
    if (b.step_h != h) {
        b.exact_steps.resize(r);
        for (size_t k = 0; k < r; ++k)
            b.exact_steps[k] = modal::exact_mode_step(b.omega[k], b.damping_ratio, h);
        b.step_h = h;
    }
    // The last substep's nodal loads stay for the accuracy report: swap instead of clearing.
    if (b.last_has_load)
        std::fill(b.last_nodal_load.begin(), b.last_nodal_load.end(), 0.0);
    b.last_has_load = b.has_nodal_load || b.has_host_nodal_load;
    // Contact loads apart from the held ones (constraints, host): they are stepped as a kick.
    b.contact_load.assign(r, 0.0);
    if (b.has_nodal_load) {
        // Q = Φᵀ f over the nodes that carry load.
        const double* phi = b.basis->mode_shapes.data();
        for (size_t i = 0; i < b.nodal_load.size(); ++i, phi += r) {
            const double f = b.nodal_load[i];
            if (f == 0.0)
                continue;
            for (size_t k = 0; k < r; ++k)
                b.contact_load[k] += phi[k] * f;
        }
        std::swap(b.nodal_load, b.last_nodal_load); // last_nodal_load was zero, so nodal_load is now
        b.has_nodal_load = false;
    }
    if (b.has_host_nodal_load)
        for (size_t i = 0; i < b.last_nodal_load.size(); ++i)
            b.last_nodal_load[i] += b.host_nodal_load[i];
    for (size_t k = 0; k < r; ++k)
        b.last_load[k] = (b.load[k] + b.contact_load[k]) + b.host_force[k];
    if (b.adaptive_tolerance > 0.0) {
        const modal::ActiveChoice choice = modal::choose_active_modes(b, b.last_load);
        if (choice.active != b.active)
            set_active_modes(b, choice.active);
        b.truncation = choice.truncation;
        b.max_truncation = std::max(b.max_truncation, choice.truncation);
        b.max_lattice_error = std::max(b.max_lattice_error, choice.lattice_error);
        b.active_mode_substeps += static_cast<double>(b.active);
    }
    // Every mode steps, active or not: an inactive one is only hidden from the surface, so it joins
    // with the motion its loads gave it instead of missing the start of a strike.
    bool switched = false;
    for (size_t k = 0; k < r; ++k) {
        const double force = b.last_load[k];
        // The modes spring back to the (plastically moved) rest shape: step the elastic part q − q_p.
        // For an elastic body q_p = 0 and this is q itself, bit for bit.
        double elastic = b.q[k] - b.q_plastic[k];
        if (b.integrator == ModalIntegrator::CentralDifference) {
            if (b.omega[k] * h < modal::k_central_difference_limit) {
                modal::central_difference_step(b.omega[k], b.damping_ratio, h, force, elastic, b.q_dot[k]);
                b.q[k] = elastic + b.q_plastic[k];
                continue;
            }
            switched = true;
        }
        // The exact map holds its force over h, which against a contact spring (Q = −κq) is not
        // symplectic: det = 1 + κ(1 − cos ωh)/ω² > 1, which pumped a soft body bouncing at small
        // ωh (docs/stability.md). So below ωh = 2 the contact part is a kick, q̇ += λhQ_c, then the
        // exact flow under the held loads (constraints: their anchors are tuned on the held map;
        // host forces: piecewise constant by contract): symplectic, and with contact taken at q_n
        // the same trajectory as half-kick / flow / half-kick. Stiffer modes keep the held map,
        // whose quasi-static response a kick would overshoot (docs/modal.md "Integrators").
        double held = force;
        if (b.contact_load[k] != 0.0) {
            const double gain = modal::contact_kick_gain(b.omega[k], h);
            if (gain > 0.0) {
                b.q_dot[k] += gain * h * b.contact_load[k];
                held = b.load[k] + b.host_force[k];
            }
        }
        modal::apply_mode_step(b.exact_steps[k], held, elastic, b.q_dot[k]);
        b.q[k] = elastic + b.q_plastic[k];
    }
    if (switched)
        flags |= k_switched;
    if (b.plastic.plastic())
        modal::relieve_plastic(*b.surface->stress, b.plastic, b.basis->young, b.q, b.q_plastic,
                               b.plastic_strain);
    if (!all_finite(b.q) || !all_finite(b.q_dot) || !all_finite(b.q_plastic)) {
        // A fault stays in this body's deformation: back to the rest shape.
        std::fill(b.q.begin(), b.q.end(), 0.0);
        std::fill(b.q_dot.begin(), b.q_dot.end(), 0.0);
        std::fill(b.q_plastic.begin(), b.q_plastic.end(), 0.0);
        flags |= k_non_finite;
    }
    std::fill(b.load.begin(), b.load.end(), 0.0);
    b.surface_stale = true;
    return flags;
}

} // namespace

void update_modal_bodies(const StepContext& ctx, const Parallel& par, Registry& reg,
                         StepWarnings& io_warnings)
{
    // Each body on any thread writes only its own amplitudes and a flag byte; the counts and the fault
    // log follow on this thread in store order, so neither depends on threads.
    std::vector<ModalBody>& bodies = reg.store<ModalBody>().values();
    std::vector<uint8_t> flags(bodies.size(), 0);
    par.for_parts(bodies.size(), 1, [&](size_t, size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i)
            flags[i] = step_modal_body(ctx.h, bodies[i]);
    });
    const std::vector<Entity>& entities = reg.store<ModalBody>().entities();
    for (size_t i = 0; i < bodies.size(); ++i) {
        if ((flags[i] & k_switched) != 0)
            ++io_warnings.modal_integrator_switches;
        if ((flags[i] & k_non_finite) != 0) {
            ++io_warnings.modal_non_finite;
            if (ctx.faults != nullptr)
                ctx.faults->record(FaultKind::ModalNonFinite, entities[i], Stage::ModalUpdate);
        }
    }
}

void update_modal_surface(ModalBody& b)
{
    const size_t r = b.q.size();
    const SampleSet& rest = *b.surface->rest->samples;
    SampleSet& out = *b.samples;
    const double* d = b.surface->sample_modes.data();
    double max_u2 = 0.0;
    for (size_t i = 0; i < rest.samples.size(); ++i, d += 3 * r) {
        Vec3 u{};
        for (size_t k = 0; k < b.active; ++k) { // the others are hidden
            u.x += d[k] * b.q[k];
            u.y += d[r + k] * b.q[k];
            u.z += d[2 * r + k] * b.q[k];
        }
        out.samples[i].point = rest.samples[i].point + u;
        max_u2 = std::max(max_u2, dot(u, u));
    }
    constexpr double inf = std::numeric_limits<double>::infinity();
    for (size_t bucket = 0; bucket + 1 < out.start.size(); ++bucket) {
        Aabb box{{inf, inf, inf}, {-inf, -inf, -inf}};
        for (uint32_t i = out.start[bucket]; i < out.start[bucket + 1]; ++i)
            for (int a = 0; a < 3; ++a) {
                box.min[a] = std::min(box.min[a], out.samples[i].point[a]);
                box.max[a] = std::max(box.max[a], out.samples[i].point[a]);
            }
        out.bucket_box[bucket] = box;
    }
    const double grow = std::sqrt(max_u2);
    const Aabb& rest_box = b.surface->rest->local_box;
    b.collider->local_box = {rest_box.min - Vec3{grow, grow, grow}, rest_box.max + Vec3{grow, grow, grow}};
    b.surface_stale = false;
}

void update_modal_surfaces(const Parallel& par, Registry& reg, std::span<const BodyPair> pairs)
{
    if (reg.store<ModalBody>().size() == 0)
        return;
    // Each stale body once (a body is in several pairs), then each on any thread: it writes only itself.
    std::vector<ModalBody*> stale;
    for (const BodyPair& pair : pairs)
        for (Entity e : {pair.a, pair.b})
            if (ModalBody* b = reg.find<ModalBody>(e); b != nullptr && b->surface_stale) {
                b->surface_stale = false;
                stale.push_back(b);
            }
    par.for_parts(stale.size(), 1, [&](size_t, size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i)
            update_modal_surface(*stale[i]);
    });
}

void clear_modal_forces(Registry& reg)
{
    for (ModalBody& b : reg.store<ModalBody>().values()) {
        std::fill(b.host_force.begin(), b.host_force.end(), 0.0);
        if (b.has_host_nodal_load)
            std::fill(b.host_nodal_load.begin(), b.host_nodal_load.end(), 0.0);
        b.has_host_nodal_load = false;
    }
}

} // namespace supermodal
