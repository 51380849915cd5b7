// SPDX-License-Identifier: MIT
#include "world/contact_system.h"

#include "core/parallel.h"
#include "world/integrate.h"
#include "world/modal_system.h"
#include "world/sleep.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

namespace supermodal
{
namespace
{

// Penalty frequency cap relative to the substep rate: ω·h = 2π/10 ≈ 0.63 keeps semi-implicit Euler
// (stable to ω·h < 2) stable with room for a body pressed by several contacts (Box2D v3 caps alike).
constexpr double k_frequency_cap_per_rate = 0.1;
// Fewest pairs worth a thread part: below this, waking a worker costs more than the pairs.
constexpr size_t k_min_pairs_per_part = 32;
// Largest share of the thinner body the penalty spring may need to stop an approach (stopping rule).
constexpr double k_stop_fraction = 0.5;
Aabb body_box(const BodyModel& m, const Pose& p)
{
    const Vec3 origin = p.position - rotate(p.orientation, m.collider->com_shape);
    return world_aabb(m.shape, origin, p.orientation);
}

// fn(part, begin, end) over [0, count) on the static partition (contact/penalty.h: per-pair slots).
// The narrowphase's own loop splits where its measured times even out instead (collide_balance): a
// floor's pairs, first in key order, cost a third of a pile's, and even counts left one thread 20% more
// work on the 4000-ellipsoid pile. Its ranges stay contiguous and keep_manifolds' gather follows them,
// so a pair's manifold is written, gathered and read again next substep on one core (blocks of 16
// dealt round-robin moved the manifolds between the cores: ~6% slower against the solve).
template <class Fn> void for_parts(const Parallel& par, size_t count, Fn&& fn)
{
    par.for_parts(count, k_min_pairs_per_part, fn);
}

bool box_above_plane(const Aabb& box, const ShapeDef& plane)
{
    const Vec3 n = normalized(plane.plane_normal);
    const Vec3 lowest{n.x >= 0.0 ? box.min.x : box.max.x, n.y >= 0.0 ? box.min.y : box.max.y,
                      n.z >= 0.0 ? box.min.z : box.max.z};
    return dot(n, lowest) > plane.plane_offset;
}

// The old manifolds (sorted by key) walked along with a part's pairs, which ascend by key: each lookup
// steps forward from the last in steps that double until they pass the key, then searches that last
// step, a few probes per pair (a binary search per pair was two fifths of collide_pair's own time on a
// box pile). The first key, and a key below the last one, search afresh, so any order finds the same.
// One per thread part, each on cache lines of its own.
class alignas(k_thread_stride) ManifoldCursor
{
  public:
    explicit ManifoldCursor(const std::vector<PairManifold>* old = nullptr) : m_old(old) {}
    [[nodiscard]] const PairManifold* find(uint64_t key)
    {
        const std::vector<PairManifold>& old = *m_old;
        auto below = [](const PairManifold& x, uint64_t k) { return x.key < k; };
        if (!m_started || key < m_last) {
            m_at = static_cast<size_t>(std::lower_bound(old.begin(), old.end(), key, below) - old.begin());
        } else {
            size_t step = 1;
            while (m_at + step < old.size() && old[m_at + step].key < key) {
                m_at += step;
                step *= 2;
            }
            const auto first = old.begin() + static_cast<std::ptrdiff_t>(m_at);
            const auto last = old.begin() + static_cast<std::ptrdiff_t>(std::min(m_at + step, old.size()));
            m_at = static_cast<size_t>(std::lower_bound(first, last, key, below) - old.begin());
        }
        m_started = true;
        m_last = key;
        return m_at < old.size() && old[m_at].key == key ? &old[m_at] : nullptr;
    }

