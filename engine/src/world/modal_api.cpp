// SPDX-License-Identifier: MIT
// Public queries and setters of modal bodies (engine/include/supermodal/modal.h, bottom section).
#include "contact/narrowphase.h"
#include "core/assert.h"
#include "modal/accuracy.h"
#include "modal/inverse_map.h"
#include "modal/stress.h"
#include "supermodal/modal.h"
#include "world/modal_system.h"
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
    return b ? b->basis.get() : nullptr;
}

BodyModalState body_modal_state(const World& world, Entity e)
{
    const ModalBody* b = modal_of(world, e);
    return b ? BodyModalState{b->q, b->q_dot} : BodyModalState{};
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
    if (amplitudes.size() != b->q.size() || velocities.size() != b->q.size())
        return Error{"", "modal", "expected " + std::to_string(b->q.size()) + " amplitudes and rates"};
    for (size_t k = 0; k < b->q.size(); ++k)
        if (!std::isfinite(amplitudes[k]) || !std::isfinite(velocities[k]))
            return Error{"", "modal", "amplitudes and rates must be finite"};
    b->q.assign(amplitudes.begin(), amplitudes.end());
    b->q_dot.assign(velocities.begin(), velocities.end());
    // An adaptive body activates every mode up to the highest one set.
    size_t needed = b->active;
    for (size_t k = b->active; k < b->q.size(); ++k)
        if (amplitudes[k] != b->q_plastic[k] || velocities[k] != 0.0)
            needed = k + 1;
    if (needed != b->active)
        set_active_modes(*b, needed);
    update_modal_surface(*b);
    return {};
}

BodyModalActivity body_modal_activity(const World& world, Entity e)
{
    const ModalBody* b = modal_of(world, e);
    if (b == nullptr)
        return {};
    BodyModalActivity out;
    out.adaptive = b->adaptive_tolerance > 0.0;
    out.active_modes = static_cast<int>(b->active);
    out.most_active_modes = static_cast<int>(b->most_active);
    out.truncation_estimate = b->truncation;
    out.max_truncation_estimate = b->max_truncation;
    out.active_count_changes = b->active_changes;
    out.active_mode_substeps = b->active_mode_substeps;
    if (b->collider && b->collider->sampling_tolerance > 0.0) {
        const SampleDensityChoice& s = b->collider->sampling;
        out.contact_samples = static_cast<int>(b->collider->samples->samples.size());
        out.sample_spacing = s.spacing;
        out.sampling_gap = s.gap;
        out.sampling_gap_met = s.met;
    }
    out.lattice_cells = b->basis->cells;
    if (!b->lattice_changes.empty()) {
        out.lattice_frequency_change =
            *std::max_element(b->lattice_changes.begin(), b->lattice_changes.end());
        out.lattice_converged = out.lattice_frequency_change <= modal::k_auto_lattice_target;
        out.lattice_error_estimate = b->max_lattice_error;
    }
    return out;
}

double body_modal_energy(const World& world, Entity e)
{
    const ModalBody* b = modal_of(world, e);
    if (b == nullptr)
        return 0.0;
    double energy = 0.0;
    for (size_t k = 0; k < b->q.size(); ++k)
        energy += b->q_dot[k] * b->q_dot[k] +
                  b->omega[k] * b->omega[k] * (b->q[k] - b->q_plastic[k]) * (b->q[k] - b->q_plastic[k]);
    return 0.5 * energy;
}

BodyPlasticState body_plastic_state(const World& world, Entity e)
{
    const ModalBody* b = modal_of(world, e);
    if (b == nullptr)
        return {};
    return {b->q_plastic, b->plastic_strain,
            b->plastic.yield_stress + b->plastic.hardening * b->plastic_strain};
}

ModalAccuracy body_modal_accuracy(const World& world, Entity e)
{
    const ModalBody* b = modal_of(world, e);
    if (b == nullptr)
        return {};
    const modal::AccuracyModel* model = b->surface->accuracy->get(*b->basis);
    if (model == nullptr)
        return {};
    modal::AccuracyInput in;
    in.nodal_force = b->last_nodal_load;
    in.modal_force = b->last_load;
    in.q = b->q;
    in.q_dot = b->q_dot;
    in.q_plastic = b->q_plastic;
    in.omega = b->omega;
    return modal::evaluate_accuracy(*model, *b->basis, in);
}

namespace
{
std::vector<double> elastic_part(const ModalBody& b)
{
    std::vector<double> q(b.q.size());
    for (size_t k = 0; k < q.size(); ++k)
        q[k] = b.q[k] - b.q_plastic[k];
    return q;
}
} // namespace

BodyStress body_max_stress(const World& world, Entity e)
{
    const ModalBody* b = modal_of(world, e);
    if (b == nullptr)
        return {};
    const modal::StressPeak peak = modal::max_von_mises(*b->surface->stress, elastic_part(*b));
    if (peak.point < 0)
        return {};
    return {peak.von_mises, b->surface->stress->points[static_cast<size_t>(peak.point)]};
}

std::array<double, 6> body_stress_at(const World& world, Entity e, const Vec3& point_shape)
{
    const ModalBody* b = modal_of(world, e);
    if (b == nullptr || !is_finite(point_shape))
        return {};
    return modal::stress_at(*b->basis, point_shape, elastic_part(*b));
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
        const modal::InverseMap inv = modal::invert_deformation(*b->basis, b->q, local);
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

Vec3 body_deformed_point(const World& world, Entity e, const Vec3& point_shape)
{
    if (!live(world, e))
        return {};
    const World::Impl& w = impl_of(world);
    const Pose& p = w.reg.get<Pose>(e);
    const Vec3 com = w.reg.get<BodyModel>(e).mass.center_of_mass;
    Vec3 local = point_shape - com;
    if (w.reg.has<ModalBody>(e))
        local += modal_displacement(*w.reg.get<ModalBody>(e).basis, point_shape, w.reg.get<ModalBody>(e).q);
    return p.position + rotate(p.orientation, local);
}

} // namespace supermodal
