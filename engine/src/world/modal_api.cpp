// SPDX-License-Identifier: MIT
// Public queries and setters of modal bodies (engine/include/supermodal/modal.h, bottom section).
#include "contact/narrowphase.h"
#include "core/assert.h"
#include "modal/accuracy.h"
#include "modal/inverse_map.h"
#include "modal/stress.h"
#include "supermodal/modal.h"
#include "world/modal_system.h"
#include "world/remould.h"
#include "world/world_impl.h"

#include <algorithm>
#include <cmath>

namespace supermodal
{
namespace
{

bool live(const World& world, Entity e)
{
    const World::Impl& w = impl_of(world);
    const bool ok = w.reg.valid(e) && w.reg.has<BodyModel>(e);
    SM_ASSERT(ok, "stale or null body handle");
    return ok;
}

const ModalBody* modal_of(const World& world, Entity e)
{
    if (!live(world, e) || !impl_of(world).reg.has<ModalBody>(e))
        return nullptr;
    return &impl_of(world).reg.get<ModalBody>(e);
}

} // namespace

Result<std::shared_ptr<const ModalBasis>> modal_basis_for(World& world, const BodyDef& def)
{
    if (!def.modal.enabled)
        return Error{"", "modal", "the body is rigid (modal.enabled is false)"};
    if (Status s = validate(def); !s)
        return s.error();
    Result<modal::LatticeChoice> choice = find_or_build_modal_basis(impl_of(world), def);
    if (!choice)
        return choice.error();
    return choice->basis;
}

const ModalBasis* body_modal_basis(const World& world, Entity e)
{
    const ModalBody* b = modal_of(world, e);
    return b ? b->model->basis.get() : nullptr;
}

BodyModalState body_modal_state(const World& world, Entity e)
{
    const ModalBody* b = modal_of(world, e);
    return b ? BodyModalState{b->state.q, b->state.q_dot} : BodyModalState{};
}

Status set_body_modal_state(World& world, Entity e, std::span<const double> amplitudes,
                            std::span<const double> velocities)
{
    World::Impl& w = impl_of(world);
    SM_ASSERT(!w.locked, "bodies cannot change while the world steps");
    if (w.locked)
        return Error{"", "modal", "bodies cannot change while the world steps"};
    ModalBody* b = live(world, e) ? w.reg.find<ModalBody>(e) : nullptr;
    if (b == nullptr)
        return Error{"", "modal", "not a modal body"};
    ModalState& s = b->state;
    if (amplitudes.size() != s.q.size() || velocities.size() != s.q.size())
        return Error{"", "modal", "expected " + std::to_string(s.q.size()) + " amplitudes and rates"};
    for (size_t k = 0; k < s.q.size(); ++k)
        if (!std::isfinite(amplitudes[k]) || !std::isfinite(velocities[k]))
            return Error{"", "modal", "amplitudes and rates must be finite"};
    wake_island_of(w.reg, w.contact, e);
    s.q.assign(amplitudes.begin(), amplitudes.end());
    s.q_dot.assign(velocities.begin(), velocities.end());
    // An adaptive body activates every mode up to the highest one set.
    size_t needed = s.active;
    for (size_t k = s.active; k < s.q.size(); ++k)
        if (amplitudes[k] != s.q_plastic[k] || velocities[k] != 0.0)
            needed = k + 1;
    if (needed != s.active)
        set_active_modes(*b, needed);
    update_modal_surface(*b);
    return {};
}

BodyModalActivity body_modal_activity(const World& world, Entity e)
{
    const ModalBody* b = modal_of(world, e);
    if (b == nullptr)
        return {};
    const ModalModel& m = *b->model;
    const ModalStats& stats = b->stats;
    BodyModalActivity out;
    out.adaptive = m.adaptive();
    out.active_modes = static_cast<int>(b->state.active);
    out.most_active_modes = static_cast<int>(stats.most_active);
    out.truncation_estimate = stats.truncation;
    out.max_truncation_estimate = stats.max_truncation;
    out.active_count_changes = stats.active_changes;
    out.active_mode_substeps = stats.active_mode_substeps;
    const Collider* collider = b->deformed.collider.get();
    if (collider != nullptr && collider->sampling_tolerance > 0.0) {
        const SampleDensityChoice& s = collider->sampling;
        out.contact_samples = static_cast<int>(collider->samples->samples.size());
        out.sample_spacing = s.spacing;
        out.sampling_gap = s.gap;
        out.sampling_gap_met = s.met;
    }
    out.lattice_cells = m.basis->cells;
    if (!m.lattice_changes.empty()) {
        out.lattice_frequency_change = *std::max_element(m.lattice_changes.begin(), m.lattice_changes.end());
        out.lattice_converged = out.lattice_frequency_change <= modal::k_auto_lattice_target;
        out.lattice_error_estimate = stats.max_lattice_error;
    }
    return out;
}

double body_modal_energy(const World& world, Entity e)
{
    const ModalBody* b = modal_of(world, e);
    if (b == nullptr)
        return 0.0;
    const ModalState& s = b->state;
    const std::vector<double>& omega = b->model->omega;
    double energy = 0.0;
    for (size_t k = 0; k < s.q.size(); ++k)
        energy += s.q_dot[k] * s.q_dot[k] +
                  omega[k] * omega[k] * (s.q[k] - s.q_plastic[k]) * (s.q[k] - s.q_plastic[k]);
    return 0.5 * energy;
}

BodyPlasticState body_plastic_state(const World& world, Entity e)
{
    const ModalBody* b = modal_of(world, e);
    if (b == nullptr)
        return {};
    const modal::PlasticParams& p = b->model->plastic;
    return {b->state.q_plastic, b->state.plastic_strain,
            p.yield_stress + p.hardening * b->state.plastic_strain};
}

ModalAccuracy body_modal_accuracy(const World& world, Entity e)
{
    const ModalBody* b = modal_of(world, e);
    if (b == nullptr)
        return {};
    const ModalModel& m = *b->model;
    const modal::AccuracyModel* model = m.surface->accuracy->get(*m.basis);
    if (model == nullptr)
        return {};
    modal::AccuracyInput in;
    in.nodal_force = b->stats.last_nodal_load;
    in.modal_force = b->stats.last_load;
    in.q = b->state.q;
    in.q_dot = b->state.q_dot;
    in.q_plastic = b->state.q_plastic;
    in.omega = m.omega;
    return modal::evaluate_accuracy(*model, *m.basis, in);
}

namespace
{
std::vector<double> elastic_part(const ModalState& s)
{
    std::vector<double> q(s.q.size());
    for (size_t k = 0; k < q.size(); ++k)
        q[k] = s.q[k] - s.q_plastic[k];
    return q;
}
} // namespace

BodyStress body_max_stress(const World& world, Entity e)
{
    const ModalBody* b = modal_of(world, e);
    if (b == nullptr)
        return {};
    const modal::StressModel& stress = *b->model->surface->stress;
    const modal::StressPeak peak = modal::max_von_mises(stress, elastic_part(b->state));
    if (peak.point < 0)
        return {};
    return {peak.von_mises, stress.points[static_cast<size_t>(peak.point)]};
}

std::array<double, 6> body_stress_at(const World& world, Entity e, const Vec3& point_shape)
{
    const ModalBody* b = modal_of(world, e);
    if (b == nullptr || !is_finite(point_shape))
        return {};
    return modal::stress_at(*b->model->basis, point_shape, elastic_part(b->state));
}

double von_mises_stress(const std::array<double, 6>& voigt)
{
    return modal::von_mises(voigt);
}

BodyPointTest body_point_test(const World& world, Entity e, const Vec3& world_point)
{
    BodyPointTest out;
    if (!live(world, e) || !is_finite(world_point))
        return out;
    const World::Impl& w = impl_of(world);
    const Pose& p = w.reg.get<Pose>(e);
    const BodyModel& m = w.reg.get<BodyModel>(e);
    // The rest shape's collider (a modal body's own collider holds deformed samples, same shape).
    const Collider& c = *m.collider;
    const Vec3 local = inv_rotate(p.orientation, world_point - p.position) + m.mass.center_of_mass;
    const ModalBody* b = modal_of(world, e);
    Vec3 rest = local;
    Mat3 forward = Mat3::identity(); // F⁻ᵀ
    if (b != nullptr) {
        const modal::InverseMap inv =
            modal::invert_deformation(*b->model->basis, b->state.q, local, b->state.correction);
        if (!inv.converged)
            return out;
        rest = inv.rest_point;
        forward = transpose(inv.inverse_deformation);
    }
    out.rest_point = rest;
    const InsideTest t = test_point(c, rest);
    if (!t.inside)
        return out;
    // depth = −m/|g| at rest; deformed: −m/|F⁻ᵀ g| = depth_rest / |F⁻ᵀ n|, normal along F⁻ᵀ n.
    const Vec3 n = forward * t.normal;
    const double scale = length(n);
    if (!(scale > 0.0) || !std::isfinite(scale))
        return out;
    out.inside = true;
    out.depth = t.depth / scale;
    out.normal = rotate(p.orientation, n / scale);
    return out;
}

std::vector<Vec3> body_static_correction(const World& world, Entity e)
{
    std::vector<Vec3> out;
    if (const ModalBody* b = modal_of(world, e))
        for (size_t i = 0; i + 2 < b->state.correction.size(); i += 3)
            out.push_back({b->state.correction[i], b->state.correction[i + 1], b->state.correction[i + 2]});
    return out;
}

Vec3 body_deformed_point(const World& world, Entity e, const Vec3& point_shape)
{
    if (!live(world, e))
        return {};
    const World::Impl& w = impl_of(world);
    const Pose& p = w.reg.get<Pose>(e);
    const Vec3 com = w.reg.get<BodyModel>(e).mass.center_of_mass;
    Vec3 local = point_shape - com;
    if (const ModalBody* b = w.reg.find<ModalBody>(e)) {
        const LatticeWeights lw = modal_weights(*b->model->basis, point_shape);
        local += modal_displacement(*b->model->basis, lw, b->state.q);
        if (!b->state.correction.empty()) // the static correction of the last substep's loads
            local += modal::interpolate_flat(lw, b->state.correction);
        if (!b->model->surface->rest_offsets.empty()) // remoulded: the rest shape moved too
            local += interpolate_nodal(lw, b->model->surface->rest_offsets);
    }
    return p.position + rotate(p.orientation, local);
}

BodyRemould body_remould(const World& world, Entity e)
{
    BodyRemould out;
    const ModalBody* b = modal_of(world, e);
    if (b == nullptr)
        return out;
    out.threshold = b->model->remould_threshold;
    out.rest_change = rest_shape_change(*b);
    out.rebuilds = b->stats.remould_count;
    out.pending_step = b->state.remould_step;
    out.failed = b->state.remould_failed;
    out.build_seconds = b->stats.remould_seconds;
    out.wait_seconds = b->stats.remould_wait_seconds;
    out.rest_offsets = b->model->surface->rest_offsets;
    return out;
}

} // namespace supermodal