  private:
    const std::vector<PairManifold>* m_old = nullptr;
    size_t m_at = 0; ///< The first manifold whose key is not below the last key asked.
    uint64_t m_last = 0;
    bool m_started = false;
};

// The narrowphase of one pair, appended to out_points; boxes holds each body's world box this substep.
// Support-map pairs (MPR + persistent manifold) carry their old manifold over by key into out_manifold.
void collide_pair(const Registry& reg, std::span<const Aabb> boxes, const BodyPair& pair,
                  const ContactDef& def, ManifoldCursor& old_manifolds, PairManifold& out_manifold,
                  std::vector<ContactPoint>& out_points, QueryCost& out_cost)
{
    out_cost = QueryCost{};
    out_manifold = PairManifold{.key = pair.key()};
    const BodyModel& ma = reg.get<BodyModel>(pair.a);
    const BodyModel& mb = reg.get<BodyModel>(pair.b);
    const Pose& pa = reg.get<Pose>(pair.a);
    const Pose& pb = reg.get<Pose>(pair.b);
    const bool plane_a = ma.shape.type == ShapeType::Plane, plane_b = mb.shape.type == ShapeType::Plane;
    if (plane_a && plane_b)
        return;
    BodyView a{ma.collider.get(), pa.position, pa.orientation, plane_a ? Aabb{} : boxes[pair.a.index]};
    BodyView b{mb.collider.get(), pb.position, pb.orientation, plane_b ? Aabb{} : boxes[pair.b.index]};
    // The soft solver takes the manifold's points that do not touch yet too (it stops their approach).
    const bool speculative = def.solver == ContactSolver::Soft;
    if (use_support_map(def.path, *ma.collider, *mb.collider)) {
        if (const PairManifold* old = old_manifolds.find(pair.key()))
            out_manifold = *old;
        if (plane_b)
            collide_manifold_plane(a, b, true, out_manifold, out_points, speculative, &out_cost);
        else if (plane_a)
            collide_manifold_plane(b, a, false, out_manifold, out_points, speculative, &out_cost);
        else if (overlaps(a.box, b.box, speculative ? speculative_gap(*ma.collider, *mb.collider) : 0.0))
            collide_manifold(a, b, out_manifold, out_points, speculative, &out_cost);
        else
            out_manifold.count = 0;
        return;
    }
    if (plane_b)
        collide_plane(a, b, true, out_points);
    else if (plane_a)
        collide_plane(b, a, false, out_points);
    else if (overlaps(a.box, b.box)) {
        if (def.deformed_inside_test) {
            a.deformed = modal_deformed_test(reg, pair.a);
            b.deformed = modal_deformed_test(reg, pair.b);
        }
        collide_sampled(a, b, out_points);
    }
}

bool any_dynamic_collider(Registry& reg)
{
    bool any = false;
    reg.each<BodyModel>(
        [&](Entity, const BodyModel& m) { any |= m.collider && m.motion == MotionType::Dynamic; });
    return any;
}

// A body's box for the step: its world box `box` swept over the step.
Aabb swept_box(const WorldDef& def, const BodyModel& m, Aabb box, const Velocity& v)
{
    const double dt = def.dt;
    if (m.shape.type != ShapeType::Plane) {
        // Sweep over the step; rotation and gravity's change of velocity widen it.
        const Vec3 half = 0.5 * (box.max - box.min);
        const double spin = length(v.angular) * length(half) * dt;
        const double sag = length(def.gravity) * dt * dt;
        const Vec3 grow{spin + sag, spin + sag, spin + sag};
        const Vec3 move = v.linear * dt;
        box.min += Vec3{std::min(move.x, 0.0), std::min(move.y, 0.0), std::min(move.z, 0.0)} - grow;
        box.max += Vec3{std::max(move.x, 0.0), std::max(move.y, 0.0), std::max(move.z, 0.0)} + grow;
    }
    return box;
}

// The world box of an awake body for the broadphase, kept for the narrowphase (box_poses).
Aabb keep_body_box(const BodyModel& m, const Pose& p, Entity e, ContactWorld& io)
{
    const Aabb box = body_box(m, p);
    io.boxes[e.index] = box;
    io.box_poses[e.index] = {p.position, p.orientation};
    io.box_made_by[e.index] = io.broadphase_count;
    return box;
}

// The broadphase's box of e if it was made at e's pose now (the same bits body_box gives).
bool reuse_body_box(const Pose& p, Entity e, const ContactWorld& io)
{
    const auto& [position, orientation] = io.box_poses[e.index];
    return io.box_made_by[e.index] == io.broadphase_count &&
           std::memcmp(&position, &p.position, sizeof(Vec3)) == 0 &&
           std::memcmp(&orientation, &p.orientation, sizeof(Quat)) == 0;
}

// Body e's broadphase proxy: its world box swept over the step (kept while it sleeps).
BroadphaseProxy swept_proxy(const WorldDef& def, const Registry& reg, Entity e, const BodyModel& m,
                            const Pose& p, const Velocity& v, ContactWorld& io)
{
    const Sleep* sleep = reg.find<Sleep>(e);
    const bool asleep = m.motion == MotionType::Dynamic && sleep != nullptr && sleep->asleep;
    uint8_t& set = io.sleep_box_set[e.index];
    if (!asleep)
        set = 0;
    else if (set == 0) {
        io.sleep_boxes[e.index] = swept_box(def, m, body_box(m, p), v);
        set = 1;
    }
    const bool moving = m.motion == MotionType::Kinematic && (v.linear != Vec3{} || v.angular != Vec3{});
    return {.entity = e,
            .box = asleep ? io.sleep_boxes[e.index] : swept_box(def, m, keep_body_box(m, p, e, io), v),
            .is_static = m.motion != MotionType::Dynamic,
            .asleep = asleep,
            .moving = moving};
}

// One broadphase proxy per body with a collider, in the body store's order: each body's on the
// threads (it writes only its own slots), then the colliders' gathered.
void add_swept_proxies(const WorldDef& def, const Parallel& par, Registry& reg, ContactWorld& io)
{
    const size_t slots = reg.pool().slot_count();
    io.sleep_boxes.resize(slots);
    io.sleep_box_set.resize(slots, 0);
    io.boxes.resize(slots);
    io.box_poses.resize(slots);
    io.box_made_by.resize(slots, 0);
    ++io.broadphase_count;
    const std::vector<Entity>& bodies = reg.store<BodyModel>().entities();
    io.body_proxies.resize(bodies.size());
    par.for_parts(bodies.size(), k_min_bodies_per_part, [&](size_t, size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
            const Entity e = bodies[i];
            const BodyModel& m = reg.store<BodyModel>().values()[i];
            const Pose* p = reg.find<Pose>(e);
            const Velocity* v = reg.find<Velocity>(e);
            io.body_proxies[i].entity = Entity{}; // no proxy
            if (m.collider && p != nullptr && v != nullptr)
                io.body_proxies[i] = swept_proxy(def, reg, e, m, *p, *v, io);
        }
    });
    for (const BroadphaseProxy& proxy : io.body_proxies)
        if (!proxy.entity.is_null())
            io.proxies.push_back(proxy);
}

// Whether a broadphase pair cannot touch: excluded, or a body whose swept box stays above a plane it
// was paired with.
bool pair_apart(const Registry& reg, const ContactWorld& io, const BodyPair& pair)
{
    if (!io.excluded_pairs.empty() && // jointed parts and parent–child pairs
        std::binary_search(io.excluded_pairs.begin(), io.excluded_pairs.end(), pair.key()))
        return true;
    // A plane's box is unbounded, so the sweep pairs it with every body; keep only the bodies whose
    // swept box reaches into its half-space (else a pile in a box of planes runs five plane tests per
    // body per substep for nothing). A modal body's box is its rest shape's; its deformation may reach
    // further, so its pairs stay.
    if (reg.has<ModalBody>(pair.a) || reg.has<ModalBody>(pair.b))
        return false;
    const ShapeDef& sa = reg.get<BodyModel>(pair.a).shape;
    const ShapeDef& sb = reg.get<BodyModel>(pair.b).shape;
    if (sa.type == ShapeType::Plane)
        return box_above_plane(io.swept[pair.b.index], sa);
    if (sb.type == ShapeType::Plane)
        return box_above_plane(io.swept[pair.a.index], sb);
    return false;
}

// Drops the broadphase's pairs that cannot touch (pair_apart): each pair asked on the threads, the
// rest kept in order.
void drop_pairs_apart(const Registry& reg, const Parallel& par, ContactWorld& io)
{
    io.swept.resize(reg.pool().slot_count());
    for (const BroadphaseProxy& proxy : io.proxies)
        io.swept[proxy.entity.index] = proxy.box;
    io.pair_apart.resize(io.pairs.size());
    for_parts(par, io.pairs.size(), [&](size_t, size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i)
            io.pair_apart[i] = pair_apart(reg, io, io.pairs[i]) ? 1 : 0;
    });
    size_t kept = 0;
    for (size_t i = 0; i < io.pairs.size(); ++i)
        if (io.pair_apart[i] == 0)
            io.pairs[kept++] = io.pairs[i];
    io.pairs.resize(kept);
}

