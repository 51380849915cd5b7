// SPDX-License-Identifier: MIT
#include "world/modal_system.h"

#include "core/assert.h"
#include "geometry/aabb.h"
#include "modal/accuracy.h"
#include "modal/adaptive.h"
#include "modal/inverse_map.h"
#include "modal/stress.h"
#include "world/integrate.h"
#include "world/world_impl.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace supermodal
{

// Per rest sample, the body-frame displacement of each unit amplitude: D_s = Σ_nodes w_n φ_n (3 × r),
// so deforming a sample costs 3r multiply-adds instead of 3·20·r.
std::shared_ptr<const ModalSurface> make_modal_surface(std::shared_ptr<const Collider> rest,
                                                       std::shared_ptr<const ModalBasis> basis,
                                                       std::shared_ptr<const Collider> material,
                                                       std::vector<Vec3> rest_offsets)
{
    auto surface = std::make_shared<ModalSurface>();
    const size_t r = static_cast<size_t>(basis->mode_count);
    const std::vector<SurfaceSample>& samples = material->samples->samples; // named where they were
    surface->sample_modes.assign(samples.size() * 3 * r, 0.0);
    surface->sample_weights.resize(samples.size());
    for (size_t i = 0; i < samples.size(); ++i) {
        const LatticeWeights& lw = surface->sample_weights[i] =
            modal_weights(*basis, samples[i].point + material->com_shape);
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
        std::make_shared<const modal::StressModel>(modal::build_stress_model(*basis, material->shape));
    surface->accuracy = std::make_shared<modal::AccuracyCache>();
    ModalBasisDef& def = surface->accuracy->def; // what modal_basis_def() gave the basis, from the basis
    def.shape = rest->shape;
    def.density = basis->density;
    def.young = basis->young;
    def.poisson = basis->poisson;
    def.lattice.cells = basis->cells;
    def.lattice.element_order = basis->element_order;
    def.mode_count = basis->mode_count;
    def.rest_offsets = rest_offsets;
    surface->rest = std::move(rest);
    surface->basis = std::move(basis);
    surface->material = std::move(material);
    surface->rest_offsets = std::move(rest_offsets);
    return surface;
}

namespace
{

std::shared_ptr<const ModalModel> make_model(std::shared_ptr<const ModalSurface> surface,
                                             const modal::LatticeChoice& choice, const BodyDef& def)
{
    auto model = std::make_shared<ModalModel>();
    const ModalBasis& basis = *choice.basis;
    const size_t r = static_cast<size_t>(basis.mode_count);
    model->omega.resize(r);
    for (size_t k = 0; k < r; ++k)
        model->omega[k] = 2.0 * std::numbers::pi * basis.frequencies_hz[k];
    model->damping_ratio = def.modal.damping_ratio;
    model->integrator = def.modal.integrator;
    model->plastic.yield_stress = def.modal.yield_stress;
    model->plastic.hardening = def.modal.hardening;
    model->plastic.max_plastic_strain = def.modal.max_plastic_strain;
    model->adaptive_tolerance = def.modal.adaptive_tolerance;
    model->remould_threshold = def.modal.remould_threshold;
    model->remould_delay_steps = def.modal.remould_delay_steps;
    model->static_correction = def.modal.static_correction;
    model->lattice_changes = choice.frequency_changes;
    model->surface = std::move(surface);
    model->basis = choice.basis;
    return model;
}

// Whether a body made from `def` with `choice` on `rest` steps exactly as model m (omega follows the basis).
bool same_model(const ModalModel& m, const std::shared_ptr<const Collider>& rest,
                const modal::LatticeChoice& choice, const BodyDef& def)
{
    return m.basis == choice.basis && m.surface->rest == rest && m.damping_ratio == def.modal.damping_ratio &&
           m.integrator == def.modal.integrator && m.plastic.yield_stress == def.modal.yield_stress &&
           m.plastic.hardening == def.modal.hardening &&
           m.plastic.max_plastic_strain == def.modal.max_plastic_strain &&
           m.adaptive_tolerance == def.modal.adaptive_tolerance &&
           m.remould_threshold == def.modal.remould_threshold &&
           m.remould_delay_steps == def.modal.remould_delay_steps &&
           m.static_correction == def.modal.static_correction &&
           m.lattice_changes == choice.frequency_changes;
}

// The world's model for a body, made on first use: identical bodies share it (and its substep maps), as
// they share colliders; bodies that differ only in their ModalBodyDef share the surface.
ModalShared shared_for(World::Impl& w, const std::shared_ptr<const Collider>& rest,
                       const modal::LatticeChoice& choice, const BodyDef& def)
{
    std::shared_ptr<const ModalSurface> surface;
    for (const ModalShared& s : w.modal_models) {
        if (same_model(*s.model, rest, choice, def))
            return s;
        if (s.model->surface->rest == rest && s.model->surface->basis == choice.basis &&
            s.model->surface->rest_offsets.empty())
            surface = s.model->surface;
    }
    if (surface == nullptr)
        surface = make_modal_surface(rest, choice.basis, rest, {});
    w.modal_models.push_back(
        {make_model(std::move(surface), choice, def), std::make_shared<ModalSubstepMaps>()});
    return w.modal_models.back();
}

// Q_k += φ_k(x_local) · Rᵀ f: the lattice field at the point, projected on the body-frame force.
void add_load(const ModalModel& model, const BodyModel& m, const Pose& p, const Vec3& x, const Vec3& f,
              std::vector<double>& io_q)
{
    const Vec3 local = inv_rotate(p.orientation, x - p.position) + m.mass.center_of_mass;
    const Vec3 fl = inv_rotate(p.orientation, f);
    if (!is_finite(local) || !is_finite(fl))
        return;
    const ModalBasis& basis = *model.basis;
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
bool lump_load(const ModalModel& model, const BodyModel& m, const Pose& p, const Vec3& x, const Vec3& f,
               std::vector<double>& io_nodal)
{
    const Vec3 local = inv_rotate(p.orientation, x - p.position) + m.mass.center_of_mass;
    const Vec3 fl = inv_rotate(p.orientation, f);
    if (!is_finite(local) || !is_finite(fl))
        return false;
    const LatticeWeights lw = modal_weights(*model.basis, local);
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
    BodyModel& m = w.reg.get<BodyModel>(e);
    const ModalShared shared = shared_for(w, m.collider, choice, def);
    const size_t r = shared.model->mode_count();
    const size_t nodal = shared.model->basis->node_positions.size() * 3;
    ModalBody b;
    b.model = shared.model;
    b.maps = shared.maps;
    b.state.q.assign(r, 0.0);
    b.state.q_dot.assign(r, 0.0);
    b.state.host_force.assign(r, 0.0);
    b.state.q_plastic.assign(r, 0.0);
    b.state.active = b.model->adaptive() ? 0 : r; // adaptive bodies start rigid
    b.loads.load.assign(r, 0.0);
    b.loads.nodal_load.assign(nodal, 0.0);
    b.loads.host_nodal_load.assign(nodal, 0.0);
    b.loads.solved_nodal_load.assign(nodal, 0.0);
    b.stats.last_nodal_load.assign(nodal, 0.0);
    b.stats.last_load.assign(r, 0.0);
    b.stats.most_active = b.state.active;
    if (def.modal.static_correction) {
        b.state.correction.assign(nodal, 0.0);
        b.state.contact_correction.assign(nodal, 0.0);
        // The full lattice is factored now rather than in the first loaded substep. Where it cannot be,
        // the correction stays zero and body_modal_accuracy() says why.
        (void)b.model->surface->accuracy->get(*b.model->basis);
    }
    // Its own collider and samples: the deformed surface belongs to this body alone. The rest shape's
    // support point would ignore the deformation, so the body counts as non-convex (samples only).
    b.deformed.samples = std::make_shared<SampleSet>(*m.collider->samples);
    b.deformed.collider = std::make_shared<Collider>(*m.collider);
    b.deformed.collider->samples = b.deformed.samples;
    b.deformed.collider->convex = false;
    // Adaptive bodies too: swapping to the rest collider (support-map contact) while rigid changed the
    // strike itself: the 2x4 board of ball_on_board bent 18% less when its contact path switched as
    // the ball struck (measured against the all-modes board, docs/modal.md "Adaptive modes").
    m.collider = b.deformed.collider;
    w.reg.emplace(e, std::move(b));
}

namespace
{

// A shape-frame point against the deformed shape: back to the rest point X with X + u(X) = p (Newton,
// the shown modes and the static correction, as the samples show them), the rest shape's measure there, its
// gradient carried forward by F⁻ᵀ: depth = depth_rest / |F⁻ᵀ n|, normal along F⁻ᵀ n. Where Newton fails (a
// folded field) the point is tested against the rest shape, as without the inverse map.
InsideTest deformed_inside_test(const void* ctx, const Collider& c, const Vec3& p_shape)
{
    const auto& b = *static_cast<const ModalBody*>(ctx);
    const std::span<const double> shown{b.state.q.data(), b.state.active};
    const modal::InverseMap inv =
        modal::invert_deformation(*b.model->basis, shown, p_shape, b.state.correction);
    if (!inv.converged)
        return test_point(c, p_shape);
    InsideTest t = test_point(c, inv.rest_point);
    if (!t.inside)
        return t;
    const Vec3 n = transpose(inv.inverse_deformation) * t.normal;
    const double scale = length(n);
    if (!(scale > 0.0) || !std::isfinite(scale))
        return test_point(c, p_shape);
    t.depth /= scale;
    t.normal = n / scale;
    return t;
}

} // namespace

DeformedTest modal_deformed_test(const Registry& reg, Entity e)
{
    const ModalBody* b = reg.find<ModalBody>(e);
    // A remoulded body's rest shape is the collider's moved by its rest offsets, which the inverse map
    // does not undo: it keeps the rest test.
    if (b == nullptr || b->state.active == 0 || !b->model->surface->rest_offsets.empty())
        return {};
    return {&deformed_inside_test, b};
}

void set_active_modes(ModalBody& b, size_t active)
{
    if (active != b.state.active)
        ++b.stats.active_changes;
    b.state.active = std::min(active, b.state.q.size());
    b.stats.most_active = std::max(b.stats.most_active, b.state.active);
    b.deformed.stale = true;
}

void modal_add_point_load(Registry& reg, Entity e, const Vec3& world_point, const Vec3& world_force)
{
    // Lumped on the lattice nodes (3·count multiply-adds) rather than projected on the modes
    // (3·count·r): a resting body has hundreds of contact points per substep.
    ModalBody* b = reg.find<ModalBody>(e);
    if (b == nullptr)
        return;
    if (lump_load(*b->model, reg.get<BodyModel>(e), reg.get<Pose>(e), world_point, world_force,
                  b->loads.nodal_load))
        b->loads.has_nodal_load = true;
}

void modal_add_solved_load(Registry& reg, Entity e, const Vec3& world_point, const Vec3& world_force)
{
    ModalBody* b = reg.find<ModalBody>(e);
    if (b != nullptr && lump_load(*b->model, reg.get<BodyModel>(e), reg.get<Pose>(e), world_point,
                                  world_force, b->loads.solved_nodal_load))
        b->loads.has_solved_nodal_load = true;
}

void modal_add_spring_work(Registry& reg, Entity e, double work)
{
    if (ModalBody* b = reg.find<ModalBody>(e))
        b->loads.spring_work += work;
}

void modal_add_host_load(Registry& reg, Entity e, const Vec3& world_point, const Vec3& world_force)
{
    if (ModalBody* b = reg.find<ModalBody>(e)) {
        add_load(*b->model, reg.get<BodyModel>(e), reg.get<Pose>(e), world_point, world_force,
                 b->state.host_force);
        // Also lumped, for the accuracy report's F (the projection above keeps the exact point's field).
        if (lump_load(*b->model, reg.get<BodyModel>(e), reg.get<Pose>(e), world_point, world_force,
                      b->loads.host_nodal_load))
            b->loads.has_host_nodal_load = true;
    }
}

void prepare_modal_substep(Registry& reg, double h)
{
    // The first body of each model makes them; the others find them made.
    reg.each<ModalBody>([&](Entity, ModalBody& b) {
        ModalSubstepMaps& maps = *b.maps;
        if (maps.h == h)
            return;
        const ModalModel& m = *b.model;
        maps.exact.resize(m.mode_count());
        maps.sinc.resize(m.mode_count());
        for (size_t k = 0; k < m.mode_count(); ++k) {
            maps.exact[k] = modal::exact_mode_step(m.omega[k], m.damping_ratio, h);
            maps.sinc[k] = modal::half_step_sinc(m.omega[k], h);
        }
        maps.h = h;
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
    const ModalBasis& basis = *b->model->basis;
    const size_t r = static_cast<size_t>(basis.mode_count);
    const LatticeWeights lw = modal_weights(basis, local);
    const std::vector<double>& sincs = b->maps->sinc;
    SM_ASSERT(sincs.size() == r, "prepare_modal_substep() runs before the contact forces");
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
        const double sinc = sincs[k];
        sum += (d == Vec3{} ? dot(phi_k, phi_k) : dot(phi_k, dl) * dot(phi_k, dl)) * sinc * sinc;
    }
    return sum;
}

void modal_add_point_impulse(Registry& reg, Entity e, const Vec3& world_point, const Vec3& impulse)
{
    if (ModalBody* b = reg.find<ModalBody>(e))
        add_load(*b->model, reg.get<BodyModel>(e), reg.get<Pose>(e), world_point, impulse, b->state.q_dot);
}

namespace
{

constexpr uint8_t k_switched = 1;   // central difference was unstable for some modes, stepped exactly
constexpr uint8_t k_non_finite = 2; // amplitudes turned NaN/Inf: reset to rest

// This substep's contact nodal loads projected on the modes (Q_c = Φᵀ F, into io.contact), and the
// accuracy report's loads: F (contact and host) into stats.last_nodal_load, and Q, what each mode is
// driven with, into stats.last_load.
void project_loads(const ModalModel& m, const ModalState& s, ModalLoads& io, ModalStats& stats)
{
    const size_t r = m.mode_count();
    // The last substep's nodal loads stay for the accuracy report: swap instead of clearing.
    if (stats.last_has_load)
        std::fill(stats.last_nodal_load.begin(), stats.last_nodal_load.end(), 0.0);
    stats.last_has_load = io.has_nodal_load || io.has_host_nodal_load || io.has_solved_nodal_load;
    // Contact loads apart from the held ones (constraints, host): they are stepped as a kick.
    io.contact.assign(r, 0.0);
    if (io.has_nodal_load) {
        // Q = Φᵀ f over the nodes that carry load.
        const double* phi = m.basis->mode_shapes.data();
        for (size_t i = 0; i < io.nodal_load.size(); ++i, phi += r) {
            const double f = io.nodal_load[i];
            if (f == 0.0)
                continue;
            for (size_t k = 0; k < r; ++k)
                io.contact[k] += phi[k] * f;
        }
        std::swap(io.nodal_load, stats.last_nodal_load); // last_nodal_load was zero, so nodal_load is now
        io.has_nodal_load = false;
    }
    if (io.has_host_nodal_load)
        for (size_t i = 0; i < stats.last_nodal_load.size(); ++i)
            stats.last_nodal_load[i] += io.host_nodal_load[i];
    if (io.has_solved_nodal_load) {
        for (size_t i = 0; i < stats.last_nodal_load.size(); ++i) {
            stats.last_nodal_load[i] += io.solved_nodal_load[i];
            io.solved_nodal_load[i] = 0.0;
        }
        io.has_solved_nodal_load = false;
    }
    for (size_t k = 0; k < r; ++k)
        stats.last_load[k] = (io.load[k] + io.contact[k]) + s.host_force[k];
}

// An adaptive body's active count for this substep's loads, and what that leaves out.
void choose_active(ModalBody& b)
{
    const modal::ActiveChoice choice = modal::choose_active_modes(*b.model, b.state, b.stats.last_load);
    if (choice.active != b.state.active)
        set_active_modes(b, choice.active);
    ModalStats& stats = b.stats;
    stats.truncation = choice.truncation;
    stats.max_truncation = std::max(stats.max_truncation, choice.truncation);
    stats.max_lattice_error = std::max(stats.max_lattice_error, choice.lattice_error);
    stats.active_mode_substeps += static_cast<double>(b.state.active);
}

// Every mode over h [s] under `force` (r, [N/√kg]: held loads plus the contact kick loads.contact); returns
// whether central difference was unstable for some mode (stepped exactly instead). Every mode steps, active
// or not: an inactive one is only hidden from the surface, so it joins with the motion its loads gave it
// instead of missing the start of a strike.
bool integrate_modes(const ModalModel& m, const ModalSubstepMaps& maps, double h, const ModalLoads& loads,
                     std::span<const double> force, ModalState& s)
{
    bool switched = false;
    for (size_t k = 0; k < m.mode_count(); ++k) {
        // The modes spring back to the (plastically moved) rest shape: step the elastic part q − q_p.
        // For an elastic body q_p = 0 and this is q itself, bit for bit.
        double elastic = s.q[k] - s.q_plastic[k];
        if (m.integrator == ModalIntegrator::CentralDifference) {
            if (m.omega[k] * h < modal::k_central_difference_limit) {
                modal::central_difference_step(m.omega[k], m.damping_ratio, h, force[k], elastic, s.q_dot[k]);
                s.q[k] = elastic + s.q_plastic[k];
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
        double held = force[k];
        if (loads.contact[k] != 0.0) {
            const double gain = modal::contact_kick_gain(m.omega[k], h);
            if (gain > 0.0) {
                s.q_dot[k] += gain * h * loads.contact[k];
                held = loads.load[k] + s.host_force[k];
            }
        }
        modal::apply_mode_step(maps.exact[k], held, elastic, s.q_dot[k]);
        s.q[k] = elastic + s.q_plastic[k];
    }
    return switched;
}

// g = Fᵀu / Σ f·depth [-]: the work the contact loads F do on their dent u over the work they do on the
// contact springs (for one point, k·c); 0 where no spring is compressed.
double loop_gain(const std::vector<double>& load, const std::vector<double>& dent, double spring_work)
{
    if (!(spring_work > 0.0))
        return 0.0;
    double dent_work = 0.0;
    for (size_t i = 0; i < load.size(); ++i)
        dent_work += load[i] * dent[i];
    return std::max(dent_work, 0.0) / spring_work;
}

// Mode acceleration: the static answer of the modes the surface does not show to this substep's loads,
// shown on the surface until the next substep replaces it. Host loads enter at once. Contact loads feed
// back: the dent moves the surface the contact force comes from, and on a soft body the dent can be far
// more compliant than the contact spring. Taken at once, force and dent chased each other every substep
// (a resting soft ellipsoid never slept). So their part moves a share of the way to its answer each
// substep: 1 − e^(−h/τ) (τ = k_contact_correction_time), at most 1 / (1 + g), where g = Fᵀu / Σ f·depth
// is the dent's compliance over the springs' (for one point: k·c). A lag loop with gain g is stable
// while share·(1 + g) < 2 and does not overshoot at 1; the load-tuned soft spring stiffens with the load,
// so g grows with it. At rest it is the same answer. Reads the loads before project_loads merges them.
void correct_statically(double h, const ModalModel& m, ModalLoads& io, ModalState& s)
{
    const modal::AccuracyModel* full = m.surface->accuracy->get(*m.basis);
    const size_t n = s.correction.size();
    std::vector<double>& load = io.correction_load;
    std::vector<double>& answer = io.correction_answer;
    load.assign(n, 0.0);
    answer.assign(n, 0.0);
    const bool contact = io.has_nodal_load || io.has_solved_nodal_load;
    for (size_t i = 0; i < n && contact; ++i)
        load[i] = (io.has_nodal_load ? io.nodal_load[i] : 0.0) +
                  (io.has_solved_nodal_load ? io.solved_nodal_load[i] : 0.0);
    if (full != nullptr && contact)
        modal::static_correction(*full, *m.basis, load, m.omega, s.active, answer);
    const double gain = contact ? loop_gain(load, answer, io.spring_work) : 0.0;
    const double share = std::min(1.0 - std::exp(-h / k_contact_correction_time), 1.0 / (1.0 + gain));
    for (size_t i = 0; i < n; ++i)
        s.contact_correction[i] += share * (answer[i] - s.contact_correction[i]);
    std::fill(answer.begin(), answer.end(), 0.0);
    if (full != nullptr && io.has_host_nodal_load)
        modal::static_correction(*full, *m.basis, io.host_nodal_load, m.omega, s.active, answer);
    for (size_t i = 0; i < n; ++i)
        s.correction[i] = s.contact_correction[i] + answer[i];
}

// A fault stays in this body's deformation: back to the rest shape. Returns whether it was needed.
bool reset_non_finite(ModalState& s)
{
    if (all_finite(s.q) && all_finite(s.q_dot) && all_finite(s.q_plastic) && all_finite(s.correction) &&
        all_finite(s.contact_correction))
        return false;
    std::fill(s.correction.begin(), s.correction.end(), 0.0);
    std::fill(s.contact_correction.begin(), s.contact_correction.end(), 0.0);
    std::fill(s.q.begin(), s.q.end(), 0.0);
    std::fill(s.q_dot.begin(), s.q_dot.end(), 0.0);
    std::fill(s.q_plastic.begin(), s.q_plastic.end(), 0.0);
    return true;
}

// One modal body's amplitudes over h [s] under this substep's loads; returns k_switched / k_non_finite.
// Reads the shared model and maps; writes only the body's own state, loads, statistics and stale flag.
uint8_t step_modal_body(double h, ModalBody& b)
{
    const ModalModel& m = *b.model;
    if (m.static_correction)
        correct_statically(h, m, b.loads, b.state);
    b.loads.spring_work = 0.0;
    project_loads(m, b.state, b.loads, b.stats);
    if (m.adaptive())
        choose_active(b);
    uint8_t flags = 0;
    if (integrate_modes(m, *b.maps, h, b.loads, b.stats.last_load, b.state))
        flags |= k_switched;
    if (m.plastic.plastic())
        modal::relieve_plastic(*m.surface->stress, m.plastic, m.basis->young, b.state.q, b.state.q_plastic,
                               b.state.plastic_strain);
    if (reset_non_finite(b.state))
        flags |= k_non_finite;
    std::fill(b.loads.load.begin(), b.loads.load.end(), 0.0);
    b.deformed.stale = true;
    return flags;
}

} // namespace

void update_modal_bodies(const StepContext& ctx, const Parallel& par, Registry& reg, ModalScratch& scratch,
                         StepWarnings& io_warnings)
{
    // The shared maps first, on this thread. Then each body on any thread writes only its own amplitudes
    // and a flag byte; the counts and the fault log follow on this thread in store order, so neither
    // depends on threads.
    prepare_modal_substep(reg, ctx.h);
    std::vector<ModalBody>& bodies = reg.store<ModalBody>().values();
    std::vector<uint8_t>& flags = scratch.flags;
    flags.assign(bodies.size(), 0);
    const std::vector<Entity>& entities = reg.store<ModalBody>().entities();
    par.for_parts(bodies.size(), 1, [&](size_t, size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i)
            if (!reg.get<Sleep>(entities[i]).asleep) // a sleeping body's modes rest with it
                flags[i] = step_modal_body(ctx.h, bodies[i]);
    });
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
    const ModalSurface& surface = *b.model->surface;
    const std::vector<double>& q = b.state.q;
    const size_t r = q.size();
    const SampleSet& rest = *surface.rest->samples;
    SampleSet& out = *b.deformed.samples;
    const double* d = surface.sample_modes.data();
    double max_u2 = 0.0;
    for (size_t i = 0; i < rest.samples.size(); ++i, d += 3 * r) {
        Vec3 u{};
        for (size_t k = 0; k < b.state.active; ++k) { // the others are hidden
            u.x += d[k] * q[k];
            u.y += d[r + k] * q[k];
            u.z += d[2 * r + k] * q[k];
        }
        if (!b.state.correction.empty())
            u += modal::interpolate_flat(surface.sample_weights[i], b.state.correction);
        out.samples[i].point = rest.samples[i].point + u;
        max_u2 = std::max(max_u2, dot(u, u));
    }
    for (size_t bucket = 0; bucket + 1 < out.start.size(); ++bucket) {
        Aabb box = empty_box();
        for (uint32_t i = out.start[bucket]; i < out.start[bucket + 1]; ++i)
            grow(box, out.samples[i].point);
        out.bucket_box[bucket] = box;
    }
    const double grow = std::sqrt(max_u2);
    const Aabb& rest_box = surface.rest->local_box;
    b.deformed.collider->local_box = {rest_box.min - Vec3{grow, grow, grow},
                                      rest_box.max + Vec3{grow, grow, grow}};
    b.deformed.stale = false;
}

void update_modal_surfaces(const Parallel& par, Registry& reg, std::span<const BodyPair> pairs,
                           ModalScratch& scratch)
{
    if (reg.store<ModalBody>().size() == 0)
        return;
    // Each stale body once (a body is in several pairs), then each on any thread: it writes only itself.
    std::vector<ModalBody*>& stale = scratch.stale;
    stale.clear();
    for (const BodyPair& pair : pairs)
        for (Entity e : {pair.a, pair.b})
            if (ModalBody* b = reg.find<ModalBody>(e); b != nullptr && b->deformed.stale) {
                b->deformed.stale = false;
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
        std::fill(b.state.host_force.begin(), b.state.host_force.end(), 0.0);
        if (b.loads.has_host_nodal_load)
            std::fill(b.loads.host_nodal_load.begin(), b.loads.host_nodal_load.end(), 0.0);
        b.loads.has_host_nodal_load = false;
    }
}

} // namespace supermodal
