// SPDX-License-Identifier: MIT
// Constraint handles and queries (the public side of constraint.h).
#include "constraints/constraint_world.h"
#include "core/assert.h"
#include "supermodal/modal.h"
#include "supermodal/world.h"
#include "world/world_impl.h"

#include <algorithm>
#include <cmath>

namespace supermodal
{
namespace
{

bool finite_anchor(const AnchorDef& anchor)
{
    return is_finite(anchor.point) && is_finite(anchor.direction) && std::isfinite(anchor.eta) &&
           std::isfinite(anchor.omega);
}

const ConstraintModel* model_of(const World& world, Constraint c)
{
    const ConstraintWorld& cw = impl_of(world).constraints;
    SM_ASSERT(cw.reg.valid(to_entity(c)), "stale or null constraint handle");
    return cw.reg.valid(to_entity(c)) ? &cw.reg.get<ConstraintModel>(to_entity(c)) : nullptr;
}

const ConstraintState* state_of(const World& world, Constraint c)
{
    const ConstraintWorld& cw = impl_of(world).constraints;
    SM_ASSERT(cw.reg.valid(to_entity(c)), "stale or null constraint handle");
    return cw.reg.valid(to_entity(c)) ? &cw.reg.get<ConstraintState>(to_entity(c)) : nullptr;
}

} // namespace

ConstraintDef default_constraint_def()
{
    return ConstraintDef{};
}

Status validate(const ConstraintDef& def)
{
    if (def.a.is_null())
        return Error{"", "a", "a constraint needs a body a"};
    if (def.a == def.b)
        return Error{"", "b", "a constraint needs two different bodies"};
    if (!(def.frequency_hz > 0.0) || !std::isfinite(def.frequency_hz))
        return Error{"", "frequency", "expected a finite frequency > 0 Hz"};
    if (!(def.damping_ratio >= 0.0) || !std::isfinite(def.damping_ratio))
        return Error{"", "damping_ratio", "expected a finite damping ratio >= 0"};
    if (!(def.angular_damping >= 0.0) || !std::isfinite(def.angular_damping))
        return Error{"", "angular_damping", "expected a finite angular damping >= 0 1/s"};
    if (!(def.break_force > 0.0))
        return Error{"", "break_force", "expected a break force > 0 N (or infinity)"};
    if (!std::isfinite(def.rest_length) || !std::isfinite(def.swing_limit) || !std::isfinite(def.twist_limit))
        return Error{"", "rest_length", "expected finite lengths and limits"};
    if (def.swing_limit > M_PI || def.twist_limit > M_PI)
        return Error{"", "swing_limit", "expected limits <= pi rad"};
    if (!finite_anchor(def.anchor_a) || !finite_anchor(def.anchor_b) || !is_finite(def.axis_a))
        return Error{"", "anchor_a", "expected finite anchors and axis"};
    for (const AnchorDef* anchor : {&def.anchor_a, &def.anchor_b})
        if (anchor->kind == AnchorKind::Direction && !(length(anchor->direction) > 0.0))
            return Error{"", "anchor_a", "a direction anchor needs a non-zero direction"};
    return {};
}

Constraint create_constraint(World& world, const ConstraintDef& def)
{
    World::Impl& w = impl_of(world);
    const Status status = validate(def);
    SM_ASSERT(status.ok(), "invalid ConstraintDef");
    SM_ASSERT(!w.locked, "constraints cannot be created while the world steps");
    const bool bodies_ok = w.reg.valid(def.a) && (def.b.is_null() || w.reg.valid(def.b));
    SM_ASSERT(bodies_ok, "constraint on a stale body handle");
    if (!status || w.locked || !bodies_ok)
        return Constraint{};
    ConstraintModel c;
    c.def = def;
    const BodyModel& ma = w.reg.get<BodyModel>(def.a);
    const Pose& pa = w.reg.get<Pose>(def.a);
    c.local_a = resolve_anchor(ma.shape, def.anchor_a);
    Vec3 world_b = def.anchor_b.point;
    Quat qb{};
    if (!def.b.is_null()) {
        const BodyModel& mb = w.reg.get<BodyModel>(def.b);
        const Pose& pb = w.reg.get<Pose>(def.b);
        c.local_b = resolve_anchor(mb.shape, def.anchor_b);
        world_b = world_point(mb, pb, c.local_b);
        qb = pb.orientation;
    } else {
        c.local_b = def.anchor_b.point; // a world point
    }
    c.rest_length =
        def.rest_length >= 0.0 ? def.rest_length : length(world_point(ma, pa, c.local_a) - world_b);
    c.rest_relative = normalized(conjugate(pa.orientation) * qb);
    Vec3 axis = def.axis_a;
    if (!(length(axis) > 0.0))
        axis = c.local_a;
    c.axis_a = length(axis) > 1e-12 ? normalized(axis) : Vec3{0, 0, 1};
    // A joint made or removed changes what holds its bodies: they wake to feel it.
    wake_island_of(w.reg, w.contact, def.a);
    wake_island_of(w.reg, w.contact, def.b);
    const Entity e = w.constraints.reg.create();
    w.constraints.reg.emplace(e, std::move(c));
    w.constraints.reg.emplace(e, ConstraintState{});
    return to_constraint(e);
}

void destroy_constraint(World& world, Constraint constraint)
{
    World::Impl& w = impl_of(world);
    SM_ASSERT(!w.locked, "constraints cannot be destroyed while the world steps");
    if (w.locked)
        return;
    if (const ConstraintModel* c = w.constraints.reg.find<ConstraintModel>(to_entity(constraint))) {
        wake_island_of(w.reg, w.contact, c->def.a);
        wake_island_of(w.reg, w.contact, c->def.b);
    }
    w.constraints.reg.destroy(to_entity(constraint));
}

bool world_valid(const World& world, Constraint constraint)
{
    return impl_of(world).constraints.reg.valid(to_entity(constraint));
}

std::vector<Constraint> world_constraints(const World& world)
{
    std::vector<Constraint> out;
    for (Entity e : impl_of(world).constraints.reg.store<ConstraintModel>().entities())
        out.push_back(to_constraint(e));
    std::sort(out.begin(), out.end(), [](Constraint x, Constraint y) { return x.index < y.index; });
    return out;
}

Constraint find_constraint(const World& world, std::string_view name)
{
    for (Constraint c : world_constraints(world))
        if (model_of(world, c)->def.name == name)
            return c;
    return Constraint{};
}

const ConstraintDef& constraint_def(const World& world, Constraint constraint)
{
    static const ConstraintDef k_none{};
    const ConstraintModel* m = model_of(world, constraint);
    return m != nullptr ? m->def : k_none;
}

ConstraintError constraint_error(const World& world, Constraint constraint)
{
    const ConstraintState* s = state_of(world, constraint);
    return s != nullptr ? s->error : ConstraintError{};
}

Vec3 constraint_force(const World& world, Constraint constraint)
{
    const ConstraintState* s = state_of(world, constraint);
    return s != nullptr ? s->force_on_a : Vec3{};
}

bool constraint_broken(const World& world, Constraint constraint)
{
    const ConstraintState* s = state_of(world, constraint);
    return s != nullptr && s->broken;
}

std::pair<Vec3, Vec3> constraint_anchors(const World& world, Constraint constraint)
{
    const ConstraintModel* c = model_of(world, constraint);
    if (c == nullptr)
        return {};
    // The material points, modal displacement included (what the springs hold together).
    const Vec3 a = body_deformed_point(world, c->def.a, c->local_a);
    if (c->def.b.is_null())
        return {a, c->local_b};
    return {a, body_deformed_point(world, c->def.b, c->local_b)};
}

double world_max_constraint_error(const World& world)
{
    return impl_of(world).constraints.max_error;
}

uint64_t world_broken_constraints(const World& world)
{
    return impl_of(world).constraints.broken_count;
}

} // namespace supermodal