// Tunnelling rule: substep so that no pair closes by more than a fraction of the thinner body per
// substep (measured in tests/contact/contact_system_test.cpp: a 50 m/s ball and a 2 cm board).
// Stopping rule, with the automatic contact frequency ω = 2π·0.1·s/dt: the spring stops an approach
// at speed v within v/ω, which must stay under half the thinner body, or bodies sink past each
// other's centres, where the normals cancel and they stay merged (measured: ellipsoids falling
// 1.8 m in the pile benchmark merged, 40 mm overlaps, at one substep).
int substeps_needed(const WorldDef& def, const Registry& reg, const Parallel& par, ContactWorld& io)
{
    const double dt = def.dt;
    const double stop_factor = 2.0 * std::numbers::pi * k_frequency_cap_per_rate * k_stop_fraction;
    const double factor = def.contact.frequency_hz > 0.0
                              ? def.contact.speculative_speed_factor
                              : std::min(def.contact.speculative_speed_factor, stop_factor);
    // Each part's largest need, then the largest of those: a maximum, so the same on any threads.
    std::vector<double>& part_needed = io.part_needed;
    part_needed.assign(par.part_capacity(), static_cast<double>(def.substep_count));
    for_parts(par, io.pairs.size(), [&](size_t part, size_t begin, size_t end) {
        double needed = part_needed[part];
        for (size_t pi = begin; pi < end; ++pi) {
            const BodyPair& pair = io.pairs[pi];
            const BodyModel& ma = reg.get<BodyModel>(pair.a);
            const BodyModel& mb = reg.get<BodyModel>(pair.b);
            const double thin = std::min(ma.shape.type == ShapeType::Plane ? 1e300 : ma.collider->thickness,
                                         mb.shape.type == ShapeType::Plane ? 1e300 : mb.collider->thickness);
            const double speed = length(reg.get<Velocity>(pair.a).linear - reg.get<Velocity>(pair.b).linear);
            needed = std::max(needed, speed * dt / (factor * thin));
        }
        part_needed[part] = needed;
    });
    const double needed = *std::max_element(part_needed.begin(), part_needed.end());
    const int cap = def.substep_count + def.contact.max_auto_substeps;
    // Compare in double first: a huge speed or a zero thickness makes `needed` overflow int (or inf),
    // and converting that is undefined (found by the fuzzer).
    if (!(needed < static_cast<double>(cap)))
        return cap;
    return static_cast<int>(std::ceil(needed));
}

} // namespace

