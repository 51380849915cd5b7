// SPDX-License-Identifier: MIT
#include "world/contact_solve.h"

#include "core/parallel.h"
#include "dynamics/step_context.h"
#include "world/contact_rows.h"
#include "world/contact_system.h"
#include "world/heavy_on_light.h"
#include "world/islands.h"
#include "world/modal_system.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace supermodal
{
namespace
{

// A pair's friction counts as sliding from this fraction of μ times its normal impulse [-]: the clamp
// of each point leaves the sum a rounding short of the disc when every point is at its own.
constexpr double k_pair_slide_fraction = 0.99;
// The spring's frequency when none is set, as a fraction of the substep rate: stiff enough that a body
// sinks little under its own weight (g/ω²: 0.28 mm at 1/60 s), soft enough that the passes converge
// (measured on a column of five rounded boxes at 1/60 s: a quarter sank 1.2 mm per contact and needed
// 12 passes to stand, a half 0.3 mm and 10).
constexpr double k_auto_frequency_per_rate = 0.5;
// ... and at most this [Hz]: at short steps half the rate is a spring the passes no longer carry up a
// tall stack (the 20-box column stood at 1/240 s on 120 Hz but chattered and fell at 1/1000 s on
// 500 Hz; on 30 or 60 Hz it stands at both), and the sink under load is already small (g/ω², 0.07 mm).
constexpr double k_auto_frequency_max_hz = 60.0;

// Two unit vectors ⟂ n and each other: the world axis least along n, made perpendicular.
void tangents(const Vec3& n, Vec3 out[2])
{
    const Vec3 ax{std::abs(n.x), std::abs(n.y), std::abs(n.z)};
    const Vec3 axis = ax.x <= ax.y && ax.x <= ax.z ? Vec3{1, 0, 0}
                      : ax.y <= ax.z               ? Vec3{0, 1, 0}
                                                   : Vec3{0, 0, 1};
    out[0] = normalized(axis - dot(axis, n) * n);
    out[1] = cross(n, out[0]);
}

void apply(SoftPoint& p, const Vec3& impulse)
{
    push(p.a, impulse, Vec3{});
    push(p.b, -1.0 * impulse, Vec3{});
}

// Friction acts on the bodies' rigid motion only: on a deforming body its rows, solved one after the
// other against the modes' compliance, left a net sideways impulse under a symmetric load (measured: a
// soft block pressed straight down at its top's middle slid 1 to 50 mm at μ 0.8, with the count of
// rows). The modes still take the normal load; their own sideways motion is not resisted.
void apply_friction(SoftPoint& p, const Vec3& impulse)
{
    push_rigid(p.a, impulse);
    push_rigid(p.b, -1.0 * impulse);
}

Vec3 relative_velocity(const SoftPoint& p)
{
    return anchor_velocity(p.a) - anchor_velocity(p.b);
}

Vec3 rigid_relative_velocity(const SoftPoint& p)
{
    return rigid_anchor_velocity(p.a) - rigid_anchor_velocity(p.b);
}

// The point's accumulated impulses (normal and friction) on its bodies: the warm start.
void apply_accumulated(SoftPoint& p)
{
    if (!p.a.modal.active() && !p.b.modal.active()) {
        apply(p, p.normal_impulse * p.normal + p.tangent_impulse[0] * p.tangent[0] +
                     p.tangent_impulse[1] * p.tangent[1]);
        return;
    }
    apply(p, p.normal_impulse * p.normal);
    apply_friction(p, p.tangent_impulse[0] * p.tangent[0] + p.tangent_impulse[1] * p.tangent[1]);
}

// How a pair's rows read and push their bodies: through the sides, modes included.
// Friction reads and pushes the rigid motion alone where a side is modal (apply_friction).
struct AnySides {
    [[nodiscard]] Vec3 velocity(const SoftPoint& p) const { return relative_velocity(p); }
    void apply(SoftPoint& p, const Vec3& impulse) const { supermodal::apply(p, impulse); }
    [[nodiscard]] double normal_velocity(const SoftPoint& p) const { return dot(velocity(p), p.normal); }
    void apply_normal(SoftPoint& p, double impulse) const { apply(p, impulse * p.normal); }
    void tangent_rates(const SoftPoint& p, double out[2]) const
    {
        const Vec3 v = rigid_relative_velocity(p);
        out[0] = dot(v, p.tangent[0]);
        out[1] = dot(v, p.tangent[1]);
    }
    void apply_tangent(SoftPoint& p, double d0, double d1) const
    {
        apply_friction(p, d0 * p.tangent[0] + d1 * p.tangent[1]);
    }
    void apply_friction(SoftPoint& p, const Vec3& impulse) const
    {
        if (p.a.modal.active() || p.b.modal.active())
            supermodal::apply_friction(p, impulse);
        else
            supermodal::apply(p, impulse);
    }
    [[nodiscard]] Vec3 spin(const SoftPoint& p) const
    {
        return angular_velocity(p.a) - angular_velocity(p.b);
    }
    void apply_spin(SoftPoint& p, const Vec3& angular_impulse) const
    {
        push_rigid_spin(p.a, angular_impulse);
        push_rigid_spin(p.b, -1.0 * angular_impulse);
    }
};

// ... or, for two rigid bodies, straight on their velocities: the arithmetic of anchor_velocity() and
// push() without their calls and checks per row (the rows were a quarter of the rounded-box pile's
// step through them). Whether a body can move is noted per pair (SoftPair::free_a), not asked per row: a
// body freezes only between the solver's phases (freeze_non_finite), never inside one pass.
struct RigidSides {
    bool free_a = false, free_b = false; // dynamic and not frozen (SoftPair::free_a)

    explicit RigidSides(const SoftPair& sp) : free_a(sp.free_a), free_b(sp.free_b) {}
    // The normal row through its precomputed arms (SoftPoint::arm_a…): three products per side instead
    // of a cross product and an inertia product (the normal rows were a third of the passes' time).
    [[nodiscard]] static double row_rate(const SoftPoint& p, const Vec3& d, const Vec3& arm_a,
                                         const Vec3& arm_b)
    {
        double rate = 0.0;
        if (p.v_a != nullptr)
            rate += dot(p.v_a->linear, d) + dot(p.v_a->angular, arm_a);
        if (p.v_b != nullptr)
            rate -= dot(p.v_b->linear, d) + dot(p.v_b->angular, arm_b);
        return rate;
    }
    [[nodiscard]] double normal_velocity(const SoftPoint& p) const
    {
        return row_rate(p, p.normal, p.arm_a, p.arm_b);
    }
    void apply_normal(SoftPoint& p, double impulse) const
    {
        if (free_a && p.inv_mass_a != 0.0) {
            p.v_a->linear += (p.inv_mass_a * impulse) * p.normal;
            p.v_a->angular += impulse * p.turn_a;
        }
        if (free_b && p.inv_mass_b != 0.0) {
            p.v_b->linear -= (p.inv_mass_b * impulse) * p.normal;
            p.v_b->angular -= impulse * p.turn_b;
        }
    }
    // The friction rows likewise through theirs (SoftPoint::tangent_arm_a…).
    void tangent_rates(const SoftPoint& p, double out[2]) const
    {
        for (int i = 0; i < 2; ++i)
            out[i] = row_rate(p, p.tangent[i], p.tangent_arm_a[i], p.tangent_arm_b[i]);
    }
    void apply_tangent(SoftPoint& p, double d0, double d1) const
    {
        const Vec3 impulse = d0 * p.tangent[0] + d1 * p.tangent[1];
        if (free_a && p.inv_mass_a != 0.0) {
            p.v_a->linear += p.inv_mass_a * impulse;
            p.v_a->angular += d0 * p.tangent_turn_a[0] + d1 * p.tangent_turn_a[1];
        }
        if (free_b && p.inv_mass_b != 0.0) {
            p.v_b->linear -= p.inv_mass_b * impulse;
            p.v_b->angular -= d0 * p.tangent_turn_b[0] + d1 * p.tangent_turn_b[1];
        }
    }
    [[nodiscard]] static Vec3 spin_of(const Side& s) { return s.v == nullptr ? Vec3{} : s.v->angular; }
    [[nodiscard]] Vec3 spin(const SoftPoint& p) const { return spin_of(p.a) - spin_of(p.b); }
    void apply_spin(SoftPoint& p, const Vec3& angular_impulse) const // as push_rigid_spin()
    {
        if (free_a && p.inv_mass_a != 0.0)
            p.v_a->angular += p.a.inv_inertia * angular_impulse;
        const Vec3 on_b = -1.0 * angular_impulse;
        if (free_b && p.inv_mass_b != 0.0)
            p.v_b->angular += p.b.inv_inertia * on_b;
    }
};

// Whether the side's body can take an impulse: dynamic, and not frozen since the side was made.
bool side_free(const Side& s)
{
    return s.v != nullptr && !(s.m != nullptr && s.m->inv_mass == 0.0);
}

void note_pair_freedom(SoftPair& sp, const SoftContacts& rows)
{
    if (sp.count == 0)
        return;
    const SoftPoint& first = rows.points[sp.first];
    sp.free_a = side_free(first.a);
    sp.free_b = side_free(first.b);
}

// Whether none of the pair's points has a modal side.
bool rigid_rows(const SoftPair& sp, const SoftContacts& rows)
{
    for (uint32_t i = 0; i < sp.count; ++i) {
        const SoftPoint& p = rows.points[sp.first + i];
        if (p.a.modal.active() || p.b.modal.active())
            return false;
    }
    return true;
}

// The pair's spring rate [rad/s]: a static (or kinematic) partner doubles the frequency, since the
// point's effective mass is then the moving body's alone.
double pair_omega(const SoftContactDef& def, double h, bool one_moves)
{
    const double hz = def.frequency_hz > 0.0
                          ? def.frequency_hz
                          : std::min(k_auto_frequency_per_rate / h, k_auto_frequency_max_hz);
    return 2.0 * std::numbers::pi * hz * (one_moves ? 2.0 : 1.0);
}

// The load-tuned spring's ω·h at most this [-] (never below the untuned one) between rigid bodies: a
// spring much stiffer than its substep is a rigid row, which a few passes leave unconverged down a
// stack, and the column's sway grew on that residual (measured at 1/60 s in four solver substeps: 25-
// and 30-box columns fell with the bottom contacts at ω·h ≈ 7, and stood within 1 cm with this bound;
// 3.14–4.4 all held the 20-box column, 2π dropped it). A modal side's row carries its modes' compliance
// and is not bounded: its light surface under a heavy body needs the full tuning (bounded, a soft ball
// on the ground still moved at 4.6 cm/s after 3 s, and a pressed elastic block slid 2.9 mm).
constexpr double k_max_tuned_omega_h = std::numbers::pi;

// A point on a modal body is damped this many times the setting's ratio [-]: its light, compliant
// surface rings under the body's weight, where a rigid body's corners rest. At the rigid pairs' ratio 5
// the soft ball of `ModalWorld.SoftSphereLandsWithoutGainingEnergy` still moved at 1.6 cm/s after 3 s
// and the pressed elastic block of the mould test slid 0.3 mm; at 10 both rest within their tests'
// bounds (1.2 cm/s, 0.1 mm).
constexpr double k_modal_damping_scale = 2.0;

// A point's spring, tuned to the larger of its effective mass and the mass its last load stands for
// (load / g): the bottom contact of a stack carries the whole stack, and a spring tuned to one body
// would sink under it by the stack's weight over m_eff·ω²; tuned to the load, every contact of the
// stack sinks by the same g/ω², whatever its height, up to the bound above.
SoftCoefficients point_soft(double omega, double zeta, double h, const SoftPoint& p, double gravity)
{
    const double load_mass = gravity > 0.0 ? p.normal_impulse / (h * gravity) : 0.0;
    const double scale = p.normal_mass > 0.0 && load_mass > p.normal_mass ? load_mass / p.normal_mass : 1.0;
    const double tuned = omega * std::sqrt(scale);
    if (p.a.modal.active() || p.b.modal.active())
        return make_soft(tuned, k_modal_damping_scale * zeta, h);
    return make_soft(std::min(tuned, std::max(omega, k_max_tuned_omega_h / h)), zeta, h);
}

// One point's rows, not yet warm started.
SoftPoint make_point(Registry& reg, const BodyPair& pair, const ContactPoint& cp, double h,
                     const std::vector<Mat3>& inv_inertia)
{
    SoftPoint p;
    p.a = contact_side(reg, pair.a, cp.point, h, &inv_inertia[pair.a.index]);
    p.b = contact_side(reg, pair.b, cp.point, h, &inv_inertia[pair.b.index]);
    p.normal = cp.normal;
    tangents(cp.normal, p.tangent);
    p.separation = -cp.depth;
    p.depth = cp.depth;
    set_point_masses(p);
    return p;
}

// The point's rows on two rigid bodies whose sides at the pair's first point are `first`: the bodies'
// terms copied from it (no registry lookups per point and side), the arms as contact_side() makes them;
// the same rows as make_point().
SoftPoint make_rigid_point(const SoftPoint& first, const ContactPoint& cp)
{
    auto side_at = [&](const Side& same) {
        Side s;
        s.m = same.m;
        s.p = same.p;
        s.v = same.v;
        s.point = cp.point;
        s.r = cp.point - same.p->position;
        s.inv_inertia = same.inv_inertia;
        s.inv_mass = same.inv_mass;
        return s;
    };
    SoftPoint p;
    p.a = side_at(first.a);
    p.b = side_at(first.b);
    p.normal = cp.normal;
    tangents(cp.normal, p.tangent);
    p.separation = -cp.depth;
    p.depth = cp.depth;
    set_point_masses(p);
    return p;
}

// A point's sides and masses made again where it is (a modal side changes every substep).
void remake_sides(Registry& reg, const BodyPair& pair, SoftPoint& p, double h)
{
    const Vec3 x = p.a.point;
    p.a = contact_side(reg, pair.a, x, h);
    p.b = contact_side(reg, pair.b, x, h);
    set_point_masses(p);
}

// The pair's rows, not yet warm started: its settings, its points' sides and masses.
void make_pair_rows(Registry& reg, ContactWorld& cw, SoftPair& sp, double h)
{
    const BodyPair& pair = cw.pairs[sp.pair];
    const BodyModel& ma = reg.get<BodyModel>(pair.a);
    const BodyModel& mb = reg.get<BodyModel>(pair.b);
    const std::span<const ContactPoint> points = cw.points_of(sp.pair);
    SoftContacts& rows = cw.soft;
    sp.friction = std::sqrt(ma.friction * mb.friction);
    sp.restitution = std::max(ma.restitution, mb.restitution);
    sp.rolling = std::max(ma.rolling_resistance, mb.rolling_resistance);
    sp.node_a = sp.node_b = k_no_node;
    std::array<uint32_t, k_max_rows_per_modal_pair> picked{};
    const std::span<uint32_t> out(picked.data(), sp.count); // the rows prepare_soft_contacts set aside
    sp.count = static_cast<uint32_t>(pick_rows(
        points, sp.count > k_max_rows_per_pair || rests_on_a_patch(ma) || rests_on_a_patch(mb), out));
    // Without modes a body's terms are the same at each of the pair's points.
    const bool rigid = reg.find<ModalBody>(pair.a) == nullptr && reg.find<ModalBody>(pair.b) == nullptr;
    for (size_t i = 0; i < sp.count; ++i)
        rows.points[sp.first + i] = rigid && i > 0
                                        ? make_rigid_point(rows.points[sp.first], points[picked[i]])
                                        : make_point(reg, pair, points[picked[i]], h, rows.inv_inertia);
    if (sp.count > 0) {
        const SoftPoint& first = rows.points[sp.first];
        sp.node_a = takes_impulse(first.a) ? pair.a.index : k_no_node;
        sp.node_b = takes_impulse(first.b) ? pair.b.index : k_no_node;
    }
    sp.rigid = sp.count > 0 && rigid_rows(sp, rows);
    note_pair_freedom(sp, rows);
}

// The pair's springs and last loads: its last normal load shared by the points' weights, its friction
// and rolling loads likewise, turned into today's contact plane. Writes the pair's rows alone; the
// loads reach the bodies in warm_start_soft_pair.
void load_pair(const ContactDef& def, Registry& reg, ContactWorld& cw, SoftPair& sp, double h)
{
    const BodyPair& pair = cw.pairs[sp.pair];
    const BodyModel& ma = reg.get<BodyModel>(pair.a);
    const BodyModel& mb = reg.get<BodyModel>(pair.b);
    SoftContacts& rows = cw.soft;
    const double omega = pair_omega(def.soft, h, ma.inv_mass == 0.0 || mb.inv_mass == 0.0);
    const PairAnchor* old = find_pair_anchor(cw.anchors, pair.key());
    const double w = 1.0 / sp.count; // the rows share the pair's last loads alike
    sp.warm = old != nullptr;
    for (size_t i = 0; i < sp.count; ++i) {
        SoftPoint& p = rows.points[sp.first + i];
        if (old != nullptr)
            p.normal_impulse = w * h * old->normal_load;
        p.soft = point_soft(omega, def.soft.damping_ratio, h, p, rows.gravity);
        if (old == nullptr)
            continue;
        p.tangent_impulse[0] = w * h * dot(old->friction_load, p.tangent[0]);
        p.tangent_impulse[1] = w * h * dot(old->friction_load, p.tangent[1]);
    }
    if (old != nullptr && sp.count > 0) {
        const Vec3 n = rows.points[sp.first].normal;
        sp.stick = old->spring - dot(old->spring, n) * n; // turned into today's contact plane
    }
    if (sp.rolling <= 0.0 || sp.count == 0)
        return;
    const SoftPoint& first = rows.points[sp.first];
    Mat3 mass;
    if (!invert(add_scaled(first.a.inv_inertia, first.b.inv_inertia, 1.0), mass))
        return;
    sp.roll_mass = mass;
    if (old != nullptr) {
        const Vec3 n = first.normal;
        sp.roll_impulse = h * (old->roll_load - dot(old->roll_load, n) * n);
        sp.roll_warm = true;
    }
}

template <class Sides>
void solve_normal(SoftPoint& p, double h, double push_out, bool use_bias, const Sides& sides)
{
    const double vn = sides.normal_velocity(p);
    double bias = 0.0, mass_scale = 1.0, impulse_scale = 0.0;
    if (p.separation > 0.0) {
        bias = p.separation / h; // apart: only the approach that would close the gap within h is stopped
    } else if (use_bias) {
        bias = std::max(p.soft.bias_rate * p.separation, -push_out);
        mass_scale = p.soft.mass_scale;
        impulse_scale = p.soft.impulse_scale;
    }
    const double d = -p.normal_mass * mass_scale * (vn + bias) - impulse_scale * p.normal_impulse;
    const double total = std::max(p.normal_impulse + d, 0.0);
    sides.apply_normal(p, total - p.normal_impulse);
    p.normal_impulse = total;
}

// Both tangent rows, then the pair of impulses clamped to the cone's disc of radius μ·λ_n.
// Static friction is a soft constraint on the pair's slip since it last slid (its stick), with the
// normal spring's coefficients: a velocity-only row lets a resting stack creep at the rate its passes
// leave unconverged (measured: a column of three boxes at 1/60 s crept 1.5 mm/s), the slip pulls it back.
template <class Sides> void solve_friction(SoftPoint& p, SoftPair& sp, bool use_bias, const Sides& sides)
{
    double rates[2];
    sides.tangent_rates(p, rates);
    double t[2];
    for (int i = 0; i < 2; ++i) {
        double rate = rates[i], mass_scale = 1.0, impulse_scale = 0.0;
        if (use_bias) {
            rate += p.soft.bias_rate * dot(sp.stick, p.tangent[i]);
            mass_scale = p.soft.mass_scale;
            impulse_scale = p.soft.impulse_scale;
        }
        t[i] = p.tangent_impulse[i] - p.tangent_mass[i] * mass_scale * rate -
               impulse_scale * p.tangent_impulse[i];
    }
    double& t0 = t[0];
    double& t1 = t[1];
    // Compared squared: a sticking row (most of a resting pile's) takes no square root.
    const double limit = sp.friction * p.normal_impulse;
    const double len2 = t0 * t0 + t1 * t1;
    if (len2 > limit * limit) {
        sp.sliding = true;
        const double len = std::sqrt(len2);
        const double s = len > 0.0 ? limit / len : 0.0;
        t0 *= s;
        t1 *= s;
    }
    sides.apply_tangent(p, t0 - p.tangent_impulse[0], t1 - p.tangent_impulse[1]);
    p.tangent_impulse[0] = t0;
    p.tangent_impulse[1] = t1;
}

// Rolling resistance: the relative rolling spin (in the contact plane) stopped by an angular impulse up
// to ℓ·λ_n, the lever of the normal force about the centre.
template <class Sides> void solve_rolling(SoftPair& sp, SoftContacts& rows, const Sides& sides)
{
    SoftPoint& first = rows.points[sp.first];
    double normal = 0.0;
    for (uint32_t i = 0; i < sp.count; ++i)
        normal += rows.points[sp.first + i].normal_impulse;
    const Vec3 n = first.normal;
    const Vec3 w = sides.spin(first);
    Vec3 total = sp.roll_impulse - sp.roll_mass * (w - dot(w, n) * n);
    total = total - dot(total, n) * n;
    const double limit = sp.rolling * normal;
    if (const double len = length(total); len > limit)
        total = limit > 0.0 ? total * (limit / len) : Vec3{};
    sides.apply_spin(first, total - sp.roll_impulse);
    sp.roll_impulse = total;
}

// Per pair, its normal rows first, so friction is bounded by this pass's normal impulses. They are taken
// first to last and last to first in turn: in one order every pass, Gauss–Seidel leaves the pass's
// unconverged share of the pair's moment on the same side of the patch (the last row solved is met
// exactly), and that bias, with the same sign every substep, leaned the 10-row pyramid out of its plane
// at a steady 2 cm/s at the top until it slept (measured at 1/240 s: 9.1 mm sideways; the rows taken
// last to first leaned it 3.8 mm the other way; alternating, 0.5 mm). A pair's first pass after the
// narrowphase goes first to last (starting last to first, three boxes placed touching moved at 1.2 cm/s
// in the first step at 1/60 s, against under 1 cm/s in one order).
template <class Sides>
void solve_pair_rows(SoftPair& sp, SoftContacts& rows, bool use_bias, const Sides& sides)
{
    for (uint32_t k = 0; k < sp.count; ++k) {
        const uint32_t i = sp.backwards ? sp.count - 1 - k : k;
        solve_normal(rows.points[sp.first + i], rows.h, rows.push_out_speed, use_bias, sides);
    }
    sp.backwards = !sp.backwards;
    for (uint32_t i = 0; i < sp.count; ++i)
        solve_friction(rows.points[sp.first + i], sp, use_bias, sides);
    if (sp.rolling > 0.0 && sp.roll_mass.m[0][0] != 0.0)
        solve_rolling(sp, rows, sides);
}

void solve_pair(SoftPair& sp, SoftContacts& rows, bool use_bias)
{
    if (sp.rigid)
        solve_pair_rows(sp, rows, use_bias, RigidSides(sp));
    else
        solve_pair_rows(sp, rows, use_bias, AnySides{});
}

// A pair's summed normal impulse [N·s] and friction impulse on a [N·s], world.
void pair_impulses(const SoftPair& sp, const SoftContacts& rows, double& out_normal, Vec3& out_friction)
{
    out_normal = 0.0;
    out_friction = Vec3{};
    for (uint32_t i = 0; i < sp.count; ++i) {
        const SoftPoint& p = rows.points[sp.first + i];
        out_normal += p.normal_impulse;
        out_friction += p.tangent_impulse[0] * p.tangent[0] + p.tangent_impulse[1] * p.tangent[1];
    }
}

// What world_contacts() reports for a solved pair: the impulse-weighted point, the summed force.
ContactInfo pair_info(const BodyPair& pair, const SoftPair& sp, const SoftContacts& rows, double& out_normal,
                      Vec3& out_friction)
{
    Vec3 centroid{}, normal_sum{}, force{};
    double weight = 0.0, deepest = 0.0;
    pair_impulses(sp, rows, out_normal, out_friction);
    for (uint32_t i = 0; i < sp.count; ++i) {
        const SoftPoint& p = rows.points[sp.first + i];
        const double w = p.normal_impulse + 1e-12; // untouched pairs still get a centroid
        centroid += w * p.a.point;
        normal_sum += w * p.normal;
        weight += w;
        deepest = std::max(deepest, p.depth);
    }
    force = out_normal * normalized(normal_sum) + out_friction;
    return {.a = pair.a,
            .b = pair.b,
            .point = centroid / weight,
            .normal = normalized(normal_sum),
            .depth = deepest,
            .force_on_a = force / rows.h,
            .point_count = static_cast<int>(sp.count)};
}

} // namespace

void prepare_soft_contacts(const ContactDef& def, const StepContext& ctx, const Parallel& par, Registry& reg,
                           ContactWorld& io)
{
    SoftContacts& rows = io.soft;
    rows.h = ctx.h;
    rows.push_out_speed = def.soft.push_out_speed;
    rows.restitution_speed = def.soft.restitution_speed;
    rows.gravity = length(ctx.gravity);
    rows.up = rows.gravity > 0.0 ? ctx.gravity * (-1.0 / rows.gravity) : Vec3{};
    io.contacts.clear();
    io.max_penetration = 0.0;
    gather_pairs_with_rows(par, reg, io);
    prepare_modal_substep(reg, ctx.h);
    // Once per awake body, not once per pair and side (a body in a pile is in about six pairs). A pair's
    // dynamic bodies are awake: the broadphase wakes every sleeper an awake or moving body reaches.
    rows.inv_inertia.resize(reg.pool().slot_count());
    if (!rows.pairs.empty())
        par.for_parts(reg.store<BodyModel>().size(), k_min_rows_per_part,
                      [&](size_t, size_t begin, size_t end) {
                          reg.each_in<BodyModel, Pose, Sleep>(
                              begin, end, [&](Entity e, const BodyModel& m, const Pose& p, const Sleep& s) {
                                  if (m.motion == MotionType::Dynamic && !s.asleep)
                                      rows.inv_inertia[e.index] = world_inv_inertia(m, p);
                              });
                      });
    // Each pair writes its own rows and only reads the bodies, so the pairs split across the threads
    // with the same bits on any count; the warm start pushes the bodies, so it runs by island with the
    // passes (warm_start_soft_pair).
    par.for_parts(rows.pairs.size(), k_min_rows_per_part, rows.make_balance,
                  [&](size_t, size_t begin, size_t end) {
                      for (size_t i = begin; i < end; ++i)
                          make_pair_rows(reg, io, rows.pairs[i], ctx.h);
                  });
    scale_heavy_on_light(par, rows);
    rows.take_approach = true;
    par.for_parts(rows.pairs.size(), k_min_rows_per_part, rows.load_balance,
                  [&](size_t, size_t begin, size_t end) {
                      for (size_t i = begin; i < end; ++i)
                          load_pair(def, reg, io, rows.pairs[i], ctx.h);
                  });
}

namespace
{

// Soft pair k's rows for another solver substep on the same points (refresh_soft_contacts).
void refresh_pair(Registry& reg, ContactWorld& io, size_t k, double h)
{
    SoftContacts& rows = io.soft;
    SoftPair& sp = rows.pairs[k];
    const BodyPair& pair = io.pairs[sp.pair];
    sp.sliding = false;
    sp.warm = true;
    sp.roll_warm = sp.count > 0 && sp.rolling > 0.0;
    note_pair_freedom(sp, rows);
    for (uint32_t i = 0; i < sp.count; ++i) {
        SoftPoint& p = rows.points[sp.first + i];
        if (p.a.modal.active() || p.b.modal.active())
            remake_sides(reg, pair, p, h); // the modes' drift is this substep's
    }
}

} // namespace

void refresh_soft_contacts(const StepContext& ctx, const Parallel& par, Registry& reg, ContactWorld& io)
{
    SoftContacts& rows = io.soft;
    io.contacts.clear();
    io.max_penetration = 0.0;
    prepare_modal_substep(reg, ctx.h);
    rows.take_approach = false; // the approach stays the narrowphase substep's
    par.for_parts(rows.pairs.size(), k_min_rows_per_part, rows.refresh_balance,
                  [&](size_t, size_t begin, size_t end) {
                      for (size_t k = begin; k < end; ++k)
                          refresh_pair(reg, io, k, ctx.h);
                  });
}

void warm_start_soft_pair(void* ctx, size_t i)
{
    SoftContacts& rows = *static_cast<SoftContacts*>(ctx);
    SoftPair& sp = rows.pairs[i];
    for (uint32_t k = 0; k < sp.count; ++k) {
        SoftPoint& p = rows.points[sp.first + k];
        if (rows.take_approach)
            p.approach = dot(relative_velocity(p), p.normal); // after the warm starts of the rows before
        if (sp.warm)
            apply_accumulated(p);
    }
    if (sp.roll_warm) {
        SoftPoint& first = rows.points[sp.first];
        push_rigid_spin(first.a, sp.roll_impulse);
        push_rigid_spin(first.b, -1.0 * sp.roll_impulse);
    }
}

void note_frozen_bodies(SoftContacts& io)
{
    for (SoftPair& sp : io.pairs)
        note_pair_freedom(sp, io);
}

ExtraRows soft_contact_rows(SoftContacts& rows, bool use_bias)
{
    auto nodes = [](void* ctx, size_t i, uint32_t& a, uint32_t& b) {
        const SoftPair& sp = static_cast<SoftContacts*>(ctx)->pairs[i];
        a = sp.node_a;
        b = sp.node_b;
    };
    auto biased = [](void* ctx, size_t i) {
        auto& rows = *static_cast<SoftContacts*>(ctx);
        solve_pair(rows.pairs[i], rows, true);
    };
    auto relaxed = [](void* ctx, size_t i) {
        auto& rows = *static_cast<SoftContacts*>(ctx);
        solve_pair(rows.pairs[i], rows, false);
    };
    return {.count = rows.pairs.size(),
            .nodes = nodes,
            .solve = use_bias ? +biased : +relaxed,
            .warm_start = use_bias ? &warm_start_soft_pair : nullptr,
            .ctx = &rows};
}

namespace
{

// The pair's points' gaps as the bodies moved them, and its slip while it sticks.
void advance_pair(SoftPair& sp, SoftContacts& io)
{
    // The points moved with the solved velocities over the substep; the rotation's change of the lever
    // arms is second order in h.
    for (uint32_t i = 0; i < sp.count; ++i) {
        SoftPoint& p = io.points[sp.first + i];
        p.separation += io.h * dot(relative_velocity(p), p.normal);
    }
    // A pair slides when its friction as a whole reached μ times its normal load: one corner at its
    // disc (a rocking face unloads a corner) is not the face sliding, and forgetting the stick then
    // let a block pulled well under μ·m·g creep at 0.27 mm/s (measured). Pairs with a modal body keep
    // the point's rule: with the pair's, an elastic block pressed straight down slid 0.14 mm, not 0.05.
    if (sp.sliding && sp.rigid) {
        double normal = 0.0;
        Vec3 friction{};
        pair_impulses(sp, io, normal, friction);
        sp.sliding = length(friction) >= k_pair_slide_fraction * sp.friction * normal;
    }
    if (sp.sliding) {
        sp.stick = Vec3{}; // it slid: static friction starts again from here
        return;
    }
    Vec3 slip{};
    for (uint32_t i = 0; i < sp.count; ++i) {
        const SoftPoint& p = io.points[sp.first + i];
        const Vec3 v = rigid_relative_velocity(p);
        slip += (io.h / sp.count) * (v - dot(v, p.normal) * p.normal);
    }
    sp.stick += slip;
}

} // namespace

void advance_soft_separations(const Parallel& par, SoftContacts& io)
{
    // Each pair reads the bodies and writes its own rows: any threads, the same bits.
    par.for_parts(io.pairs.size(), k_min_rows_per_part, io.advance_balance,
                  [&](size_t, size_t begin, size_t end) {
                      for (size_t i = begin; i < end; ++i)
                          advance_pair(io.pairs[i], io);
                  });
}

void restitute_soft_pair(void* rows, size_t pair)
{
    SoftContacts& io = *static_cast<SoftContacts*>(rows);
    const SoftPair& sp = io.pairs[pair];
    if (sp.restitution == 0.0)
        return;
    for (uint32_t i = 0; i < sp.count; ++i) {
        SoftPoint& p = io.points[sp.first + i];
        // A deforming body bounces through its modes; the point's approach speed includes their
        // ringing, and a bounce target on it pumped a modal ball to 3.3× its drop energy (measured).
        if (p.approach > -io.restitution_speed || p.normal_impulse == 0.0 || p.a.modal.active() ||
            p.b.modal.active())
            continue;
        const double vn = dot(relative_velocity(p), p.normal);
        const double d = -p.normal_mass * (vn + sp.restitution * p.approach);
        const double total = std::max(p.normal_impulse + d, 0.0);
        apply(p, (total - p.normal_impulse) * p.normal);
        p.normal_impulse = total;
    }
}

namespace
{

// The normal forces the rows put on modal bodies' modes, lumped on their lattice nodes (the static
// correction and the accuracy report read them; friction on a modal side moves its rigid part only). In
// pair order on this thread: a body in several pairs sums its loads in one order.
void lump_modal_forces(Registry& reg, const ContactWorld& io)
{
    const SoftContacts& rows = io.soft;
    for (const SoftPair& sp : rows.pairs) {
        const BodyPair& pair = io.pairs[sp.pair];
        for (uint32_t i = 0; i < sp.count; ++i) {
            const SoftPoint& p = rows.points[sp.first + i];
            if (p.normal_impulse == 0.0)
                continue;
            const Vec3 f = (p.normal_impulse / rows.h) * p.normal;
            const double work = p.normal_impulse / rows.h * std::max(p.depth, 0.0);
            if (p.a.modal.active()) {
                modal_add_solved_load(reg, pair.a, p.a.point, f);
                modal_add_spring_work(reg, pair.a, work);
            }
            if (p.b.modal.active()) {
                modal_add_solved_load(reg, pair.b, p.b.point, -1.0 * f);
                modal_add_spring_work(reg, pair.b, work);
            }
        }
    }
}

// Speculative rows alone (a gap, no push) are not a contact: no events, not in the list.
bool is_contact(const ContactInfo& info, double normal_force)
{
    return info.depth > 0.0 || normal_force != 0.0;
}

// Soft pair i's report, anchor and touch from its impulses over the substep h [s] (its own slots).
void finish_pair(ContactWorld& io, size_t i, double h)
{
    const SoftContacts& rows = io.soft;
    const SoftPair& sp = rows.pairs[i];
    const BodyPair& pair = io.pairs[sp.pair];
    double normal = 0.0;
    Vec3 friction{};
    ContactInfo& info = io.soft.infos[i];
    info = pair_info(pair, sp, rows, normal, friction);
    PairAnchor& anchor = io.next_anchors[i];
    anchor = PairAnchor{.key = pair.key()};
    anchor.normal_load = normal / h;
    anchor.friction_load = friction / h;
    anchor.roll_load = sp.roll_impulse / h;
    anchor.spring = sp.stick;
    // Each pair has its own slot of the step's touches.
    if (is_contact(info, anchor.normal_load))
        accumulate_touch(io.events, sp.pair, info, anchor.normal_load, h);
}

} // namespace

void finish_soft_contacts(const StepContext& ctx, const Parallel& par, Registry& reg, ContactWorld& io)
{
    SoftContacts& rows = io.soft;
    std::vector<PairAnchor>& anchors = io.next_anchors;
    // The pairs' sums on the threads (each writes its own slots), then the lists in pair order.
    anchors.resize(rows.pairs.size());
    rows.infos.resize(rows.pairs.size());
    par.for_parts(rows.pairs.size(), k_min_rows_per_part, rows.finish_balance,
                  [&](size_t, size_t begin, size_t end) {
                      for (size_t i = begin; i < end; ++i)
                          finish_pair(io, i, ctx.h);
                  });
    for (size_t i = 0; i < rows.pairs.size(); ++i) {
        const ContactInfo& info = rows.infos[i];
        if (!is_contact(info, anchors[i].normal_load))
            continue;
        io.contacts.push_back(info);
        io.max_penetration = std::max(io.max_penetration, info.depth);
    }
    io.anchors.swap(anchors);
    lump_modal_forces(reg, io);
}

} // namespace supermodal
