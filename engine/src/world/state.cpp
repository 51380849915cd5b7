// SPDX-License-Identifier: MIT
// Hash, snapshot and restore cover exactly the dynamic state (STYLE.md 2.4), walked in entity-index
// order so the result does not depend on component-store history.
#include "modal/modal_world.h"
#include "supermodal/world.h"
#include "world/world_impl.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace supermodal
{
namespace
{

// FNV-1a, 64 bit (Fowler–Noll–Vo): offset basis and prime from the reference definition.
constexpr uint64_t k_fnv_offset = 14695981039346656037ull;
constexpr uint64_t k_fnv_prime = 1099511628211ull;

struct Fnv {
    uint64_t h = k_fnv_offset;
    void bytes(const void* data, size_t n)
    {
        const auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < n; ++i) {
            h ^= p[i];
            h *= k_fnv_prime;
        }
    }
    void f64(double v) { bytes(&v, sizeof v); }
    void u64(uint64_t v) { bytes(&v, sizeof v); }
};

// The packed layout of one body in a Snapshot; k_values_per_body doubles.
void pack(const World::Impl& w, Entity e, std::vector<double>& out)
{
    const Pose& p = w.reg.get<Pose>(e);
    const Velocity& v = w.reg.get<Velocity>(e);
    const ForceAccumulator& f = w.reg.get<ForceAccumulator>(e);
    const double values[k_values_per_body] = {p.position.x,
                                              p.position.y,
                                              p.position.z,
                                              p.orientation.w,
                                              p.orientation.x,
                                              p.orientation.y,
                                              p.orientation.z,
                                              p.prev_position.x,
                                              p.prev_position.y,
                                              p.prev_position.z,
                                              p.prev_orientation.w,
                                              p.prev_orientation.x,
                                              p.prev_orientation.y,
                                              p.prev_orientation.z,
                                              v.linear.x,
                                              v.linear.y,
                                              v.linear.z,
                                              v.angular.x,
                                              v.angular.y,
                                              v.angular.z,
                                              f.force.x,
                                              f.force.y,
                                              f.force.z,
                                              f.torque.x,
                                              f.torque.y,
                                              f.torque.z};
    out.insert(out.end(), values, values + k_values_per_body);
}

void unpack(World::Impl& w, Entity e, const double* in)
{
    Pose& p = w.reg.get<Pose>(e);
    Velocity& v = w.reg.get<Velocity>(e);
    ForceAccumulator& f = w.reg.get<ForceAccumulator>(e);
    p.position = {in[0], in[1], in[2]};
    p.orientation = {in[3], in[4], in[5], in[6]};
    p.prev_position = {in[7], in[8], in[9]};
    p.prev_orientation = {in[10], in[11], in[12], in[13]};
    v.linear = {in[14], in[15], in[16]};
    v.angular = {in[17], in[18], in[19]};
    f.force = {in[20], in[21], in[22]};
    f.torque = {in[23], in[24], in[25]};
}

void pack_constraint(const ConstraintState& c, std::vector<double>& out)
{
    const double values[k_values_per_constraint] = {
        c.broken ? 1.0 : 0.0, c.impulse.x,          c.impulse.y,          c.impulse.z,
        c.ang_impulse.x,      c.ang_impulse.y,      c.ang_impulse.z,      c.limit_impulse[0].x,
        c.limit_impulse[0].y, c.limit_impulse[0].z, c.limit_impulse[1].x, c.limit_impulse[1].y,
        c.limit_impulse[1].z};
    out.insert(out.end(), values, values + k_values_per_constraint);
}

void unpack_constraint(const double* in, ConstraintState& c)
{
    c.broken = in[0] != 0.0;
    c.impulse = {in[1], in[2], in[3]};
    c.ang_impulse = {in[4], in[5], in[6]};
    c.limit_impulse[0] = {in[7], in[8], in[9]};
    c.limit_impulse[1] = {in[10], in[11], in[12]};
}

} // namespace