const PairAnchor* find_pair_anchor(const std::vector<PairAnchor>& anchors, uint64_t key)
{
    auto it = std::lower_bound(anchors.begin(), anchors.end(), key,
                               [](const PairAnchor& a, uint64_t k) { return a.key < k; });
    return it != anchors.end() && it->key == key ? &*it : nullptr;
}

int update_pairs(const WorldDef& def, const Parallel& par, Registry& reg, ContactWorld& io)
{
    io.proxies.clear();
    io.pairs.clear();
    // No contact at all, or no pair with a dynamic body (only those collide): a scene of static and
    // kinematic bodies (a gallery, a paused editor scene) skips the boxes, the grid and, per substep, the
    // narrowphase's boxes.
    if (!def.contact.enabled || !any_dynamic_collider(reg)) {
        begin_step_events(io.events, 0);
        return def.substep_count;
    }
    // Sleeping bodies pair only with awake and moving ones; when those wake an island, its bodies'
    // pairs with other sleepers are found by running the broadphase again (rare: a wake).
    do {
        io.proxies.clear();
        io.pairs.clear();
        add_swept_proxies(def, par, reg, io);
        // Nothing awake or moving: no pair can matter (a scene that has all gone to sleep).
        if (std::none_of(io.proxies.begin(), io.proxies.end(),
                         [](const BroadphaseProxy& x) { return (!x.is_static && !x.asleep) || x.moving; }))
            break;
        find_overlapping_pairs(io.proxies, io.broadphase, io.pairs, par);
        drop_pairs_apart(reg, par, io);
    } while (settle_sleeping_pairs(par, reg, io));
    begin_step_events(io.events, io.pairs.size());
    io.support_calls = 0;
    io.touching_pairs = 0;
    io.touching_support_calls = 0;
    return substeps_needed(def, reg, par, io);
}

