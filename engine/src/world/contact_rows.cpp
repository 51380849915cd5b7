// SPDX-License-Identifier: MIT
// Which of a pair's contact points become soft-contact rows, and the rows' effective masses (the last
// declared in contact_solve.h with the rest of the soft rows).
#include "world/contact_rows.h"

#include "core/parallel.h"
#include "world/constraint_side.h"
#include "world/contact_solve.h"
#include "world/contact_system.h"

#include <algorithm>
#include <limits>
#include <vector>

namespace supermodal
{
namespace
{

// Bodies with an exponent below this have flat faces and rest on a patch; rounder ones touch in one
// point, their deepest (as the support-map manifold treats them): several rows around a sphere's contact
// spot are nearly parallel, and their rounding let a sampled sphere roll off at 1.5 mm/s.
constexpr double k_flat_exponent = 0.8;

// Above this a superquadric is concave: it rests on several separate tips (a star's arms), and one row
// at the deepest did not hold it (measured: an ε 3.5 star dropped at 2 ms still moved at 3.7 cm/s after
// 10 s). Its rows span the tips as a flat face's span its patch.
constexpr double k_concave_exponent = 2.0;

// out.size() of the points, farthest-point first from the deepest: each next the one farthest from
// all taken, so the rows cover the patch evenly.
size_t spread_rows(std::span<const ContactPoint> points, std::span<uint32_t> out)
{
    size_t first = 0;
    for (size_t i = 1; i < points.size(); ++i)
        if (points[i].depth > points[first].depth)
            first = i;
    thread_local std::vector<double> gap; // squared distance to the nearest taken [m²]; kept: no allocation
    gap.assign(points.size(), std::numeric_limits<double>::infinity());
    out[0] = static_cast<uint32_t>(first);
    for (size_t count = 1; count < out.size(); ++count) {
        const Vec3 last = points[out[count - 1]].point;
        size_t best = 0;
        for (size_t i = 0; i < points.size(); ++i) {
            const Vec3 d = points[i].point - last;
            gap[i] = std::min(gap[i], dot(d, d));
            if (gap[i] > gap[best])
                best = i;
        }
        out[count] = static_cast<uint32_t>(best);
    }
    return out.size();
}

// How many rows pair pi may take: none without points or without a body that can move.
size_t pair_row_count(const Registry& reg, const ContactWorld& io, size_t pi)
{
    const BodyPair& pair = io.pairs[pi];
    const bool modal = reg.find<ModalBody>(pair.a) != nullptr || reg.find<ModalBody>(pair.b) != nullptr;
    const size_t n =
        std::min(io.points_of(pi).size(), modal ? k_max_rows_per_modal_pair : k_max_rows_per_pair);
    if (n == 0 || !(reg.get<BodyModel>(pair.a).inv_mass + reg.get<BodyModel>(pair.b).inv_mass > 0.0))
        return 0;
    return n;
}

} // namespace

bool rests_on_a_patch(const BodyModel& m)
{
    if (m.shape.type != ShapeType::Superquadric)
        return false;
    const double lo = std::min(m.shape.epsilon1, m.shape.epsilon2);
    const double hi = std::max(m.shape.epsilon1, m.shape.epsilon2);
    return lo < k_flat_exponent || hi > k_concave_exponent;
}

// Up to out.size() (k_max_rows_per_pair) of the points: the deepest, then each next the one that widens the
// patch most in the contact plane (farthest from the first, then from their line, then from their triangle).
size_t pick_rows(std::span<const ContactPoint> points, bool flat_faces, std::span<uint32_t> out)
{
    if (!flat_faces) {
        out[0] = 0;
        for (size_t i = 1; i < points.size(); ++i)
            if (points[i].depth > points[out[0]].depth)
                out[0] = static_cast<uint32_t>(i);
        return 1;
    }
    if (points.size() <= out.size()) {
        for (size_t i = 0; i < points.size(); ++i)
            out[i] = static_cast<uint32_t>(i);
        return points.size();
    }
    if (out.size() > k_max_rows_per_pair)
        return spread_rows(points, out);
    const Vec3 n = points[0].normal;
    auto flat = [&](size_t i) { return points[i].point - dot(points[i].point, n) * n; };
    size_t count = 0;
    auto take_best = [&](auto&& score) {
        size_t best = 0;
        double best_score = -1.0;
        for (size_t i = 0; i < points.size(); ++i)
            if (const double sc = score(flat(i)); sc > best_score) {
                best = i;
                best_score = sc;
            }
        out[count++] = static_cast<uint32_t>(best);
    };
    take_best([&](const Vec3&) { return 0.0; });
    for (size_t i = 1; i < points.size(); ++i)
        if (points[i].depth > points[out[0]].depth)
            out[0] = static_cast<uint32_t>(i);
    const Vec3 p0 = flat(out[0]);
    take_best([&](const Vec3& p) { return dot(p - p0, p - p0); });
    const Vec3 p1 = flat(out[1]);
    take_best([&](const Vec3& p) { return length(cross(p1 - p0, p - p0)); });
    const Vec3 p2 = flat(out[2]);
    take_best([&](const Vec3& p) {
        return length(cross(p0 - p, p1 - p)) + length(cross(p1 - p, p2 - p)) + length(cross(p2 - p, p0 - p));
    });
    return count;
}

// A pair takes rows when it has points and something that can move: the pairs with rows, in pair
// order, each with its first point, gathered on the threads.
void gather_pairs_with_rows(const Parallel& par, const Registry& reg, ContactWorld& io)
{
    SoftContacts& rows = io.soft;
    std::vector<uint32_t>& counts = rows.pair_rows;
    counts.resize(io.pairs.size());
    auto tally = [&](size_t begin, size_t end) {
        RowTally t;
        for (size_t pi = begin; pi < end; ++pi) {
            counts[pi] = static_cast<uint32_t>(pair_row_count(reg, io, pi));
            t.pairs += counts[pi] > 0 ? 1 : 0;
            t.points += counts[pi];
        }
        return t;
    };
    auto size = [&](const RowTally& total) {
        rows.pairs.resize(total.pairs); // no clear first: every slot is written
        rows.points.resize(total.points);
    };
    auto fill = [&](const RowTally& start, size_t begin, size_t end) {
        RowTally at = start;
        for (size_t pi = begin; pi < end; ++pi) {
            if (counts[pi] == 0)
                continue;
            rows.pairs[at.pairs++] = SoftPair{.pair = static_cast<uint32_t>(pi),
                                              .first = static_cast<uint32_t>(at.points),
                                              .count = counts[pi]};
            at.points += counts[pi];
        }
    };
    par.gather(io.pairs.size(), k_min_rows_per_part, rows.tally, tally, size, fill);
}

double inverse_along(const Mat3& k, const Vec3& d)
{
    const double w = dot(d, k * d);
    return w > 0.0 ? 1.0 / w : 0.0;
}

namespace
{

// 1 / (d·K d) for the rigid bodies alone, from the row's arms r × d and turns I⁻¹(r × d):
// d·K d = (1/ma + 1/mb)|d|² + (ra × d)·Ia⁻¹(ra × d) + (rb × d)·Ib⁻¹(rb × d), the same sum as
// point_mass_inverse's matrix along d without forming it (the rows' set-up was ~2% of a box pile's work in
// those matrices). A side that takes no impulse (inv_mass 0) adds nothing, as there.
double rigid_inverse_along(const SoftPoint& p, const Vec3& d, const Vec3& arm_a, const Vec3& turn_a,
                           const Vec3& arm_b, const Vec3& turn_b)
{
    double w = (p.a.inv_mass + p.b.inv_mass) * dot(d, d);
    if (p.a.inv_mass > 0.0)
        w += dot(arm_a, turn_a);
    if (p.b.inv_mass > 0.0)
        w += dot(arm_b, turn_b);
    return w > 0.0 ? 1.0 / w : 0.0;
}

} // namespace

// The point's effective masses: along the normal with the modes, in the contact plane without them.
void set_point_masses(SoftPoint& p)
{
    p.v_a = p.a.v;
    p.v_b = p.b.v;
    p.inv_mass_a = p.a.inv_mass;
    p.inv_mass_b = p.b.inv_mass;
    p.arm_a = cross(p.a.r, p.normal);
    p.arm_b = cross(p.b.r, p.normal);
    p.turn_a = p.a.inv_inertia * p.arm_a;
    p.turn_b = p.b.inv_inertia * p.arm_b;
    for (int i = 0; i < 2; ++i) {
        p.tangent_arm_a[i] = cross(p.a.r, p.tangent[i]);
        p.tangent_arm_b[i] = cross(p.b.r, p.tangent[i]);
        p.tangent_turn_a[i] = p.a.inv_inertia * p.tangent_arm_a[i];
        p.tangent_turn_b[i] = p.b.inv_inertia * p.tangent_arm_b[i];
    }
    p.tangent_mass[0] = rigid_inverse_along(p, p.tangent[0], p.tangent_arm_a[0], p.tangent_turn_a[0],
                                            p.tangent_arm_b[0], p.tangent_turn_b[0]);
    p.tangent_mass[1] = rigid_inverse_along(p, p.tangent[1], p.tangent_arm_a[1], p.tangent_turn_a[1],
                                            p.tangent_arm_b[1], p.tangent_turn_b[1]);
    p.normal_mass = p.a.modal.active() || p.b.modal.active()
                        ? inverse_along(point_mass_inverse(p.a, p.b), p.normal)
                        : rigid_inverse_along(p, p.normal, p.arm_a, p.turn_a, p.arm_b, p.turn_b);
}

} // namespace supermodal