uint64_t World::state_hash() const
{
    const Impl& w = *m_impl;
    Fnv fnv;
    fnv.f64(w.time);
    fnv.u64(w.step_count);
    std::vector<double> values;
    values.reserve(k_values_per_body);
    w.reg.pool().for_each_alive([&](Entity e) {
        if (!w.reg.has<Pose>(e))
            return;
        fnv.u64((uint64_t{e.index} << 32) | e.generation);
        values.clear();
        pack(w, e, values);
        // Previous pose and pending forces are left out: the hash is of where bodies are and how they move.
        for (size_t i : {0, 1, 2, 3, 4, 5, 6, 14, 15, 16, 17, 18, 19})
            fnv.f64(values[i]);
        if (w.reg.has<ModalBody>(e)) {
            const ModalBody& b = w.reg.get<ModalBody>(e);
            for (size_t k = 0; k < b.q.size(); ++k) {
                fnv.f64(b.q[k]);
                fnv.f64(b.q_dot[k]);
            }
            if (b.plastic.plastic()) { // elastic bodies keep the hash they had before plasticity existed
                for (const double v : b.q_plastic)
                    fnv.f64(v);
                fnv.f64(b.plastic_strain);
            }
            if (b.adaptive_tolerance > 0.0) // the others step every mode, as before adaptive modes
                fnv.u64(b.active);
        }
    });
    for (const PairAnchor& a : w.contact.anchors) {
        fnv.u64(a.key);
        fnv.f64(a.spring.x);
        fnv.f64(a.spring.y);
        fnv.f64(a.spring.z);
        fnv.f64(a.twist);
        fnv.f64(a.roll.x);
        fnv.f64(a.roll.y);
        fnv.f64(a.roll.z);
        fnv.f64(a.stiffness);
        fnv.f64(a.credit);
    }
    for (const PairManifold& m : w.contact.manifolds) {
        fnv.u64(m.key);
        fnv.u64(static_cast<uint64_t>(m.count));
        for (int i = 0; i < m.count; ++i)
            for (const Vec3& p : {m.points[i].local_a, m.points[i].local_b}) {
                fnv.f64(p.x);
                fnv.f64(p.y);
                fnv.f64(p.z);
            }
    }
    w.constraints.reg.pool().for_each_alive([&](Entity e) {
        fnv.u64((uint64_t{e.index} << 32) | e.generation);
        values.clear();
        pack_constraint(w.constraints.reg.get<ConstraintState>(e), values);
        for (double v : values)
            fnv.f64(v);
    });
    return fnv.h;
}

Snapshot World::snapshot() const
{
    const Impl& w = *m_impl;
    Snapshot s;
    s.time = w.time;
    s.step_count = w.step_count;
    s.accumulator = w.accumulator;
    w.reg.pool().for_each_alive([&](Entity e) {
        if (!w.reg.has<Pose>(e))
            return;
        s.entities.push_back(e);
        pack(w, e, s.values);
        if (w.reg.has<ModalBody>(e)) {
            const ModalBody& b = w.reg.get<ModalBody>(e);
            s.modal_values.insert(s.modal_values.end(), b.q.begin(), b.q.end());
            s.modal_values.insert(s.modal_values.end(), b.q_dot.begin(), b.q_dot.end());
            s.modal_values.insert(s.modal_values.end(), b.host_force.begin(), b.host_force.end());
            s.modal_values.insert(s.modal_values.end(), b.q_plastic.begin(), b.q_plastic.end());
            s.modal_values.push_back(b.plastic_strain);
            s.modal_values.push_back(static_cast<double>(b.active));
        }
    });
    for (const PairAnchor& a : w.contact.anchors) {
        s.anchor_keys.push_back(a.key);
        s.anchor_springs.push_back(a.spring);
        s.anchor_twists.push_back(a.twist);
        s.anchor_rolls.push_back(a.roll);
        s.anchor_stiffness.push_back(a.stiffness);
        s.anchor_credits.push_back(a.credit);
    }
    for (const PairManifold& m : w.contact.manifolds) {
        s.manifold_keys.push_back(m.key);
        s.manifold_counts.push_back(m.count);
        for (int i = 0; i < m.count; ++i) {
            s.manifold_points.push_back(m.points[i].local_a);
            s.manifold_points.push_back(m.points[i].local_b);
        }
    }
    w.constraints.reg.pool().for_each_alive([&](Entity e) {
        s.constraints.push_back(e);
        pack_constraint(w.constraints.reg.get<ConstraintState>(e), s.constraint_values);
    });
    s.broken_constraint_count = w.constraints.broken_count;
    return s;
}