namespace
{

// Kept while touching, or apart with a direction that separated it (the next query's start).
bool keeps_manifold(const PairManifold& m)
{
    return m.count > 0 || length(m.normal) > 0.0;
}

// The substep's manifolds worth keeping, in pair order (pairs are sorted by key, so the list is too),
// and the support-map counts, gathered on the threads: the copy is a few megabytes on a large pile.
void keep_manifolds(const Parallel& par, ContactWorld& io)
{
    auto tally = [&](size_t begin, size_t end) {
        ManifoldTally t;
        for (size_t pi = begin; pi < end; ++pi) {
            const auto calls = static_cast<uint64_t>(io.pair_cost[pi].support_calls);
            const bool touching = io.pair_points[pi].end > io.pair_points[pi].begin;
            t.kept += keeps_manifold(io.pair_manifold[pi]) ? 1 : 0;
            t.support_calls += calls;
            t.touching_pairs += touching ? 1 : 0;
            t.touching_support_calls += touching ? calls : 0;
        }
        return t;
    };
    auto size = [&](const ManifoldTally& total) {
        io.manifolds.resize(total.kept); // no clear first: every slot is written
        io.support_calls += total.support_calls;
        io.touching_pairs += total.touching_pairs;
        io.touching_support_calls += total.touching_support_calls;
    };
    auto fill = [&](const ManifoldTally& start, size_t begin, size_t end) {
        size_t out = start.kept;
        for (size_t pi = begin; pi < end; ++pi)
            if (keeps_manifold(io.pair_manifold[pi]))
                io.manifolds[out++] = io.pair_manifold[pi];
    };
    par.gather(io.pairs.size(), k_min_pairs_per_part, io.manifold_tally, tally, size, fill,
               &io.collide_balance);
}

} // namespace

