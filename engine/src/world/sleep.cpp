// SPDX-License-Identifier: MIT
#include "world/sleep.h"

#include "world/integrate.h"

#include <algorithm>
#include <limits>

namespace supermodal
{
namespace
{

// What a body is to sleeping, per entity index.
enum SleepClass : uint8_t {
    k_fixed = 0,  ///< Static, stationary kinematic, or no body: neither wakes nor sleeps.
    k_awake = 1,  ///< Awake dynamic body.
    k_asleep = 2, ///< Sleeping dynamic body.
    k_moving = 3, ///< Kinematic body with a velocity: wakes what it reaches, never sleeps.
};

bool moving(const Velocity& v)
{
    return v.linear != Vec3{} || v.angular != Vec3{};
}

// Each body writes only its own byte (by entity index), so any threads give the same classes.
void classify_bodies(Registry& reg, std::vector<uint8_t>& out, const Parallel& par = Parallel{})
{
    out.assign(reg.pool().slot_count(), k_fixed);
    par.for_parts(reg.store<BodyModel>().size(), k_min_bodies_per_part,
                  [&](size_t, size_t begin, size_t end) {
                      reg.each_in<BodyModel, Sleep, Velocity>(
                          begin, end, [&](Entity e, const BodyModel& m, const Sleep& s, const Velocity& v) {
                              if (m.motion == MotionType::Dynamic)
                                  out[e.index] = s.asleep ? k_asleep : k_awake;
                              else if (m.motion == MotionType::Kinematic && moving(v))
                                  out[e.index] = k_moving;
                          });
                  });
}

uint8_t class_of(const std::vector<uint8_t>& classes, uint64_t index)
{
    return index < classes.size() ? classes[index] : uint8_t{k_fixed};
}

// A pair to park: one end sleeps and no end is awake (the other sleeps too, or is fixed).
bool sleeping_key(const std::vector<uint8_t>& classes, uint64_t key)
{
    const auto [ia, ib] = pair_key_indices(key);
    const uint8_t a = class_of(classes, ia), b = class_of(classes, ib);
    return (a == k_asleep || b == k_asleep) && a != k_awake && b != k_awake && a != k_moving && b != k_moving;
}

// Moves the entries of `from` whose key `pick` accepts into `to`; both stay sorted by key.
template <class T, class Pick> void move_entries(std::vector<T>& from, std::vector<T>& to, Pick pick)
{
    const size_t kept = to.size();
    for (const T& x : from)
        if (pick(x.key))
            to.push_back(x);
    if (to.size() == kept)
        return;
    std::erase_if(from, [&](const T& x) { return pick(x.key); });
    std::inplace_merge(to.begin(), to.begin() + static_cast<std::ptrdiff_t>(kept), to.end(),
                       [](const T& x, const T& y) { return x.key < y.key; });
}

void park(Registry& reg, ContactWorld& io)
{
    ParkedContacts& p = io.parked;
    classify_bodies(reg, p.body_class);
    auto sleeping = [&](uint64_t key) { return sleeping_key(p.body_class, key); };
    move_entries(io.anchors, p.anchors, sleeping);
    move_entries(io.manifolds, p.manifolds, sleeping);
    move_entries(io.events.touching, p.touching, sleeping);
}

// Brings back the parked contacts of pairs that no longer sleep; leaves body_class current.
void unpark(Registry& reg, ContactWorld& io)
{
    ParkedContacts& p = io.parked;
    classify_bodies(reg, p.body_class);
    auto woken = [&](uint64_t key) { return !sleeping_key(p.body_class, key); };
    move_entries(p.anchors, io.anchors, woken);
    move_entries(p.manifolds, io.manifolds, woken);
    move_entries(p.touching, io.events.touching, woken);
}

// Wakes every body whose island is in `ids` (emptied), restarting their timers.
void wake_islands(Registry& reg, ContactWorld& io, std::vector<uint32_t>& ids)
{
    if (ids.empty())
        return;
    std::sort(ids.begin(), ids.end());
    reg.each<Sleep>([&](Entity, Sleep& s) {
        if (s.asleep && std::binary_search(ids.begin(), ids.end(), s.island))
            s = Sleep{};
    });
    ids.clear();
    unpark(reg, io);
}

// Notes the island of `sleeper` when `other` may push it this step.
void note_reached(const Registry& reg, const std::vector<uint8_t>& classes, Entity sleeper, Entity other,
                  std::vector<uint32_t>& ids)
{
    const uint8_t o = class_of(classes, other.index);
    if (class_of(classes, sleeper.index) == k_asleep && (o == k_awake || o == k_moving))
        ids.push_back(reg.get<Sleep>(sleeper).island);
}

} // namespace

void wake_island_of(Registry& reg, ContactWorld& io, Entity body)
{
    Sleep* s = reg.find<Sleep>(body);
    if (s == nullptr)
        return;
    if (s->asleep) {
        io.parked.wake.assign(1, s->island);
        wake_islands(reg, io, io.parked.wake);
    }
    s->timer = 0.0;
}

void wake_every_body(Registry& reg, ContactWorld& io)
{
    bool any = false;
    reg.each<Sleep>([&](Entity, Sleep& s) {
        if (s.asleep) {
            any = true;
            s = Sleep{};
        }
    });
    if (any)
        unpark(reg, io);
}

void wake_jointed(const ConstraintWorld& cw, const Parallel& par, Registry& reg, ContactWorld& io)
{
    ParkedContacts& p = io.parked;
    const std::vector<Entity>& constraints = cw.reg.store<ConstraintModel>().entities();
    classify_bodies(reg, p.body_class, par);
    // To a fixed point: a woken island may hold a joint to another sleeping one.
    for (;;) {
        p.wake.clear();
        for (Entity c : constraints) {
            if (cw.reg.get<ConstraintState>(c).broken)
                continue;
            const ConstraintDef& d = cw.reg.get<ConstraintModel>(c).def;
            note_reached(reg, p.body_class, d.a, d.b, p.wake);
            note_reached(reg, p.body_class, d.b, d.a, p.wake);
        }
        if (p.wake.empty())
            return;
        wake_islands(reg, io, p.wake);
    }
}

bool settle_sleeping_pairs(const Parallel& par, Registry& reg, ContactWorld& io)
{
    ParkedContacts& p = io.parked;
    classify_bodies(reg, p.body_class, par);
    p.wake.clear();
    for (const BodyPair& pair : io.pairs) {
        note_reached(reg, p.body_class, pair.a, pair.b, p.wake);
        note_reached(reg, p.body_class, pair.b, pair.a, p.wake);
    }
    if (!p.wake.empty()) {
        wake_islands(reg, io, p.wake);
        return true;
    }
    // With nobody asleep every pair has an awake dynamic end, so this drops nothing.
    std::erase_if(io.pairs, [&](const BodyPair& pair) {
        return class_of(p.body_class, pair.a.index) != k_awake &&
               class_of(p.body_class, pair.b.index) != k_awake;
    });
    return false;
}

namespace
{

// Slow enough to sleep: its fastest point, |v| + ρ·|ω| with ρ its largest radius (Box2D v3's rule, so a
// small body may turn faster than a large one), under the linear limit; |ω| under the angular one; and
// for a modal body the modes' kinetic energy ½|q̇|² (q̇ in √kg·m/s) under the body's at the linear
// limit, ½·m·v².
bool is_slow(const SleepDef& d, const BodyModel& m, const Velocity& v, const ModalBody* modal)
{
    const double lin2 = d.linear_speed * d.linear_speed;
    const double spin = length(v.angular);
    const double reach = std::max({m.shape.radii.x, m.shape.radii.y, m.shape.radii.z});
    if (!m.allow_sleep || !(length(v.linear) + reach * spin < d.linear_speed) || !(spin < d.angular_speed))
        return false;
    if (modal == nullptr)
        return true;
    double energy2 = 0.0;
    for (double rate : modal->state.q_dot)
        energy2 += rate * rate;
    return energy2 < lin2 * m.mass.mass;
}

// Each awake dynamic body's timer on any thread (it writes only its own); returns whether any has run
// for the sleep time, without which no island can fall asleep this step. Then, on this thread, a body
// that a moving kinematic body carries or pushes stays awake with it.
bool update_timers(const WorldDef& def, const Parallel& par, Registry& reg, const ContactWorld& io,
                   std::vector<uint8_t>& ripe)
{
    ripe.assign(par.part_capacity(), 0);
    par.for_parts(
        reg.store<BodyModel>().size(), k_min_bodies_per_part, [&](size_t part, size_t begin, size_t end) {
            bool any = false; // one write per part: the parts' bytes share a cache line
            reg.each_in<BodyModel, Velocity, Sleep>(
                begin, end, [&](Entity e, const BodyModel& m, const Velocity& v, Sleep& s) {
                    if (m.motion != MotionType::Dynamic || s.asleep)
                        return;
                    s.timer = is_slow(def.sleep, m, v, reg.find<ModalBody>(e)) ? s.timer + def.dt : 0.0;
                    any = any || s.timer >= def.sleep.time;
                });
            ripe[part] = any ? 1 : 0;
        });
    const std::vector<uint8_t>& classes = io.parked.body_class;
    if (std::find(classes.begin(), classes.end(), uint8_t{k_moving}) != classes.end())
        for (const ContactInfo& c : io.contacts) {
            if (class_of(classes, c.a.index) == k_moving)
                reg.get<Sleep>(c.b).timer = 0.0;
            if (class_of(classes, c.b.index) == k_moving)
                reg.get<Sleep>(c.a).timer = 0.0;
        }
    return std::find(ripe.begin(), ripe.end(), uint8_t{1}) != ripe.end();
}

// Islands of the awake dynamic bodies, linked by the last substep's touching pairs and the unbroken
// constraints; anything else at a row's end (static, kinematic) links nothing.
void link_islands(const ContactWorld& io, const ConstraintWorld& cw, IslandBuilder& islands)
{
    const std::vector<uint8_t>& classes = io.parked.body_class;
    auto node = [&](Entity e) { return class_of(classes, e.index) == k_awake ? e.index : k_no_node; };
    islands.clear();
    for (const ContactInfo& c : io.contacts)
        islands.add_row(node(c.a), node(c.b));
    for (Entity c : cw.reg.store<ConstraintModel>().entities()) {
        if (cw.reg.get<ConstraintState>(c).broken)
            continue;
        const ConstraintDef& d = cw.reg.get<ConstraintModel>(c).def;
        islands.add_row(node(d.a), node(d.b));
    }
}

// The islands whose every body has been slow for the sleep time fall asleep, at rest.
bool fall_asleep(const WorldDef& def, Registry& reg, SleepScratch& scratch)
{
    std::vector<double>& timers = scratch.island_timer;
    timers.assign(reg.pool().slot_count(), std::numeric_limits<double>::infinity());
    reg.each<BodyModel, Sleep>([&](Entity e, const BodyModel& m, const Sleep& s) {
        if (m.motion == MotionType::Dynamic && !s.asleep) {
            double& t = timers[scratch.islands.root(e.index)];
            t = std::min(t, s.timer);
        }
    });
    bool fell = false;
    reg.each<BodyModel, Sleep, Velocity>([&](Entity e, const BodyModel& m, Sleep& s, Velocity& v) {
        const uint32_t root = scratch.islands.root(e.index);
        if (m.motion != MotionType::Dynamic || s.asleep || !(timers[root] >= def.sleep.time))
            return;
        s.asleep = true;
        s.island = root; // the lowest index: IslandBuilder keeps the smaller root
        v = Velocity{};
        if (ModalBody* b = reg.find<ModalBody>(e))
            std::fill(b->state.q_dot.begin(), b->state.q_dot.end(), 0.0);
        fell = true;
    });
    return fell;
}

} // namespace

size_t update_sleep(const WorldDef& def, const Parallel& par, Registry& reg, ContactWorld& io,
                    const ConstraintWorld& cw, SleepScratch& scratch)
{
    if (!def.sleep.enabled)
        return 0;
    classify_bodies(reg, io.parked.body_class, par);
    // An island sleeps when its shortest timer has run, so no timer run means no island to build.
    if (update_timers(def, par, reg, io, scratch.ripe)) {
        link_islands(io, cw, scratch.islands);
        if (fall_asleep(def, reg, scratch))
            park(reg, io);
    }
    size_t asleep = 0;
    for (const Sleep& s : reg.store<Sleep>().values())
        asleep += s.asleep ? 1 : 0;
    return asleep;
}

} // namespace supermodal
