// SPDX-License-Identifier: MIT
// Constraint springs for one substep. Each spring acts through the effective mass of its own error
// direction(s) (the 3×3 point mass matrix K⁻¹ for a ball joint), so its frequency is what the user
// asked for whatever the masses and lever arms. The spring–damper is integrated implicitly (backward
// Euler on the constraint coordinate, Catto's "soft constraint" coefficients), so a stiff spring or
// a light part between heavy ones cannot blow up; a few Gauss–Seidel passes over all constraints let
// chains carry loads (a heavy part hanging below a light one) without the light part's mass limiting
// the stiffness, as an explicit penalty spring would.
#include "world/constraint_side.h"
#include "world/constraint_system.h"
#include "world/integrate.h"
#include "world/sleep.h"

#include <algorithm>
#include <cmath>
#include <span>

namespace supermodal
{
namespace
{

// Below this norm of the twist part (a swing within ~11° of a half turn) the twist is not measured.
constexpr double k_twist_singular = 0.1;

// Rotation vector of a unit quaternion, taking the short way round (|angle| ≤ π).
Vec3 rotation_vector(Quat q)
{
    if (q.w < 0.0)
        q = Quat{-q.w, -q.x, -q.y, -q.z};
    const Vec3 v{q.x, q.y, q.z};
    const double s = length(v);
    if (s < 1e-12)
        return 2.0 * v;
    return (2.0 * std::atan2(s, q.w) / s) * v;
}

// Swing and twist of the relative rotation r (a's frame) about unit axis: r = swing·twist.
void swing_twist(const Quat& r, const Vec3& axis, Vec3& out_swing, double& out_twist)
{
    const double proj = r.x * axis.x + r.y * axis.y + r.z * axis.z;
    Quat twist{r.w, proj * axis.x, proj * axis.y, proj * axis.z};
    const double n = norm(twist);
    // Near a half-turn swing (n → 0) the split is singular and the twist meaningless: report none
    // rather than a twist that jumps between substeps (it pumped energy into a joint without swing limit).
    twist = n > k_twist_singular ? Quat{twist.w / n, twist.x / n, twist.y / n, twist.z / n} : Quat{};
    out_twist = dot(rotation_vector(twist), axis);
    out_swing = rotation_vector(r * conjugate(twist));
}

// Joint limits and joint friction turn the material at the anchor: on a modal body the modes' rotation
// there too (ψ, as a weld holds it), else a limit held the body's frame while its modes bent past it.
bool is_modal(const Side& s)
{
    return s.modal.active() && !s.modal->psi.empty();
}

// An angular impulse L [N·m·s] on the side's material at the anchor.
void push_spin(Side& s, const Vec3& angular_impulse)
{
    if (is_modal(s))
        push(s, Vec3{}, angular_impulse);
    else
        push_rigid_spin(s, angular_impulse);
}

// Spin change of b relative to a per unit angular impulse about unit `axis` [1/(kg·m²)].
double inverse_inertia_along(const Side& a, const Side& b, const Vec3& axis)
{
    if (is_modal(a) || is_modal(b))
        return dot(axis, anchor_inertia_inverse(a, b) * axis);
    return dot(axis, a.inv_inertia * axis) + dot(axis, b.inv_inertia * axis);
}

// Joint limits start acting this far before the limit [rad] (speculatively, see solve_angular).
constexpr double k_limit_margin = 0.1;

using Row = ConstraintRow;

// Applies the row's accumulated impulses times `sign` (−1 takes them back).
void apply_row(Row& r, double sign)
{
    push(r.a, sign * r.impulse, sign * -1.0 * r.ang_impulse);
    push(r.b, sign * -1.0 * r.impulse, sign * r.ang_impulse);
    for (int i = 0; i < 2; ++i) {
        push_spin(r.a, sign * r.limit_impulse[i] * r.limit_axis[i]);
        push_spin(r.b, -sign * r.limit_impulse[i] * r.limit_axis[i]);
    }
    push_spin(r.a, -sign * r.friction_impulse);
    push_spin(r.b, sign * r.friction_impulse);
}

void solve_linear(Row& r, const ConstraintDef& d)
{
    const Vec3 rate = anchor_velocity(r.a) - anchor_velocity(r.b);
    Vec3 dj{};
    if (d.type == ConstraintType::Distance) {
        const double cn = dot(r.normal, rate) + r.soft.bias_rate * dot(r.normal, r.gap);
        dj = (-r.mass.m[0][0] * r.soft.mass_scale * cn - r.soft.impulse_scale * dot(r.normal, r.impulse)) *
             r.normal;
    } else {
        dj = -1.0 * (r.soft.mass_scale * (r.mass * (rate + r.soft.bias_rate * r.gap))) -
             r.soft.impulse_scale * r.impulse;
    }
    r.impulse += dj;
    push(r.a, dj, Vec3{});
    push(r.b, -1.0 * dj, Vec3{});
}

void solve_angular(Row& r)
{
    if (r.has_ang_mass) {
        const Vec3 rate = anchor_spin(r.b) - anchor_spin(r.a);
        const Vec3 dl = -1.0 * (r.soft.mass_scale * (r.ang_mass * (rate + r.soft.bias_rate * r.theta))) -
                        r.soft.impulse_scale * r.ang_impulse;
        r.ang_impulse += dl;
        push(r.a, Vec3{}, -1.0 * dl);
        push(r.b, Vec3{}, dl);
    }
    for (int i = 0; i < 2; ++i) {
        if (!r.limit_active[i])
            continue;
        const Vec3& axis = r.limit_axis[i];
        const double rate = dot(anchor_spin(r.b) - anchor_spin(r.a), axis);
        // Impulse on b against the axis; accumulated ≥ 0 so the limit pushes back but never pulls.
        // Past the limit it is the soft spring; short of it, only the approach that would cross the
        // limit within this substep is removed (speculative, as for contact), so a joint resting at
        // its limit does not chatter between free and pushed.
        const double excess = r.limit_excess[i];
        const double want = excess > 0.0
                                ? r.limit_mass[i] * r.soft.mass_scale * (rate + r.soft.bias_rate * excess) -
                                      r.soft.impulse_scale * r.limit_impulse[i]
                                : r.limit_mass[i] * (rate + excess / r.h);
        const double total = std::max(0.0, r.limit_impulse[i] + want);
        const double dl = total - r.limit_impulse[i];
        r.limit_impulse[i] = total;
        push_spin(r.a, dl * axis);
        push_spin(r.b, -dl * axis);
    }
}

// The last substep's impulses, applied first: over substeps they converge to the load a spring carries,
// so chains hold without many passes (Box2D's warm starting).
void warm_start(Row& r)
{
    const ConstraintState& st = *r.state;
    const ConstraintDef& d = r.model->def;
    if (r.has_mass)
        r.impulse = d.type == ConstraintType::Distance ? dot(st.impulse, r.normal) * r.normal : st.impulse;
    if (r.has_ang_mass)
        r.ang_impulse = st.ang_impulse;
    for (int i = 0; i < 2; ++i)
        // As a vector, projected on today's axis: the swing axis turns, and the twist axis flips sign
        // as the twist passes zero; a scalar would push the old amount along the new axis.
        r.limit_impulse[i] =
            r.limit_active[i] ? std::max(0.0, dot(st.limit_impulse[i], r.limit_axis[i])) : 0.0;
    apply_row(r, 1.0);
}

// Inverse inertia of a dynamic side about its anchor [1/(kg·m²)]: I + m(|r|²·1 − r rᵀ) (parallel axes),
// inverted; zero for the world and non-dynamic bodies.
Mat3 inverse_inertia_about_anchor(const Side& s)
{
    Mat3 inertia, out;
    if (s.inv_mass == 0.0 || !invert(s.inv_inertia, inertia))
        return out;
    const Mat3 arm = skew(s.r) * skew(s.r); // r rᵀ − |r|²·1
    return invert(add_scaled(inertia, arm, -1.0 / s.inv_mass), out) ? out : Mat3{};
}

// Joint friction: a torque −C·(ω_b − ω_a) with C = rate·(Ia,p⁻¹ + Ib,p⁻¹)⁻¹ from the parts' inertias
// about the joint, so a limb swinging on the joint slows at `rate` (angular_damping [1/s]). It is a soft
// row solved with the joint's other rows (ω_rel + (h·C)⁻¹·λ = 0: implicit, any rate is stable). An
// impulse that removed the relative spin about the centres of mass alone, before the passes, was mostly
// undone by the ball joint: measured on a hanging three-link arm, its swing kept 1 cm/s after 7 s.
void setup_friction(Row& r, double rate, double h)
{
    Mat3 pivot_inertia, compliance, mass;
    const Mat3 k_pivot =
        add_scaled(inverse_inertia_about_anchor(r.a), inverse_inertia_about_anchor(r.b), 1.0);
    if (!invert(k_pivot, pivot_inertia))
        return;
    if (!invert(add_scaled(Mat3{}, pivot_inertia, rate * h), compliance))
        return;
    const Mat3 k = is_modal(r.a) || is_modal(r.b) ? anchor_inertia_inverse(r.a, r.b)
                                                  : add_scaled(r.a.inv_inertia, r.b.inv_inertia, 1.0);
    if (!invert(add_scaled(k, compliance, 1.0), mass))
        return;
    r.has_friction = true;
    r.friction_compliance = compliance;
    r.friction_mass = mass;
}

void solve_friction(Row& r)
{
    if (!r.has_friction)
        return;
    const Vec3 spin = anchor_spin(r.b) - anchor_spin(r.a);
    const Vec3 dl = -1.0 * (r.friction_mass * (spin + r.friction_compliance * r.friction_impulse));
    r.friction_impulse += dl;
    push_spin(r.a, -1.0 * dl);
    push_spin(r.b, dl);
}

// The linear row: the anchors' gap and its effective mass (along the axis for a distance constraint).
void prepare_linear(Row& r, const ConstraintModel& c, ConstraintState& st)
{
    const Vec3 gap = r.a.point - r.b.point;
    if (c.def.type == ConstraintType::Distance) {
        const double len = length(gap);
        st.error.linear = std::abs(len - c.rest_length);
        if (len > 1e-12) {
            r.normal = gap / len;
            r.gap = (len - c.rest_length) * r.normal;
            const double k_inv = dot(r.normal, point_mass_inverse(r.a, r.b) * r.normal);
            r.has_mass = k_inv > 0.0;
            r.mass.m[0][0] = r.has_mass ? 1.0 / k_inv : 0.0;
        }
    } else {
        st.error.linear = length(gap);
        r.gap = gap;
        r.has_mass = invert(point_mass_inverse(r.a, r.b), r.mass);
    }
}

// A one-sided limit row in `slot` about unit world axis_w, active from k_limit_margin before the limit
// (excess [rad], > 0 past it).
void add_limit(Row& r, ConstraintState& st, int slot, const Vec3& axis_w, double excess)
{
    if (excess <= -k_limit_margin)
        return;
    st.error.angular = std::max(st.error.angular, excess);
    const double k_inv = inverse_inertia_along(r.a, r.b, axis_w);
    if (!(k_inv > 0.0))
        return;
    r.limit_active[slot] = true;
    r.limit_axis[slot] = axis_w;
    r.limit_excess[slot] = excess;
    r.limit_mass[slot] = 1.0 / k_inv;
}

// A ball joint's swing and twist limits, from the relative rotation in a's frame.
void prepare_limits(Row& r, const ConstraintModel& c, ConstraintState& st)
{
    const ConstraintDef& d = c.def;
    const Quat qa = anchor_orientation(r.a), qb = anchor_orientation(r.b);
    const Quat rel = conjugate(qa) * qb * conjugate(c.rest_relative); // a's frame
    Vec3 swing{};
    double twist = 0.0;
    swing_twist(rel, c.axis_a, swing, twist);
    const double swing_angle = length(swing);
    if (d.swing_limit >= 0.0 && swing_angle > 1e-12)
        add_limit(r, st, 0, rotate(qa, swing / swing_angle), swing_angle - d.swing_limit);
    if (d.twist_limit >= 0.0) {
        // The twist turns about the axis as each body carries it (a's axis, and the same axis swung
        // onto b): their bisector is the direction whose relative spin changes the twist; a's axis
        // alone is wrong once the joint swings and pumped energy into a twist-limited joint.
        const Vec3 axis_on_a = rotate(qa, c.axis_a);
        const Vec3 axis_on_b = rotate(qa, rotate(quat_from_rotation_vector(swing), c.axis_a));
        const Vec3 bisector = axis_on_a + axis_on_b;
        if (length(bisector) > 1e-6) {
            const Vec3 axis_w = normalized(bisector);
            add_limit(r, st, 1, twist >= 0.0 ? axis_w : -1.0 * axis_w, std::abs(twist) - d.twist_limit);
        }
    }
}

// Reads the bodies' poses, models and modal amplitudes, never what the rows push (velocities, modal
// loads), and writes only the row and its constraint's state: rows can be prepared in any order, on
// any thread, before any of them pushes.
bool prepare(Row& r, Registry& bodies, double h)
{
    const ConstraintModel& c = *r.model;
    ConstraintState& st = *r.state;
    const ConstraintDef& d = c.def;
    // A weld holds the material's orientation at the anchors, and limits and joint friction turn it, so
    // they need the modes' rotation there.
    const bool weld = d.type == ConstraintType::Weld;
    const bool limits = d.type == ConstraintType::Point && (d.swing_limit >= 0.0 || d.twist_limit >= 0.0);
    const bool material_rotation = weld || limits || d.angular_damping > 0.0;
    make_side(bodies, d.a, c.local_a, h, material_rotation, r.a);
    make_side(bodies, d.b, c.local_b, h, material_rotation, r.b);
    if (r.a.m == nullptr)
        return false;
    r.soft = make_soft(2.0 * M_PI * d.frequency_hz, d.damping_ratio, h);
    r.h = h;
    prepare_linear(r, c, st);
    if (weld) {
        // Orientation error of b's material against where the weld holds it, as a world rotation vector.
        r.theta =
            rotation_vector(anchor_orientation(r.b) * conjugate(anchor_orientation(r.a) * c.rest_relative));
        st.error.angular = length(r.theta);
        r.has_ang_mass = invert(anchor_inertia_inverse(r.a, r.b), r.ang_mass);
    } else if (limits) {
        prepare_limits(r, c, st);
    }
    if (d.angular_damping > 0.0)
        setup_friction(r, d.angular_damping, h);
    return true;
}

// The island node of a side: its body when the row's pushes change it (velocity or modes), else none.
uint32_t island_node(const Side& s, Entity body)
{
    return takes_impulse(s) ? body.index : k_no_node;
}

// This substep's rows, one per unbroken constraint in entity index order (so the result does not depend
// on the store's creation/destruction history), not yet prepared. Returns their count.
size_t collect_rows(const Registry& bodies, ConstraintWorld& cw, ConstraintScratch& scratch)
{
    const std::vector<Entity>& stored = cw.reg.store<ConstraintModel>().entities();
    scratch.order.assign(stored.begin(), stored.end());
    std::sort(scratch.order.begin(), scratch.order.end(),
              [](Entity x, Entity y) { return x.index < y.index; });
    scratch.rows.resize(std::max(scratch.rows.size(), scratch.order.size()));
    size_t n = 0;
    for (Entity ce : scratch.order) {
        // Both ends asleep (or one asleep, the other fixed): the joint sleeps with them, its state kept.
        const ConstraintDef& d = cw.reg.get<ConstraintModel>(ce).def;
        if (is_asleep(bodies, d.a) || is_asleep(bodies, d.b))
            continue;
        ConstraintState& st = cw.reg.get<ConstraintState>(ce);
        st.force_on_a = Vec3{};
        st.error = ConstraintError{};
        if (st.broken)
            continue;
        Row& r = scratch.rows[n++];
        // The sides are made afresh by prepare() in place, keeping their modal buffers.
        static_cast<ConstraintRowTerms&>(r) = ConstraintRowTerms{};
        r.id = ce;
        r.model = &cw.reg.get<ConstraintModel>(ce);
        r.state = &st;
    }
    return n;
}

// Prepares the rows on any thread (each writes only itself and its constraint's state), then on this
// one, in row order, the largest error and the islands.
void prepare_rows(double h, const Parallel& par, Registry& bodies, std::span<Row> rows, ConstraintWorld& cw,
                  IslandBuilder& islands, const ExtraRows& extra)
{
    par.for_parts(rows.size(), k_min_rows_per_part, [&](size_t, size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i)
            rows[i].active = prepare(rows[i], bodies, h);
    });
    islands.clear();
    for (const Row& r : rows) {
        cw.max_error = std::max(cw.max_error, r.state->error.linear);
        // An inactive row pushes nothing: an island of its own, skipped.
        if (r.active)
            islands.add_row(island_node(r.a, r.model->def.a), island_node(r.b, r.model->def.b));
        else
            islands.add_row(k_no_node, k_no_node);
    }
    for (size_t i = 0; i < extra.count; ++i) {
        uint32_t a = k_no_node, b = k_no_node;
        extra.nodes(extra.ctx, i, a, b);
        islands.add_row(a, b);
    }
    islands.build();
}

// One Gauss–Seidel update of an active row.
void solve_row(Row& r)
{
    if (r.has_mass)
        solve_linear(r, r.model->def);
    solve_angular(r);
    solve_friction(r);
}

// fn(index, island) for every island, on the parts of `par` (an island is never split).
template <class Fn> void for_islands(const Parallel& par, const IslandBuilder& islands, size_t rows, Fn&& fn)
{
    const size_t parts = std::min(par.part_count(rows, k_min_rows_per_part), islands.island_count());
    par.for_parts(parts, 1, [&](size_t part, size_t, size_t) {
        const auto [first, last] = islands.islands_of_part(part, parts);
        for (size_t i = first; i < last; ++i)
            fn(i, islands.island(i));
    });
}

// Splits each island of at least two slabs' rows by its bodies' positions (IslandSlabs).
void split_large_islands(const Registry& bodies, bool enabled, const Parallel& par, ConstraintScratch& s)
{
    const IslandBuilder& islands = s.islands;
    s.island_split.assign(islands.island_count(), k_not_split);
    s.split_count = 0;
    if (!enabled)
        return;
    auto position = [&](uint32_t node) { return bodies.get<Pose>(bodies.pool().at(node)).position; };
    for (size_t i = 0; i < islands.island_count(); ++i) {
        const std::span<const uint32_t> rows = islands.island(i);
        const size_t slabs = std::min(rows.size() / k_rows_per_slab, k_max_slabs);
        if (slabs < 2)
            continue;
        if (s.slabs.size() <= s.split_count)
            s.slabs.emplace_back();
        s.slabs[s.split_count].build(rows, islands, slabs, position, par);
        s.island_split[i] = static_cast<uint32_t>(s.split_count++);
    }
}

// `passes` times fn(row) over every row: each island in its rows' global order, on one thread, as the
// serial loop over all rows does to each of the island's bodies since no other row touches them; a split
// island phase by phase, a phase's groups on the threads. The result does not depend on the threads.
template <class Fn>
void run_islands(const Parallel& par, const ConstraintScratch& s, size_t rows, int passes, Fn&& fn)
{
    for_islands(par, s.islands, rows, [&](size_t index, std::span<const uint32_t> island) {
        if (s.island_split[index] != k_not_split)
            return;
        for (int pass = 0; pass < passes; ++pass)
            for (uint32_t i : island)
                fn(i);
    });
    for (size_t k = 0; k < s.split_count; ++k) {
        const IslandSlabs& split = s.slabs[k];
        for (int pass = 0; pass < passes; ++pass)
            for (size_t p = 0; p < IslandSlabs::k_phases; ++p) {
                // Not a structured binding: lambdas may not capture those before clang 16.
                const std::pair<size_t, size_t> groups = split.phase(p);
                const size_t first = groups.first;
                par.for_parts(groups.second - first, 1, [&](size_t, size_t begin, size_t end) {
                    for (size_t g = first + begin; g < first + end; ++g)
                        for (uint32_t i : split.group(g))
                            fn(i);
                });
            }
    }
}

// On the stepping thread in row order: breaks, then the impulses become the state that warm-starts the
// next substep.
void finish_rows(double h, std::span<Row> rows, ConstraintWorld& cw)
{
    for (Row& r : rows) {
        if (!r.active)
            continue;
        ConstraintState& st = *r.state;
        // A spring that would need more than its break force snaps instead of pulling: its impulses
        // are taken back, so the parts fly apart with the momentum they had.
        if (length(r.impulse) > h * r.model->def.break_force) {
            apply_row(r, -1.0);
            st = ConstraintState{.broken = true, .error = st.error};
            ++cw.broken_count;
            continue;
        }
        st.force_on_a = r.impulse / h;
        st.impulse = r.impulse;
        st.ang_impulse = r.ang_impulse;
        st.limit_impulse[0] = r.limit_impulse[0] * r.limit_axis[0];
        st.limit_impulse[1] = r.limit_impulse[1] * r.limit_axis[1];
    }
}

} // namespace