void collide_pairs(const WorldDef& def, const Registry& reg, const Parallel& par, ContactWorld& io)
{
    // Double-buffered, so a warm substep allocates no manifold list.
    std::vector<PairManifold>& old_manifolds = io.old_manifolds;
    old_manifolds.swap(io.manifolds);
    io.pair_manifold.resize(io.pairs.size());
    io.pair_cost.resize(io.pairs.size());
    io.part_points.resize(par.part_capacity());
    for (std::vector<ContactPoint>& points : io.part_points)
        points.clear();
    io.pair_points.resize(io.pairs.size());
    // World boxes once per body, not once per pair it is in (three support-map calls each); none for a
    // sleeping body, which is in no pair by now (those an awake body reached woke).
    io.boxes.resize(reg.pool().slot_count());
    for_parts(par, io.proxies.size(), [&](size_t, size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
            if (io.proxies[i].asleep)
                continue;
            const Entity e = io.proxies[i].entity;
            const BodyModel& m = reg.get<BodyModel>(e);
            const Pose& p = reg.get<Pose>(e);
            if (m.shape.type != ShapeType::Plane && !reuse_body_box(p, e, io))
                io.boxes[e.index] = body_box(m, p);
        }
    });
    std::vector<ManifoldCursor> cursors(par.part_capacity(), ManifoldCursor(&old_manifolds));
    par.for_parts(io.pairs.size(), k_min_pairs_per_part, io.collide_balance,
                  [&](size_t part, size_t begin, size_t end) {
                      std::vector<ContactPoint>& points = io.part_points[part];
                      ManifoldCursor& old = cursors[part];
                      for (size_t pi = begin; pi < end; ++pi) {
                          const auto first = static_cast<uint32_t>(points.size());
                          collide_pair(reg, io.boxes, io.pairs[pi], def.contact, old, io.pair_manifold[pi],
                                       points, io.pair_cost[pi]);
                          io.pair_points[pi] = {static_cast<uint32_t>(part), first,
                                                static_cast<uint32_t>(points.size())};
                      }
                  });
    keep_manifolds(par, io);
}

namespace
{

// The modes as the contact springs feel them: one reader per thread part, with its own φ scratch.
struct ModalReader {
    const Registry* reg = nullptr;
    std::vector<double>* phi = nullptr;