Status World::restore(const Snapshot& s)
{
    Impl& w = *m_impl;
    if (s.values.size() != s.entities.size() * k_values_per_body ||
        s.anchor_keys.size() != s.anchor_springs.size() || s.anchor_keys.size() != s.anchor_twists.size() ||
        s.anchor_keys.size() != s.anchor_rolls.size() || s.anchor_keys.size() != s.anchor_stiffness.size() ||
        s.anchor_keys.size() != s.anchor_credits.size())
        return Error{"", "snapshot", "corrupt snapshot: value count does not match its bodies"};
    size_t manifold_points = 0;
    for (int count : s.manifold_counts) {
        if (count < 0 || count > PairManifold::k_capacity)
            return Error{"", "snapshot", "corrupt snapshot: a contact manifold has a bad point count"};
        manifold_points += 2 * static_cast<size_t>(count);
    }
    if (s.manifold_counts.size() != s.manifold_keys.size() || s.manifold_points.size() != manifold_points)
        return Error{"", "snapshot", "corrupt snapshot: manifold points do not match their counts"};
    std::vector<Entity> live;
    w.reg.pool().for_each_alive([&](Entity e) {
        if (w.reg.has<Pose>(e))
            live.push_back(e);
    });
    if (live != s.entities)
        return Error{"", "snapshot", "bodies were created or destroyed since this snapshot was taken"};
    std::vector<Entity> live_constraints;
    w.constraints.reg.pool().for_each_alive([&](Entity e) { live_constraints.push_back(e); });
    if (live_constraints != s.constraints ||
        s.constraint_values.size() != s.constraints.size() * k_values_per_constraint)
        return Error{"", "snapshot", "constraints were created or destroyed since this snapshot was taken"};
    for (size_t i = 0; i < live_constraints.size(); ++i)
        unpack_constraint(s.constraint_values.data() + i * k_values_per_constraint,
                          w.constraints.reg.get<ConstraintState>(live_constraints[i]));
    w.constraints.broken_count = s.broken_constraint_count;
    size_t modal_count = 0;
    for (Entity e : live)
        if (w.reg.has<ModalBody>(e))
            modal_count += 4 * w.reg.get<ModalBody>(e).q.size() + 2;
    if (modal_count != s.modal_values.size())
        return Error{"", "snapshot", "corrupt snapshot: modal value count does not match its bodies"};
    for (size_t i = 0; i < live.size(); ++i)
        unpack(w, live[i], s.values.data() + i * k_values_per_body);
    for (const double* modal = s.modal_values.data(); Entity e : live)
        if (const ModalBody* b = w.reg.find<ModalBody>(e)) {
            const double active = modal[4 * b->q.size() + 1];
            if (!(active >= 0.0 && active <= static_cast<double>(b->q.size())) ||
                active != std::floor(active))
                return Error{"", "snapshot", "corrupt snapshot: an active mode count is out of range"};
            modal += 4 * b->q.size() + 2;
        }
    const double* modal = s.modal_values.data();
    for (Entity e : live) {
        ModalBody* b = w.reg.find<ModalBody>(e);
        if (b == nullptr)
            continue;
        const size_t r = b->q.size();
        b->q.assign(modal, modal + r);
        b->q_dot.assign(modal + r, modal + 2 * r);
        b->host_force.assign(modal + 2 * r, modal + 3 * r);
        b->q_plastic.assign(modal + 3 * r, modal + 4 * r);
        b->plastic_strain = modal[4 * r];
        set_active_modes(*b, static_cast<size_t>(modal[4 * r + 1]));
        modal += 4 * r + 2;
        // The last substep's loads (accuracy report) are not state: the report starts afresh.
        std::fill(b->last_nodal_load.begin(), b->last_nodal_load.end(), 0.0);
        std::fill(b->last_load.begin(), b->last_load.end(), 0.0);
        b->last_has_load = false;
        update_modal_surface(*b);
    }
    w.contact.anchors.clear();
    for (size_t i = 0; i < s.anchor_keys.size(); ++i)
        w.contact.anchors.push_back({s.anchor_keys[i], s.anchor_springs[i], s.anchor_twists[i],
                                     s.anchor_rolls[i], s.anchor_stiffness[i], s.anchor_credits[i]});
    w.contact.manifolds.clear();
    for (size_t i = 0, next = 0; i < s.manifold_keys.size(); ++i) {
        PairManifold m{.key = s.manifold_keys[i], .count = s.manifold_counts[i]};
        for (int j = 0; j < m.count; ++j, next += 2)
            m.points[j] = {s.manifold_points[next], s.manifold_points[next + 1]};
        w.contact.manifolds.push_back(m);
    }
    w.time = s.time;
    w.step_count = s.step_count;
    w.accumulator = s.accumulator;
    return {};
}

} // namespace supermodal
