// SPDX-License-Identifier: MIT
#include "contact/contact_system.h"

#include "dynamics/integrate.h"
#include "modal/modal_world.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace supermodal
{
namespace
{

// Penalty frequency cap relative to the substep rate: ω·h = 2π/10 ≈ 0.63 keeps semi-implicit Euler
// (stable to ω·h < 2) stable with room for a body pressed by several contacts (Box2D v3 caps alike).
constexpr double k_frequency_cap_per_rate = 0.1;
// Tangential spring frequency relative to the normal one, on the tangential effective mass (which
// includes rotation about the centres of mass): below 1 so that a body held by several sticking
// contacts (a box in a stack has two) stays inside the explicit stability region.
constexpr double k_tangential_frequency_ratio = 0.7;
// Damping ratio of the tangential spring: enough that a sticking contact does not ring, small enough
// that the explicit dashpot of two contacts on one body does not overshoot (c·h/m < 1 each).
constexpr double k_tangential_damping_ratio = 0.5;
// Cap on a normal dashpot's c·h/m_eff [-]: two contacts on a box against each other stay below 1
// (2 × 2 × 0.4 × m_eff/m = 0.8 with m_eff = m/2). At the default frequency (ωh = 0.63) restitutions
// e ≥ 0.45 are not affected (c·h/m_eff = 2ζ·ωh ≤ 0.4 for ζ ≤ 0.32); lower ones bounce a little more.
constexpr double k_max_dashpot_step = 0.4;

Aabb body_box(const BodyModel& m, const Pose& p)
{
    const Vec3 origin = p.position - rotate(p.orientation, m.collider->com_shape);
    return world_aabb(m.shape, origin, p.orientation);
}

// Restitution of the no-pull spring–dashpot x'' + 2ζx' + x = 0 (unit frequency): contact starts at
// x = 0, x' = 1 and ends when the force x + 2ζx' first reaches zero, at ω_d·t = atan2(2ζω_d, 2ζ² − 1)
// (ω_d = √(1 − ζ²)); e = −x'(t). The textbook exp(−ζπ/ω_d) ignores the clamp and asks for too little
// damping (a 0.5 target bounced to 0.56, measured).
double clamped_restitution(double zeta)
{
    if (zeta >= 1.0)
        return 0.0;
    const double wd = std::sqrt(1.0 - zeta * zeta);
    const double phase = std::atan2(2.0 * zeta * wd, 2.0 * zeta * zeta - 1.0);
    return -std::exp(-zeta * phase / wd) * (std::cos(phase) - zeta * std::sin(phase) / wd);
}

// ζ for restitution e, by bisection (e falls monotonically with ζ).
double damping_ratio_for_restitution(double e)
{
    double lo = 0.0, hi = 1.0;
    for (int it = 0; it < 50; ++it) {
        const double mid = 0.5 * (lo + hi);
        (clamped_restitution(mid) > e ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

// Inverse effective mass of a body at offset r for a push along unit d: 1/m + (r×d)·I⁻¹(r×d); for
// d = 0 (any tangent direction) the bound 1/m + |r|²·max(I⁻¹) [1/kg].
double inverse_mass_at(const BodyModel& m, const Pose& p, const Vec3& r, const Vec3& d)
{
    if (m.motion != MotionType::Dynamic)
        return 0.0;
    const Vec3& ii = m.inv_inertia_body;
    if (d == Vec3{})
        return m.inv_mass + dot(r, r) * std::max({ii.x, ii.y, ii.z});
    const Vec3 rd = inv_rotate(p.orientation, cross(r, d));
    return m.inv_mass + dot(rd, hadamard(ii, rd));
}

// n·I⁻¹n in the world frame [1/(kg·m²)]: how easily the body turns about the contact normal.
double inverse_twist_inertia(const BodyModel& m, const Pose& p, const Vec3& n)
{
    if (m.motion != MotionType::Dynamic)
        return 0.0;
    const Vec3 nb = inv_rotate(p.orientation, n);
    return dot(nb, hadamard(m.inv_inertia_body, nb));
}

Vec3 velocity_at(const Velocity& v, const Vec3& centre, const Vec3& point)
{
    return v.linear + cross(v.angular, point - centre);
}

PairAnchor* find_anchor(std::vector<PairAnchor>& anchors, uint64_t key)
{
    auto it = std::lower_bound(anchors.begin(), anchors.end(), key,
                               [](const PairAnchor& a, uint64_t k) { return a.key < k; });
    return it != anchors.end() && it->key == key ? &*it : nullptr;
}

// Support-map pair (MPR + persistent manifold): carries the pair's old manifold over by key.
void collide_support_map(const BodyView& a, const BodyView& b, uint64_t key,
                         const std::vector<PairManifold>& old_manifolds, ContactWorld& io)
{
    PairManifold m{.key = key};
    auto it = std::lower_bound(old_manifolds.begin(), old_manifolds.end(), key,
                               [](const PairManifold& x, uint64_t k) { return x.key < k; });
    if (it != old_manifolds.end() && it->key == key)
        m = *it;
    const bool plane_a = a.collider->shape.type == ShapeType::Plane;
    const bool plane_b = b.collider->shape.type == ShapeType::Plane;
    if (plane_b)
        collide_manifold_plane(a, b, true, m, io.points);
    else if (plane_a)
        collide_manifold_plane(b, a, false, m, io.points);
    else if (overlaps(a.box, b.box))
        collide_manifold(a, b, m, io.points);
    else
        m.count = 0;
    if (m.count > 0)
        io.manifolds.push_back(m);
}

} // namespace

double ZetaCache::get(double e)
{
    for (const Entry& entry : entries)
        if (entry.e == e)
            return entry.zeta;
    entries[next] = {e, damping_ratio_for_restitution(e)};
    const double zeta = entries[next].zeta;
    next = (next + 1) % entries.size();
    return zeta;
}

int update_pairs(const WorldDef& def, Registry& reg, ContactWorld& io)
{
    io.proxies.clear();
    io.pairs.clear();
    if (!def.contact.enabled)
        return def.substep_count;
    const double dt = def.dt;
    reg.each<BodyModel, Pose, Velocity>([&](Entity e, const BodyModel& m, const Pose& p, const Velocity& v) {
        if (!m.collider)
            return;
        Aabb box = body_box(m, p);
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
        io.proxies.push_back({.entity = e, .box = box, .is_static = m.motion != MotionType::Dynamic});
    });
    find_overlapping_pairs(io.proxies, io.broadphase, io.pairs);
    if (!io.excluded_pairs.empty())
        std::erase_if(io.pairs, [&](const BodyPair& pair) {
            const uint64_t key =
                (uint64_t{std::min(pair.a.index, pair.b.index)} << 32) | std::max(pair.a.index, pair.b.index);
            return std::binary_search(io.excluded_pairs.begin(), io.excluded_pairs.end(), key);
        });

    // Tunnelling rule: substep so that no pair closes by more than a fraction of the thinner body per
    // substep (measured in tests/contact/contact_system_test.cpp: a 50 m/s ball and a 2 cm board).
    double needed = def.substep_count;
    for (const BodyPair& pair : io.pairs) {
        const BodyModel& ma = reg.get<BodyModel>(pair.a);
        const BodyModel& mb = reg.get<BodyModel>(pair.b);
        const Velocity& va = reg.get<Velocity>(pair.a);
        const Velocity& vb = reg.get<Velocity>(pair.b);
        const double thin = std::min(ma.shape.type == ShapeType::Plane ? 1e300 : ma.collider->thickness,
                                     mb.shape.type == ShapeType::Plane ? 1e300 : mb.collider->thickness);
        const double speed = length(va.linear - vb.linear);
        needed = std::max(needed, speed * dt / (def.contact.speculative_speed_factor * thin));
    }
    const int cap = def.substep_count + def.contact.max_auto_substeps;
    return std::min(cap, static_cast<int>(std::ceil(needed)));
}

void collide_pairs(const WorldDef& def, Registry& reg, ContactWorld& io)
{
    io.points.clear();
    io.pair_start.assign(1, 0);
    std::vector<PairManifold> old_manifolds;
    old_manifolds.swap(io.manifolds); // pairs are sorted by key, so the new manifolds are too
    for (const BodyPair& pair : io.pairs) {
        const BodyModel& ma = reg.get<BodyModel>(pair.a);
        const BodyModel& mb = reg.get<BodyModel>(pair.b);
        const Pose& pa = reg.get<Pose>(pair.a);
        const Pose& pb = reg.get<Pose>(pair.b);
        const bool plane_a = ma.shape.type == ShapeType::Plane, plane_b = mb.shape.type == ShapeType::Plane;
        if (!(plane_a && plane_b)) {
            const BodyView a{ma.collider.get(), pa.position, pa.orientation,
                             plane_a ? Aabb{} : body_box(ma, pa)};
            const BodyView b{mb.collider.get(), pb.position, pb.orientation,
                             plane_b ? Aabb{} : body_box(mb, pb)};
            if (use_support_map(def.contact.path, *ma.collider, *mb.collider))
                collide_support_map(a, b, pair.key(), old_manifolds, io);
            else if (plane_b)
                collide_plane(a, b, true, io.points);
            else if (plane_a)
                collide_plane(b, a, false, io.points);
            else if (overlaps(a.box, b.box))
                collide_sampled(a, b, io.points);
        }
        io.pair_start.push_back(static_cast<uint32_t>(io.points.size()));
    }
}

void apply_penalty_forces(const WorldDef& def, const StepContext& ctx, Registry& reg, ContactWorld& io,
                          StepWarnings& io_warnings)
{
    const size_t slots = reg.pool().slot_count();
    io.force.assign(slots, Vec3{});
    io.torque.assign(slots, Vec3{});
    io.contacts.clear();
    io.max_penetration = 0.0;
    std::vector<PairAnchor> anchors;
    anchors.reserve(io.anchors.size());
    std::vector<bool> has_twist;
    ZetaCache& zeta_cache = io.zeta_cache;
    const double cap_hz = k_frequency_cap_per_rate / ctx.h;
    double f_hz = def.contact.frequency_hz > 0.0 ? def.contact.frequency_hz : cap_hz;
    if (f_hz > cap_hz) {
        f_hz = cap_hz;
        ++io_warnings.contact_frequency_clamps;
    }
    const double omega = 2.0 * std::numbers::pi * f_hz;

    for (size_t pi = 0; pi < io.pairs.size(); ++pi) {
        const uint32_t begin = io.pair_start[pi], end = io.pair_start[pi + 1];
        if (begin == end)
            continue;
        const BodyPair& pair = io.pairs[pi];
        const BodyModel& ma = reg.get<BodyModel>(pair.a);
        const BodyModel& mb = reg.get<BodyModel>(pair.b);
        const double inv_m = ma.inv_mass + mb.inv_mass;
        if (!(inv_m > 0.0))
            continue;
        const Pose& pa = reg.get<Pose>(pair.a);
        const Pose& pb = reg.get<Pose>(pair.b);
        const Velocity& va = reg.get<Velocity>(pair.a);
        const Velocity& vb = reg.get<Velocity>(pair.b);
        Vec3 normal_sum{}, centroid{};
        double weight_sum = 0.0;
        for (uint32_t i = begin; i < end; ++i) {
            normal_sum += io.points[i].weight * io.points[i].normal;
            centroid += io.points[i].weight * io.points[i].point;
            weight_sum += io.points[i].weight;
        }
        centroid = centroid / weight_sum;
        const Vec3 n = normalized(normal_sum);
        const Vec3 ra = centroid - pa.position, rb = centroid - pb.position;
        // Effective masses at the contact, rotation included, so a push off the centre of mass (an edge,
        // a corner) gets a spring its own inertia can carry at this substep.
        const double modal_inv = modal_inverse_mass(reg, pair.a, centroid, n, ctx.h) +
                                 modal_inverse_mass(reg, pair.b, centroid, n, ctx.h); // modes are lighter
        const double m_eff =
            1.0 / (inverse_mass_at(ma, pa, ra, n) + inverse_mass_at(mb, pb, rb, n) + modal_inv);
        const double zeta = def.contact.damping_ratio >= 0.0
                                ? def.contact.damping_ratio
                                : zeta_cache.get(std::max(ma.restitution, mb.restitution));
        // The dashpot is explicit: a body feels the sum of its contacts' c·h/m_eff, and in a stack
        // every middle box has two, whose Nyquist mode (neighbours moving against each other) flips
        // the velocity every step once the sum passes 1 (measured: ten boxes, e = 0.2, c·h/m_eff =
        // 0.92 per contact, in a period-2 limit cycle at 0.19 m/s). Capped at k_max_dashpot_step for
        // rigid pairs. Not for pairs with a modal body: their m_eff holds the modes' inverse mass, the
        // modes absorb the dashpot's kick, and the cap starves them of damping (measured: a soft
        // sphere kept bouncing at 0.2–0.3 m/s for 12 s with it, rests within 3 s without).
        const double k = m_eff * omega * omega;
        const double c_free = 2.0 * zeta * m_eff * omega;
        const double c = modal_inv > 0.0 ? c_free : std::min(c_free, k_max_dashpot_step * m_eff / ctx.h);

        Vec3 total{};
        double normal_force = 0.0, deepest = 0.0;
        for (uint32_t i = begin; i < end; ++i) {
            const ContactPoint& cp = io.points[i];
            const double vn = dot(
                velocity_at(va, pa.position, cp.point) - velocity_at(vb, pb.position, cp.point), cp.normal);
            // No pull: a separating contact whose dashpot would exceed its spring just lets go.
            const double f = std::max(0.0, k * cp.depth - c * vn) * cp.weight;
            const Vec3 fv = f * cp.normal;
            io.force[pair.a.index] += fv;
            io.torque[pair.a.index] += cross(cp.point - pa.position, fv);
            io.force[pair.b.index] -= fv;
            io.torque[pair.b.index] -= cross(cp.point - pb.position, fv);
            modal_add_point_load(reg, pair.a, cp.point, fv); // deforms modal bodies; no-op for rigid
            modal_add_point_load(reg, pair.b, cp.point, -fv);
            total += fv;
            normal_force += f;
            deepest = std::max(deepest, cp.depth);
        }

        // Friction: a tangential spring anchored where the contact stuck, clamped to the Coulomb cone.
        const double mu = std::sqrt(ma.friction * mb.friction);
        PairAnchor anchor{pair.key(), {}};
        if (const PairAnchor* old = find_anchor(io.anchors, anchor.key)) {
            anchor.spring = old->spring - dot(old->spring, n) * n; // keep it in today's contact plane
            anchor.twist = old->twist;
        }
        const Vec3 v_rel = velocity_at(va, pa.position, centroid) - velocity_at(vb, pb.position, centroid);
        const Vec3 v_t = v_rel - dot(v_rel, n) * n;
        const double m_t = 1.0 / (inverse_mass_at(ma, pa, ra, {}) + inverse_mass_at(mb, pb, rb, {}) +
                                  modal_inverse_mass(reg, pair.a, centroid, {}, ctx.h) +
                                  modal_inverse_mass(reg, pair.b, centroid, {}, ctx.h));
        const double omega_t = k_tangential_frequency_ratio * omega;
        const double kt = m_t * omega_t * omega_t;
        const double ct = 2.0 * k_tangential_damping_ratio * m_t * omega_t;
        Vec3 ft = -kt * anchor.spring - ct * v_t;
        const double limit = mu * normal_force;
        if (length(ft) > limit) {
            ft = limit > 0.0 ? ft * (limit / length(ft)) : Vec3{};
            anchor.spring = limit > 0.0 ? -(ft + ct * v_t) / kt : Vec3{}; // slide: the anchor follows
        }
        io.force[pair.a.index] += ft;
        io.torque[pair.a.index] += cross(centroid - pa.position, ft);
        io.force[pair.b.index] -= ft;
        io.torque[pair.b.index] -= cross(centroid - pb.position, ft);
        modal_add_point_load(reg, pair.a, centroid, ft);
        modal_add_point_load(reg, pair.b, centroid, -ft);
        // Torsional friction about the normal: a spring on the relative twist, clamped to what Coulomb
        // friction over the patch can resist ((2/3)·μ·F·R for a disc of radius R = √(2ρ²), ρ² the
        // patch's second moment). Without it a single friction anchor lets a resting face spin up.
        double patch_rho2 = 0.0;
        for (uint32_t i = begin; i < end; ++i) {
            const Vec3 d = io.points[i].point - centroid;
            patch_rho2 += io.points[i].weight * (dot(d, d) - dot(d, n) * dot(d, n)) / weight_sum;
        }
        const double inv_j = inverse_twist_inertia(ma, pa, n) + inverse_twist_inertia(mb, pb, n);
        if (patch_rho2 > 0.0 && inv_j > 0.0) {
            const double j = 1.0 / inv_j;
            const double k_tw = j * omega_t * omega_t, c_tw = 2.0 * k_tangential_damping_ratio * j * omega_t;
            const double spin = dot(va.angular - vb.angular, n);
            double tau = -k_tw * anchor.twist - c_tw * spin;
            const double tau_limit = (2.0 / 3.0) * limit * std::sqrt(2.0 * patch_rho2);
            if (std::abs(tau) > tau_limit) {
                tau = std::copysign(tau_limit, tau);
                anchor.twist = -(tau + c_tw * spin) / k_tw;
            }
            io.torque[pair.a.index] += tau * n;
            io.torque[pair.b.index] -= tau * n;
        } else {
            anchor.twist = 0.0;
        }
        anchors.push_back(anchor);
        has_twist.push_back(patch_rho2 > 0.0 && inv_j > 0.0);
        io.contacts.push_back({.a = pair.a,
                               .b = pair.b,
                               .point = centroid,
                               .normal = n,
                               .depth = deepest,
                               .force_on_a = total + ft,
                               .point_count = static_cast<int>(end - begin)});
        io.max_penetration = std::max(io.max_penetration, deepest);
    }
    io.anchors.swap(anchors); // pairs are sorted, so the new anchors are too

    // Forces into velocities, one body at a time (order-independent).
    reg.each<BodyModel, Pose, Velocity>([&](Entity e, const BodyModel& m, const Pose& p, Velocity& v) {
        if (m.motion != MotionType::Dynamic)
            return;
        v.linear += (ctx.h * m.inv_mass) * io.force[e.index];
        const Vec3 dl_body = inv_rotate(p.orientation, ctx.h * io.torque[e.index]);
        v.angular += rotate(p.orientation, hadamard(m.inv_inertia_body, dl_body));
    });

    // The anchors follow the displacement the bodies actually make this substep, x' − x = h·v': with
    // the velocity from before the contact forces (which still holds this substep's gravity), a
    // sticking spring would grow by h²·g every substep and shove the body uphill (measured: a block
    // crept 7 mm/s up a 22° incline).
    for (size_t i = 0; i < io.contacts.size(); ++i) {
        const ContactInfo& ci = io.contacts[i];
        PairAnchor& anchor = io.anchors[i];
        const Velocity& va = reg.get<Velocity>(ci.a);
        const Velocity& vb = reg.get<Velocity>(ci.b);
        const Vec3 v_rel = velocity_at(va, reg.get<Pose>(ci.a).position, ci.point) -
                           velocity_at(vb, reg.get<Pose>(ci.b).position, ci.point);
        anchor.spring += ctx.h * (v_rel - dot(v_rel, ci.normal) * ci.normal);
        if (has_twist[i])
            anchor.twist += ctx.h * dot(va.angular - vb.angular, ci.normal);
    }
}

} // namespace supermodal