    static double inverse_mass(void* ctx, Entity body, const Vec3& x, const Vec3& d)
    {
        const auto* r = static_cast<const ModalReader*>(ctx);
        return modal_inverse_mass(*r->reg, body, x, d, *r->phi);
    }
};

[[nodiscard]] bool has_modes(const Registry& reg, const BodyPair& pair)
{
    return reg.has<ModalBody>(pair.a) || reg.has<ModalBody>(pair.b);
}

// The penalty forces of pair pi; a pair with a modal body also writes its points' normal forces.
PairForce pair_penalty(const PenaltyParams& params, const Registry& reg, ContactWorld& io, size_t pi,
                       ZetaCache& io_zeta, const PairModes& modes)
{
    const std::span<const ContactPoint> points = io.points_of(pi);
    if (points.empty())
        return PairForce{};
    const BodyPair& pair = io.pairs[pi];
    auto side = [&](Entity e) {
        return PenaltyBody{&reg.get<BodyModel>(e), &reg.get<Pose>(e), &reg.get<Velocity>(e)};
    };
    const PairAnchor* old_anchor = find_pair_anchor(io.anchors, pair.key());
    if (!has_modes(reg, pair))
        return penalty_pair(params, pair, side(pair.a), side(pair.b), points, old_anchor, io_zeta);
    const PairPoints& r = io.pair_points[pi];
    const std::span<double> point_force{io.part_point_force[r.part].data() + r.begin, points.size()};
    return penalty_pair(params, pair, side(pair.a), side(pair.b), points, old_anchor, io_zeta, &modes,
                        point_force);
}

// A touching pair's loads on its modal bodies (a no-op for rigid ones): each point's normal force, then
// the friction force at the centroid. Serial, in pair order, so the sums do not depend on threads.
void load_modes(Registry& reg, const ContactWorld& io, size_t pi)
{
    const BodyPair& pair = io.pairs[pi];
    if (!has_modes(reg, pair))
        return;
    const std::span<const ContactPoint> points = io.points_of(pi);
    const PairPoints& r = io.pair_points[pi];
    const double* force = io.part_point_force[r.part].data() + r.begin;
    for (size_t i = 0; i < points.size(); ++i) {
        const Vec3 fv = force[i] * points[i].normal;
        modal_add_point_load(reg, pair.a, points[i].point, fv);
        modal_add_point_load(reg, pair.b, points[i].point, -1.0 * fv);
        const double work = std::abs(force[i]) * std::max(points[i].depth, 0.0);
        modal_add_spring_work(reg, pair.a, work);
        modal_add_spring_work(reg, pair.b, work);
    }
    const PairForce& pf = io.pair_force[pi];
    modal_add_point_load(reg, pair.a, pf.info.point, pf.friction_force);
    modal_add_point_load(reg, pair.b, pf.info.point, -1.0 * pf.friction_force);
}

// The substep's spring rate: the world's frequency, or the stability cap 1/(10 h) (always in material
// mode, where it caps the Hertz stiffness); a frequency over the cap is clamped and counted.
PenaltyParams penalty_params(const WorldDef& def, const StepContext& ctx, StepWarnings& io_warnings)
{
    const double cap_hz = k_frequency_cap_per_rate / ctx.h;
    const bool material = def.contact.stiffness == ContactStiffness::Material;
    double f_hz = def.contact.frequency_hz > 0.0 && !material ? def.contact.frequency_hz : cap_hz;
    if (f_hz > cap_hz) {
        f_hz = cap_hz;
        ++io_warnings.contact_frequency_clamps;
    }
    return {.omega = 2.0 * std::numbers::pi * f_hz,
            .material = material,
            .damping_ratio = def.contact.damping_ratio,
            .h = ctx.h};
}

// Per pair, on any thread: reads bodies and old anchors, writes only the pair's slot (and, for a pair
// with a modal body, its points' normal forces, which load the modes afterwards).
void compute_pair_forces(const PenaltyParams& params, const StepContext& ctx, Registry& reg,
                         const Parallel& par, ContactWorld& io)
{
    io.pair_force.resize(io.pairs.size());
    io.zeta_caches.resize(par.part_capacity());
    io.modal_phi.resize(par.part_capacity());
    io.part_point_force.resize(io.part_points.size());
    for (size_t part = 0; part < io.part_points.size(); ++part)
        io.part_point_force[part].resize(io.part_points[part].size());
    prepare_modal_substep(reg, ctx.h);
    const Registry& creg = reg;
    for_parts(par, io.pairs.size(), [&](size_t part, size_t begin, size_t end) {
        ModalReader reader{&creg, &io.modal_phi[part]};
        const PairModes modes{.inverse_mass = &ModalReader::inverse_mass, .ctx = &reader};
        for (size_t pi = begin; pi < end; ++pi)
            io.pair_force[pi] = pair_penalty(params, creg, io, pi, io.zeta_caches[part], modes);
    });
}

// In pair order, on one thread: sums per body, modal loads, new anchors (sorted, as the pairs are),
// events.
void sum_pair_forces(const StepContext& ctx, Registry& reg, ContactWorld& io, StepWarnings& io_warnings)
{
    // Double-buffered, so a warm substep allocates no anchor list.
    std::vector<PairAnchor>& anchors = io.next_anchors;
    anchors.clear();
    for (size_t pi = 0; pi < io.pairs.size(); ++pi) {
        const PairForce& pf = io.pair_force[pi];
        if (!pf.touching)
            continue;
        const uint32_t a = io.pairs[pi].a.index, b = io.pairs[pi].b.index;
        io.force[a] += pf.force_a;
        io.torque[a] += pf.torque_a;
        io.force[b] -= pf.force_a;
        io.torque[b] += pf.torque_b;
        load_modes(reg, io, pi);
        anchors.push_back(pf.anchor);
        if (pf.stiffness_clamped)
            ++io_warnings.contact_frequency_clamps;
        io.has_twist.push_back(pf.has_twist ? 1 : 0);
        io.has_roll.push_back(pf.has_roll ? 1 : 0);
        io.contacts.push_back(pf.info);
        io.max_penetration = std::max(io.max_penetration, pf.info.depth);
        accumulate_touch(io.events, pi, pf.info, pf.normal_force, ctx.h);
    }
    io.anchors.swap(anchors);
}

} // namespace

