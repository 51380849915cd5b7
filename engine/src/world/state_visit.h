// SPDX-License-Identifier: MIT
// The dynamic state of a world, listed once. visit_state() walks every field in one fixed order (entity
// index order, so component-store history cannot matter) and hands each to a visitor, tagged Hashed
// (where bodies are and how they move) or Saved (also needed to continue bit for bit: previous pose,
// pending host forces, counts). The hash, the snapshot writer and the restore reader are three visitors
// of this one list, so a new state field is added in one place and all three follow.
//
// A visitor provides: real(double&, Field), integer(T&, Field), flag(bool&, Field), check(bool, what)
// (false stops a reader with that error) and sequence(container, Field) (a length; a reader resizes).
#pragma once

#include "world/world_impl.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace supermodal
{

enum class Field : uint8_t {
    Hashed, ///< In the state hash and in snapshots.
    Saved,  ///< In snapshots only.
};

/// Bump when the order or meaning of the visited fields changes: old snapshots are then refused.
inline constexpr uint32_t k_snapshot_layout_version = 7;

[[nodiscard]] inline uint64_t entity_key(Entity e)
{
    return (uint64_t{e.index} << 32) | e.generation;
}

template <class V, class T> void visit_vec3(V& v, T& x, Field f)
{
    v.real(x.x, f);
    v.real(x.y, f);
    v.real(x.z, f);
}

template <class V, class T> void visit_quat(V& v, T& q, Field f)
{
    v.real(q.w, f);
    v.real(q.x, f);
    v.real(q.y, f);
    v.real(q.z, f);
}

/// A list of handles that must match the world's own (creation and destruction are not state), each
/// followed by what fields(e) visits.
template <class V, class Fields>
void visit_each(V& v, const std::vector<Entity>& live, const char* mismatch, Fields&& fields)
{
    uint64_t count = live.size();
    v.integer(count, Field::Saved);
    if (!v.check(count == live.size(), mismatch))
        return;
    for (Entity e : live) {
        uint64_t key = entity_key(e);
        v.integer(key, Field::Hashed);
        if (!v.check(key == entity_key(e), mismatch))
            return;
        fields(e);
    }
}

/// A modal body's state (ModalState); which fields are hashed depends on its model.
template <class V, class S> void visit_modal(V& v, S& s, const ModalModel& m)
{
    const size_t r = s.q.size();
    uint64_t modes = r;
    v.integer(modes, Field::Saved);
    if (!v.check(modes == r, "corrupt snapshot: a modal body's mode count differs"))
        return;
    for (size_t k = 0; k < r; ++k) {
        v.real(s.q[k], Field::Hashed);
        v.real(s.q_dot[k], Field::Hashed);
    }
    for (size_t k = 0; k < r; ++k)
        v.real(s.host_force[k], Field::Saved);
    // Elastic bodies keep the hash they had before plasticity existed; bodies that step every mode, the
    // one from before adaptive modes.
    const Field plastic = m.plastic.plastic() ? Field::Hashed : Field::Saved;
    for (size_t k = 0; k < r; ++k)
        v.real(s.q_plastic[k], plastic);
    v.real(s.plastic_strain, plastic);
    v.integer(s.active, m.adaptive() ? Field::Hashed : Field::Saved);
    v.check(s.active <= r, "corrupt snapshot: an active mode count is out of range");
    // Remoulding: the moulded rest shape is hashed (empty, as for every body that was never remoulded,
    // it adds nothing); a pending rebuild is saved so that restore asks for it again.
    for (auto& x : v.sequence(s.rest_offsets, Field::Saved))
        v.real(x, Field::Hashed);
    v.integer(s.remould_step, Field::Saved);
    for (auto& x : v.sequence(s.remould_q_plastic, Field::Saved))
        v.real(x, Field::Saved);
    v.flag(s.remould_failed, Field::Saved);
    v.check(s.remould_q_plastic.size() == (s.remould_step != 0 ? r : 0),
            "corrupt snapshot: a pending remould has the wrong mode count");
    // The static correction shapes the next substep's surface: hashed (empty, as for bodies without it,
    // it adds nothing).
    for (auto& x : v.sequence(s.correction, Field::Saved))
        v.real(x, Field::Hashed);
    for (auto& x : v.sequence(s.contact_correction, Field::Saved))
        v.real(x, Field::Hashed);
    v.check(s.correction.empty() == !m.static_correction &&
                s.contact_correction.size() == s.correction.size(),
            "corrupt snapshot: a modal body's static correction does not match its model");
}

template <class V, class W> void visit_bodies(V& v, W& w)
{
    std::vector<Entity> live;
    w.reg.pool().for_each_alive([&](Entity e) {
        if (w.reg.template has<Pose>(e))
            live.push_back(e);
    });
    visit_each(v, live, "bodies were created or destroyed since this snapshot was taken", [&](Entity e) {
        auto& p = w.reg.template get<Pose>(e);
        auto& vel = w.reg.template get<Velocity>(e);
        auto& force = w.reg.template get<ForceAccumulator>(e);
        visit_vec3(v, p.position, Field::Hashed);
        visit_quat(v, p.orientation, Field::Hashed);
        visit_vec3(v, p.prev_position, Field::Saved);
        visit_quat(v, p.prev_orientation, Field::Saved);
        visit_vec3(v, vel.linear, Field::Hashed);
        visit_vec3(v, vel.angular, Field::Hashed);
        visit_vec3(v, force.force, Field::Saved);
        visit_vec3(v, force.torque, Field::Saved);
        auto& sleep = w.reg.template get<Sleep>(e);
        v.real(sleep.timer, Field::Hashed);
        v.flag(sleep.asleep, Field::Hashed);
        v.integer(sleep.island, Field::Saved);
        if (auto* b = w.reg.template find<ModalBody>(e))
            visit_modal(v, b->state, *b->model);
    });
}

template <class V, class A> void visit_anchors(V& v, A& anchors)
{
    for (auto& a : v.sequence(anchors, Field::Saved)) {
        v.integer(a.key, Field::Hashed);
        visit_vec3(v, a.spring, Field::Hashed);
        v.real(a.twist, Field::Hashed);
        visit_vec3(v, a.roll, Field::Hashed);
        v.real(a.stiffness, Field::Hashed);
        v.real(a.credit, Field::Hashed);
        v.real(a.normal_load, Field::Hashed);
        visit_vec3(v, a.friction_load, Field::Hashed);
        visit_vec3(v, a.roll_load, Field::Hashed);
    }
}

template <class V, class M> void visit_manifolds(V& v, M& manifolds)
{
    for (auto& m : v.sequence(manifolds, Field::Saved)) {
        v.integer(m.key, Field::Hashed);
        v.integer(m.count, Field::Hashed);
        if (!v.check(m.count >= 0 && m.count <= PairManifold::k_capacity,
                     "corrupt snapshot: a contact manifold has a bad point count"))
            return;
        for (int i = 0; i < m.count; ++i) {
            visit_vec3(v, m.points[static_cast<size_t>(i)].local_a, Field::Hashed);
            visit_vec3(v, m.points[static_cast<size_t>(i)].local_b, Field::Hashed);
        }
        visit_vec3(v, m.normal, Field::Hashed); // where the next penetration search starts
        v.integer(m.steady, Field::Hashed);     // and whether it searches at all
        visit_vec3(v, m.query_offset, Field::Hashed);
        visit_quat(v, m.query_turn, Field::Hashed);
    }
}

template <class V, class W> void visit_contacts(V& v, W& w)
{
    visit_anchors(v, w.contact.anchors);
    visit_manifolds(v, w.contact.manifolds);
    // Sleeping pairs' contacts, which their bodies wake with.
    visit_anchors(v, w.contact.parked.anchors);
    visit_manifolds(v, w.contact.parked.manifolds);
}

template <class V, class W> void visit_constraints(V& v, W& w)
{
    std::vector<Entity> live;
    w.constraints.reg.pool().for_each_alive([&](Entity e) { live.push_back(e); });
    visit_each(v, live, "constraints were created or destroyed since this snapshot was taken", [&](Entity e) {
        auto& c = w.constraints.reg.template get<ConstraintState>(e);
        v.flag(c.broken, Field::Hashed);
        visit_vec3(v, c.impulse, Field::Hashed);
        visit_vec3(v, c.ang_impulse, Field::Hashed);
        visit_vec3(v, c.limit_impulse[0], Field::Hashed);
        visit_vec3(v, c.limit_impulse[1], Field::Hashed);
    });
    v.integer(w.constraints.broken_count, Field::Saved);
}

/// Every field of the state, in one fixed order. W is World::Impl (restore) or const World::Impl.
template <class V, class W> void visit_state(V& v, W& w)
{
    v.real(w.time, Field::Hashed);
    v.integer(w.step_count, Field::Hashed);
    v.real(w.accumulator, Field::Saved);
    visit_bodies(v, w);
    visit_contacts(v, w);
    visit_constraints(v, w);
}

} // namespace supermodal
