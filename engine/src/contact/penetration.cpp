// SPDX-License-Identifier: MIT
#include "contact/penetration.h"

#include "contact/mpr.h"
#include "geometry/support_internal.h"

#include <algorithm>
#include <cmath>

namespace supermodal
{
namespace
{

// Largest turn of the normal in one Newton step [rad]; a step that does not improve is retried at a
// quarter of its length (flat faces make the map from normal to support point steep).
constexpr double k_max_turn = 0.25;
constexpr double k_shrink = 0.25;

// One body's support along a world direction, relative to `origin` (A's position, so that far-away
// pairs lose no digits), with its world Jacobian.
struct WorldJet {
    Vec3 point{};
    Mat3 jacobian{};
};

WorldJet world_jet(const BodyView& body, const Mat3& rotation, const Vec3& origin, const Vec3& dir)
{
    const Collider& c = *body.collider;
    const SupportJet jet = support_jet(c.shape, transpose(rotation) * dir);
    return {(body.position - origin) + rotation * (jet.point - c.com_shape),
            rotation * jet.jacobian * transpose(rotation)};
}

void tangent_basis(const Vec3& n, Vec3& t1, Vec3& t2)
{
    const Vec3 axis =
        std::abs(n.x) < 0.57735 ? Vec3{1, 0, 0} : (std::abs(n.y) < 0.57735 ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
    t1 = normalized(cross(n, axis));
    t2 = cross(n, t1);
}

struct Query {
    const BodyView* a;
    const BodyView* b;
    PenetrationTarget target;
    Mat3 ra, rb;
    Vec3 u;      // unit, c_A − c_B: the ray's direction beyond the origin
    Vec3 e1, e2; // basis of the plane ⊥ u, where the residual lives
    int calls = 0;
};

// One evaluation at a normal: the Minkowski support w (relative to A's position: on_b − on_a), its
// residual (off the ray, or the overlap's tangential gradient) and Newton's step to make it zero.
struct Sample {
    Vec3 n{}, on_a{}, on_b{}; // on_a, on_b relative to A's position [m]
    double f = 0.0;           // overlap along n [m]
    double residual = 0.0;    // |w − (w·u) u|, or |P w| for the least overlap [m]
    Vec3 step{};              // Newton's turn of n, tangent [rad]
    bool solvable = false;    // the 2×2 system was regular (ray: and w points along +u)
    double decrease = 0.0;    // least overlap: the overlap Newton's full step is predicted to remove [m]
};

Sample evaluate(Query& q, const Vec3& n)
{
    Sample s;
    s.n = n;
    const WorldJet ja = world_jet(*q.a, q.ra, q.a->position, -1.0 * n);
    const WorldJet jb = world_jet(*q.b, q.rb, q.a->position, n);
    q.calls += 2;
    s.on_a = ja.point;
    s.on_b = jb.point;
    const Vec3 w = jb.point - ja.point;
    s.f = dot(n, w);
    const double r1 = dot(q.e1, w), r2 = dot(q.e2, w);
    s.residual = std::hypot(r1, r2);
    // ∂w/∂n = J_A(−n) + J_B(n) (d/dn of −s_A(−n) is +J_A): K δ = −r with K_ij = e_i · J t_j.
    Vec3 t1, t2;
    tangent_basis(n, t1, t2);
    const Vec3 jt1 = ja.jacobian * t1 + jb.jacobian * t1, jt2 = ja.jacobian * t2 + jb.jacobian * t2;
    if (q.target == PenetrationTarget::LeastOverlap) {
        // Gradient P w, Hessian P J P − f·P on the tangent plane; a minimum needs it positive definite.
        const double g1 = dot(t1, w), g2 = dot(t2, w);
        const double h11 = dot(t1, jt1) - s.f, h12 = dot(t1, jt2), h22 = dot(t2, jt2) - s.f;
        const double det = h11 * h22 - h12 * h12;
        s.residual = std::hypot(g1, g2);
        if (!(h11 > 0.0) || !(det > 0.0) || !std::isfinite(det))
            return s;
        s.step = (-(h22 * g1 - h12 * g2) / det) * t1 + (-(h11 * g2 - h12 * g1) / det) * t2;
        s.solvable = is_finite(s.step);
        s.decrease = -0.5 * dot(w, s.step);
        return s;
    }
    const double k11 = dot(q.e1, jt1), k12 = dot(q.e1, jt2), k21 = dot(q.e2, jt1), k22 = dot(q.e2, jt2);
    const double det = k11 * k22 - k12 * k21;
    if (!(std::abs(det) > 0.0) || !std::isfinite(det) || !(dot(w, q.u) > 0.0))
        return s;
    const double d1 = -(k22 * r1 - k12 * r2) / det, d2 = -(k11 * r2 - k21 * r1) / det;
    s.step = d1 * t1 + d2 * t2;
    s.solvable = is_finite(s.step);
    return s;
}

// Whether a trial sample improves on the current one: a smaller residual off the ray, or a smaller
// overlap; a separating direction always does.
bool improves(const Query& q, const Sample& next, const Sample& cur)
{
    if (!(next.f > 0.0))
        return true;
    return q.target == PenetrationTarget::LeastOverlap ? next.f < cur.f : next.residual < cur.residual;
}

Penetration result_of(const Query& q, const Sample& s, bool converged)
{
    Penetration r;
    r.hit = s.f > 0.0;
    r.converged = converged;
    r.depth = s.f;
    r.normal = s.n;
    r.on_a = q.a->position + s.on_a;
    r.on_b = q.a->position + s.on_b;
    r.point = 0.5 * (r.on_a + r.on_b);
    r.support_calls = q.calls;
    return r;
}

} // namespace

Penetration refine_penetration(const BodyView& a, const BodyView& b, const Vec3& start,
                               PenetrationTarget target, int max_evaluations)
{
    Query q{&a, &b, target, to_mat3(a.orientation), to_mat3(b.orientation), {}, {}, {}};
    const Vec3 centre_gap = body_shape_centre(a) - body_shape_centre(b);
    if (!(length(centre_gap) > 0.0))
        return {}; // no ray: MPR's own nudging handles coincident centres
    q.u = normalized(centre_gap);
    tangent_basis(q.u, q.e1, q.e2);
    Sample cur = evaluate(q, normalized(start));
    double turn = k_max_turn;
    while (true) {
        if (!(cur.f > 0.0)) // a separating direction: no contact, exactly
            return result_of(q, cur, true);
        if (!cur.solvable)
            return result_of(q, cur, false);
        const double len = length(cur.step);
        if (len <= k_penetration_angle_tolerance ||
            (q.target == PenetrationTarget::LeastOverlap && cur.decrease <= k_penetration_depth_tolerance))
            return result_of(q, cur, true);
        if (q.calls >= 2 * max_evaluations)
            return result_of(q, cur, false);
        const double scale = len > turn ? turn / len : 1.0;
        const Sample next = evaluate(q, normalized(cur.n + scale * cur.step));
        if (improves(q, next, cur)) {
            cur = next;
            turn = k_max_turn;
        } else {
            turn = k_shrink * std::min(len, turn);
        }
    }
}

namespace
{

// Whether a world point lies inside a body (its implicit function, no support-map evaluation).
bool inside(const BodyView& body, const Vec3& p)
{
    const Collider& c = *body.collider;
    return test_point(c, inv_rotate(body.orientation, p - body.position) + c.com_shape).inside;
}

// A least-overlap minimum is local: f > 0 there does not prove the bodies overlap (a box sliding off
// another's edge keeps a positive overlap along the face normal). A point of one body inside the other
// does; at the true minimum each deepest point lies inside the other body.
bool proven(const BodyView& a, const BodyView& b, const Penetration& r)
{
    return r.hit && (inside(b, r.on_a) || inside(a, r.on_b));
}

} // namespace

Penetration find_penetration(const BodyView& a, const BodyView& b, const Vec3& warm, PenetrationTarget target)
{
    if (!is_finite(a.position) || !is_finite(a.orientation) || !is_finite(b.position) ||
        !is_finite(b.orientation))
        return {};
    int calls = 0;
    if (length(warm) > 0.0 && is_finite(warm)) {
        Penetration r = refine_penetration(a, b, warm, target);
        if (r.converged && (target == PenetrationTarget::RayExit || !r.hit || proven(a, b, r)))
            return r;
        calls += r.support_calls;
    }
    const MprResult mpr = mpr_penetration(a, b);
    calls += 2 * mpr.support_calls;
    if (!mpr.hit)
        return {.support_calls = calls};
    Penetration r = refine_penetration(a, b, mpr.normal, target);
    r.support_calls += calls;
    if (r.converged && r.hit && (target == PenetrationTarget::RayExit || proven(a, b, r)))
        return r;
    // Newton failed from MPR's normal too: MPR's answer.
    Penetration m = penetration_from_mpr(a, b, mpr);
    m.support_calls += r.support_calls;
    return m;
}

Penetration penetration_from_mpr(const BodyView& a, const BodyView& b, const MprResult& mpr)
{
    Penetration r{.hit = mpr.hit};
    if (!mpr.hit)
        return r;
    r.depth = mpr.depth;
    r.normal = mpr.normal;
    r.on_a = body_support(a, -1.0 * mpr.normal);
    r.on_b = body_support(b, mpr.normal);
    r.point = mpr.point;
    r.support_calls = 2;
    return r;
}

} // namespace supermodal