void apply_penalty_forces(const WorldDef& def, const StepContext& ctx, Registry& reg, const Parallel& par,
                          ContactWorld& io, StepWarnings& io_warnings)
{
    const size_t slots = reg.pool().slot_count();
    io.force.assign(slots, Vec3{});
    io.torque.assign(slots, Vec3{});
    io.contacts.clear();
    io.has_twist.clear();
    io.has_roll.clear();
    io.max_penetration = 0.0;
    const PenaltyParams params = penalty_params(def, ctx, io_warnings);
    compute_pair_forces(params, ctx, reg, par, io);
    sum_pair_forces(ctx, reg, io, io_warnings);
    // Forces into velocities, one body at a time (order-independent).
    reg.each<BodyModel, Pose, Velocity>([&](Entity e, const BodyModel& m, const Pose& p, Velocity& v) {
        if (m.motion != MotionType::Dynamic)
            return;
        v.linear += (ctx.h * m.inv_mass) * io.force[e.index];
        const Quat q = principal_orientation(m, p.orientation);
        const Vec3 dl_body = inv_rotate(q, ctx.h * io.torque[e.index]);
        v.angular += rotate(q, hadamard(m.inv_inertia_body, dl_body));
    });
}

void update_contact_anchors(const StepContext& ctx, const Registry& reg, const Parallel& par,
                            ContactWorld& io)
{
    // The anchors follow the displacement the bodies actually make this substep, x' − x = h·v', with
    // v' the velocity after every force of the substep: with the velocity from before the contact forces
    // (which still holds this substep's gravity), a sticking spring would grow by h²·g every substep and
    // shove the body uphill (measured: a block crept 7 mm/s up a 22° incline); with the velocity from
    // before the constraint impulses, a part held by a joint while it rests on something ratchets its
    // spring the same way (measured: the chair sample's dummy crept forward off the seat at 1 cm/s, its
    // thighs and the chair jittering at 2–6 cm/s). Each contact writes only its own anchor.
    const Registry& creg = reg;
    for_parts(par, io.contacts.size(), [&](size_t, size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
            const ContactInfo& ci = io.contacts[i];
            PairAnchor& anchor = io.anchors[i];
            const Velocity& va = creg.get<Velocity>(ci.a);
            const Velocity& vb = creg.get<Velocity>(ci.b);
            const Vec3 v_rel = velocity_at(va, creg.get<Pose>(ci.a).position, ci.point) -
                               velocity_at(vb, creg.get<Pose>(ci.b).position, ci.point);
            anchor.spring += ctx.h * (v_rel - dot(v_rel, ci.normal) * ci.normal);
            if (io.has_twist[i] != 0)
                anchor.twist += ctx.h * dot(va.angular - vb.angular, ci.normal);
            if (io.has_roll[i] != 0) {
                const Vec3 w_rel = va.angular - vb.angular;
                anchor.roll += ctx.h * (w_rel - dot(w_rel, ci.normal) * ci.normal);
            }
        }
    });
}

void requery_pairs_of(ContactWorld& io, Entity body)
{
    for (PairManifold& m : io.manifolds)
        if (const auto [a, b] = pair_key_indices(m.key); a == body.index || b == body.index)
            m.steady = 0;
}

} // namespace supermodal