void apply_constraint_forces(const StepContext& ctx, const Parallel& par, Registry& bodies,
                             ConstraintWorld& cw, ConstraintScratch& scratch, ExtraRows extra)
{
    cw.max_error = 0.0;
    const size_t n = collect_rows(bodies, cw, scratch);
    scratch.row_count = n;
    const std::span<Row> rows(scratch.rows.data(), n);
    prepare_rows(ctx.h, par, bodies, rows, cw, scratch.islands, extra);
    split_large_islands(bodies, cw.split_islands, par, scratch);
    const size_t total = n + extra.count;
    if (extra.warm_start != nullptr && extra.count > 0)
        run_islands(par, scratch, total, 1, [&](uint32_t i) {
            if (i >= n)
                extra.warm_start(extra.ctx, i - n);
        });
    if (n > 0) // the warm start first, on every island
        run_islands(par, scratch, total, 1, [&](uint32_t i) {
            if (i < n && rows[i].active)
                warm_start(rows[i]);
        });
    run_islands(par, scratch, total, cw.iterations, [&](uint32_t i) {
        if (i >= n)
            extra.solve(extra.ctx, i - n);
        else if (rows[i].active)
            solve_row(rows[i]);
    });
    finish_rows(ctx.h, rows, cw);
}

void solve_extra_rows(const Parallel& par, const ConstraintScratch& scratch, size_t extra_count, int passes,
                      void (*fn)(void* ctx, size_t i), void* ctx)
{
    const size_t n = scratch.row_count;
    run_islands(par, scratch, n + extra_count, passes, [&](uint32_t i) {
        if (i >= n)
            fn(ctx, i - n);
    });
}

} // namespace supermodal
