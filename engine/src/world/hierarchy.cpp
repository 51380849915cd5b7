// SPDX-License-Identifier: MIT
// Part hierarchies and run-time part edits (hierarchy.h).
#include "supermodal/hierarchy.h"

#include "constraints/constraint_world.h"
#include "core/assert.h"
#include "supermodal/body.h"
#include "world/world_impl.h"

#include <algorithm>

namespace supermodal
{
namespace
{

Entity parent_of(const ConstraintWorld& cw, Entity e)
{
    return e.index < cw.parent.size() ? cw.parent[e.index] : Entity{};
}

} // namespace

Status set_body_parent(World& world, Entity child, Entity parent)
{
    World::Impl& w = impl_of(world);
    if (w.locked)
        return Error{"", "parent", "the hierarchy cannot change while the world steps"};
    if (!w.reg.valid(child) || (!parent.is_null() && !w.reg.valid(parent)))
        return Error{"", "parent", "stale or null body handle"};
    for (Entity p = parent; !p.is_null(); p = parent_of(w.constraints, p))
        if (p == child)
            return Error{"", "parent", "a body cannot be its own ancestor"};
    if (w.constraints.parent.size() <= child.index)
        w.constraints.parent.resize(child.index + 1);
    w.constraints.parent[child.index] = parent;
    // The link turns collision between the two off: they wake to let go of each other.
    wake_island_of(w.reg, w.contact, child);
    wake_island_of(w.reg, w.contact, parent);
    return {};
}

Entity body_parent(const World& world, Entity body)
{
    SM_ASSERT(world_valid(world, body), "stale or null body handle");
    return parent_of(impl_of(world).constraints, body);
}

std::vector<Entity> body_children(const World& world, Entity body)
{
    std::vector<Entity> out;
    for (Entity e : world_bodies(world))
        if (parent_of(impl_of(world).constraints, e) == body)
            out.push_back(e);
    return out;
}

std::vector<Entity> assembly_of(const World& world, Entity root)
{
    std::vector<Entity> out;
    if (!world_valid(world, root))
        return out;
    for (Entity e : world_bodies(world))
        for (Entity p = e; !p.is_null(); p = parent_of(impl_of(world).constraints, p))
            if (p == root) {
                out.push_back(e);
                break;
            }
    return out;
}

void move_assembly(World& world, Entity root, const Vec3& position, const Quat& orientation)
{
    SM_ASSERT(world_valid(world, root) && is_finite(position) && norm(orientation) > 0.0,
              "move_assembly needs a live body and a finite pose");
    if (!world_valid(world, root) || !is_finite(position) || !(norm(orientation) > 0.0))
        return;
    // The rigid map x → position + R·(x − origin), with R the change of root's orientation.
    const Vec3 origin = body_position(world, root);
    const Quat turn = normalized(orientation) * conjugate(body_orientation(world, root));
    for (Entity e : assembly_of(world, root)) {
        const Vec3 p = position + rotate(turn, body_position(world, e) - origin);
        const Quat q = normalized(turn * body_orientation(world, e));
        const Vec3 v = rotate(turn, body_linear_velocity(world, e));
        const Vec3 wv = rotate(turn, body_angular_velocity(world, e));
        set_body_orientation(world, e, q);
        set_body_position(world, e, p);
        if (body_motion(world, e) != MotionType::Static) {
            set_body_linear_velocity(world, e, v);
            set_body_angular_velocity(world, e, wv);
        }
    }
}

Status set_body_shape(World& world, Entity body, const ShapeDef& shape)
{
    World::Impl& w = impl_of(world);
    if (w.locked)
        return Error{"", "shape", "a shape cannot change while the world steps"};
    if (!w.reg.valid(body))
        return Error{"", "shape", "stale or null body handle"};
    if (Status s = validate(shape); !s)
        return s;
    if (w.reg.has<ModalBody>(body))
        return Error{"", "shape", "a modal body cannot be reshaped yet (its modes would need rebuilding)"};
    wake_island_of(w.reg, w.contact, body);
    BodyModel& m = w.reg.get<BodyModel>(body);
    if ((m.shape.type == ShapeType::Plane) != (shape.type == ShapeType::Plane))
        return Error{"", "shape/type", "a plane cannot become a solid or the other way round"};
    // Keep the shape origin where it is: the pose tracks the centre of mass, which may move.
    const Vec3 origin = body_position(world, body);
    const double density = m.mass.volume > 0.0 ? m.mass.mass / m.mass.volume : 0.0;
    m.shape = shape;
    set_mass_model(m, shape, density > 0.0 ? density : 1000.0);
    m.collider = collider_for(w, shape, m.mass.center_of_mass);
    requery_pairs_of(w.contact, body); // their stored points lay on the old surface
    Pose& p = w.reg.get<Pose>(body);
    p.position = origin + rotate(p.orientation, m.mass.center_of_mass);
    p.prev_position = p.position;
    refresh_anchors(w.constraints, body, w.reg.get<BodyModel>(body).shape);
    return {};
}

} // namespace supermodal
