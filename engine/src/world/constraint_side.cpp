// SPDX-License-Identifier: MIT
#include "world/constraint_side.h"

#include "constraints/constraint_world.h"
#include "world/integrate.h"

#include <algorithm>
#include <cmath>

namespace supermodal
{

Mat3 world_inv_inertia(const BodyModel& m, const Pose& p)
{
    const Mat3 r = to_mat3(principal_orientation(m, p.orientation));
    return r * Mat3::diagonal(m.inv_inertia_body) * transpose(r);
}

bool invert(const Mat3& a, Mat3& out)
{
    const auto& m = a.m;
    const Vec3 c0{m[1][1] * m[2][2] - m[1][2] * m[2][1], m[1][2] * m[2][0] - m[1][0] * m[2][2],
                  m[1][0] * m[2][1] - m[1][1] * m[2][0]};
    const double det = m[0][0] * c0.x + m[0][1] * c0.y + m[0][2] * c0.z;
    double scale = 0.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            scale = std::max(scale, std::abs(m[i][j]));
    if (!(std::abs(det) > 1e-12 * scale * scale * scale) || !std::isfinite(det))
        return false;
    const double inv = 1.0 / det;
    out.m[0][0] = c0.x * inv;
    out.m[1][0] = c0.y * inv;
    out.m[2][0] = c0.z * inv;
    out.m[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * inv;
    out.m[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * inv;
    out.m[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * inv;
    out.m[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * inv;
    out.m[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * inv;
    out.m[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * inv;
    return true;
}

void make_side(Registry& bodies, Entity e, const Vec3& local, double h, bool with_rotation, Side& s)
{
    // Field by field rather than s = Side{}: the modal anchor keeps its buffers (modal_anchor() refills
    // them), so a warm step allocates nothing, and a row's sides are cheap to remake.
    s.m = nullptr;
    s.p = nullptr;
    s.v = nullptr;
    s.r = Vec3{};
    s.inv_inertia = Mat3{};
    s.inv_mass = 0.0;
    if (e.is_null() || !bodies.valid(e)) {
        s.point = local;
        s.modal.clear(); // the world has no modes
        return;
    }
    s.m = &bodies.get<BodyModel>(e);
    s.p = &bodies.get<Pose>(e);
    s.point = world_point(*s.m, *s.p, local);
    // A modal body's anchor rides on the deformed material (a surface anchor stays on the deformed
    // surface, as the contact samples do).
    ModalBody* modal = bodies.find<ModalBody>(e);
    if (modal != nullptr && modal_anchor(modal, s.p->orientation, local, h, with_rotation, s.modal.fill()))
        s.point += s.modal->displacement;
    else
        s.modal.clear();
    s.r = s.point - s.p->position;
    if (s.m->motion == MotionType::Dynamic) {
        s.v = &bodies.get<Velocity>(e);
        s.inv_mass = s.m->inv_mass;
        s.inv_inertia = world_inv_inertia(*s.m, *s.p);
    } else if (s.m->motion == MotionType::Kinematic) {
        s.v = &bodies.get<Velocity>(e); // moves, but takes no impulse (inv_mass 0)
    }
}

Side contact_side(Registry& bodies, Entity e, const Vec3& x, double h, const Mat3* inv_inertia)
{
    Side s;
    s.point = x;
    s.m = &bodies.get<BodyModel>(e);
    s.p = &bodies.get<Pose>(e);
    s.r = x - s.p->position;
    if (ModalBody* b = bodies.find<ModalBody>(e)) {
        // x carries the displacement already; φ at the displaced point differs from φ at the rest
        // point only to second order in the deformation.
        const Vec3 local = inv_rotate(s.p->orientation, s.r) + s.m->mass.center_of_mass;
        modal_anchor(b, s.p->orientation, local, h, false, s.modal.fill());
    }
    if (s.m->motion == MotionType::Dynamic) {
        s.v = &bodies.get<Velocity>(e);
        s.inv_mass = s.m->inv_mass;
        s.inv_inertia = inv_inertia != nullptr ? *inv_inertia : world_inv_inertia(*s.m, *s.p);
    } else if (s.m->motion == MotionType::Kinematic) {
        s.v = &bodies.get<Velocity>(e);
    }
    return s;
}

Quat anchor_orientation(const Side& s)
{
    if (s.p == nullptr)
        return Quat{};
    return s.modal.active() && !s.modal->psi.empty()
               ? normalized(quat_from_rotation_vector(s.modal->rotation) * s.p->orientation)
               : s.p->orientation;
}

Vec3 rigid_anchor_velocity(const Side& s)
{
    return s.v == nullptr ? Vec3{} : s.v->linear + cross(s.v->angular, s.r);
}

Vec3 anchor_velocity(const Side& s)
{
    Vec3 v = rigid_anchor_velocity(s);
    if (s.modal.active())
        v += modal_anchor_velocity(*s.modal);
    return v;
}

Vec3 angular_velocity(const Side& s)
{
    return s.v == nullptr ? Vec3{} : s.v->angular;
}

Vec3 anchor_spin(const Side& s)
{
    return s.modal.active() ? angular_velocity(s) + modal_anchor_spin(*s.modal) : angular_velocity(s);
}

namespace
{

// Whether the side's body was frozen (made immovable) since the side was made: a body that turned
// non-finite in one pass of the soft solver must not be moved by the rows' later passes, which would make
// it non-finite, and report it, again.
bool frozen_since(const Side& s)
{
    return s.m != nullptr && s.m->inv_mass == 0.0;
}

} // namespace

void push_rigid_spin(Side& s, const Vec3& angular_impulse)
{
    if (s.v != nullptr && s.inv_mass != 0.0 && !frozen_since(s))
        s.v->angular += s.inv_inertia * angular_impulse;
}

void push_rigid(Side& s, const Vec3& impulse)
{
    if (s.v == nullptr || s.inv_mass == 0.0 || frozen_since(s))
        return;
    s.v->linear += s.inv_mass * impulse;
    s.v->angular += s.inv_inertia * (cross(s.r, impulse) + Vec3{}); // as push() adds it, to the bit
}

void push(Side& s, const Vec3& impulse, const Vec3& angular_impulse)
{
    if (s.modal.active())
        modal_anchor_push(*s.modal, impulse, angular_impulse);
    if (s.v == nullptr || s.inv_mass == 0.0 || frozen_since(s))
        return;
    s.v->linear += s.inv_mass * impulse;
    s.v->angular += s.inv_inertia * (cross(s.r, impulse) + angular_impulse);
}

// K = (1/ma + 1/mb)·I − [ra]× Ia⁻¹ [ra]× − [rb]× Ib⁻¹ [rb]× + Σ φφᵀ over both bodies' modes.
Mat3 point_mass_inverse(const Side& a, const Side& b)
{
    Mat3 k = Mat3::diagonal({1, 1, 1});
    for (int i = 0; i < 3; ++i)
        k.m[i][i] = a.inv_mass + b.inv_mass;
    for (const Side* s : {&a, &b}) {
        if (s->inv_mass > 0.0)
            k = add_scaled(k, skew(s->r) * s->inv_inertia * skew(s->r), -1.0);
        if (s->modal.active())
            k = add_scaled(k, modal_anchor_inverse_mass(*s->modal), 1.0);
    }
    return k;
}

Mat3 anchor_inertia_inverse(const Side& a, const Side& b)
{
    Mat3 k = add_scaled(a.inv_inertia, b.inv_inertia, 1.0);
    for (const Side* s : {&a, &b})
        if (s->modal.active())
            k = add_scaled(k, modal_anchor_inverse_inertia(*s->modal), 1.0);
    return k;
}

} // namespace supermodal
