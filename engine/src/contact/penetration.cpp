// SPDX-License-Identifier: MIT
#include "contact/penetration.h"

#include "contact/mpr.h"
#include "geometry/support_internal.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace supermodal
{
namespace
{

// Largest turn of the normal in one Newton step [rad]; a step that does not improve is retried at a
// quarter of its length (flat faces make the map from normal to support point steep).
constexpr double k_max_turn = 0.25;
constexpr double k_shrink = 0.25;
// Face planes farther than this from the normal (|n·e|) are left to Newton's own steps [-].
constexpr double k_kink_reach = 0.2;
// Two face planes closer to parallel than this (sine of their angle) are not told apart [-].
constexpr double k_kink_min_sine = 0.1;

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
    Vec3 t1{}, t2{};          // least overlap: the tangent basis of the gradient and Hessian below
    double g1 = 0.0, g2 = 0.0, h11 = 0.0, h12 = 0.0, h22 = 0.0;
};

// |(x, y)| by a square root where the squares neither overflow nor lose digits to underflow, which
// covers every body size the engine takes; std::hypot (several times slower) elsewhere.
double norm2d(double x, double y)
{
    const double s = x * x + y * y;
    return s > 1e-290 && s < 1e290 ? std::sqrt(s) : std::hypot(x, y);
}

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
    s.residual = norm2d(r1, r2);
    // ∂w/∂n = J_A(−n) + J_B(n) (d/dn of −s_A(−n) is +J_A): K δ = −r with K_ij = e_i · J t_j.
    Vec3 t1, t2;
    tangent_basis(n, t1, t2);
    const Vec3 jt1 = ja.jacobian * t1 + jb.jacobian * t1, jt2 = ja.jacobian * t2 + jb.jacobian * t2;
    if (q.target == PenetrationTarget::LeastOverlap) {
        // Gradient P w, Hessian P J P − f·P on the tangent plane; a minimum needs it positive definite.
        const double g1 = dot(t1, w), g2 = dot(t2, w);
        const double h11 = dot(t1, jt1) - s.f, h12 = dot(t1, jt2), h22 = dot(t2, jt2) - s.f;
        const double det = h11 * h22 - h12 * h12;
        s.residual = norm2d(g1, g2);
        s.t1 = t1;
        s.t2 = t2;
        s.g1 = g1;
        s.g2 = g2;
        s.h11 = h11;
        s.h12 = h12;
        s.h22 = h22;
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

// A flat-faced superquadric's support function h(d) grows as C·|d·e|^q across the plane d·e = 0 of
// each face axis e, with q = 2/(2 − ε) < 2 (its face exponent ε < 1): its curvature there is
// infinite, and Newton's quadratic model, fitted where the curvature is finite, overshoots across the
// plane by (2 − q)/(q − 1) times its distance (4.7× at ε = 0.3). A rounded corner on a rounded edge
// has its least overlap just off one such plane, an edge on an edge near the line where two meet;
// there Newton zigzags until its budget runs out (measured on a resting pile: 85% of the failed
// searches had the normal within 1e-3 of a face plane).
struct Kink {
    Vec3 axis{};      // the face axis e (unit, world)
    double q = 2.0;   // exponent of |d·e| in h [-]
    double tau = 0.0; // n·e at the current normal [-]
};

// The face planes nearest to n (within k_kink_reach), at most two and not nearly parallel; returns
// how many.
int nearest_kinks(const Query& q, const Vec3& n, std::array<Kink, 2>& out)
{
    std::array<Kink, 6> all;
    int count = 0;
    for (int body = 0; body < 2; ++body) {
        const ShapeDef& shape = (body == 0 ? q.a : q.b)->collider->shape;
        const Mat3& r = body == 0 ? q.ra : q.rb;
        for (int k = 0; k < 3; ++k) {
            const double eps = k == 2 ? shape.epsilon1 : shape.epsilon2;
            const Vec3 e{r.m[0][k], r.m[1][k], r.m[2][k]};
            const double tau = dot(n, e);
            if (eps < 1.0 && std::abs(tau) < k_kink_reach && tau != 0.0)
                all[static_cast<size_t>(count++)] = {e, 2.0 / (2.0 - eps), tau};
        }
    }
    for (int i = 1; i < count; ++i) // insertion sort by |τ| (at most six)
        for (int j = i; j > 0 && std::abs(all[static_cast<size_t>(j)].tau) <
                                     std::abs(all[static_cast<size_t>(j - 1)].tau);
             --j)
            std::swap(all[static_cast<size_t>(j)], all[static_cast<size_t>(j - 1)]);
    int found = 0;
    for (int i = 0; i < count && found < 2; ++i)
        if (found == 0 || length(cross(out[0].axis, all[static_cast<size_t>(i)].axis)) > k_kink_min_sine)
            out[static_cast<size_t>(found++)] = all[static_cast<size_t>(i)];
    return found;
}

// Where s·τ + C·|τ|^q is least, with s and C fitted to the slope and curvature at τ0 ≠ 0; NaN when the
// curvature is not positive.
double power_law_target(double tau0, double q, double slope, double curvature)
{
    if (!(curvature > 0.0))
        return std::nan("");
    const double t0 = std::abs(tau0), sign0 = tau0 > 0.0 ? 1.0 : -1.0;
    const double cq = curvature * std::pow(t0, 2.0 - q) / (q - 1.0); // C·q
    const double linear = slope - cq * std::pow(t0, q - 1.0) * sign0;
    const double target = (linear > 0.0 ? -1.0 : 1.0) * std::pow(std::abs(linear) / cq, 1.0 / (q - 1.0));
    return std::clamp(target, -1.0, 1.0);
}

// The step that places each coordinate τ_k = n·e_k of the nearest face planes where its power law is
// least (one plane: Newton's step along it), the cross terms of the Hessian left out. The coordinates
// are (u₁·δ, u₂·δ) of a tangent step δ, u = e's tangent part (one plane: u₂ the unit tangent ⊥ u₁).
bool kink_step(const Sample& cur, const std::array<Kink, 2>& kinks, int count, Vec3& out)
{
    auto tangent = [&](const Vec3& v) { return v - dot(v, cur.n) * cur.n; };
    const Vec3 u1 = tangent(kinks[0].axis);
    const Vec3 u2 = count == 2 ? tangent(kinks[1].axis) : normalized(cross(cur.n, u1));
    // M maps the basis coordinates (t1, t2) of δ to (τ₁, τ₂); gradient and Hessian go by M⁻ᵀ.
    const double m11 = dot(u1, cur.t1), m12 = dot(u1, cur.t2), m21 = dot(u2, cur.t1), m22 = dot(u2, cur.t2);
    const double det = m11 * m22 - m12 * m21;
    if (!(std::abs(det) > 0.0))
        return false;
    // Rows of M⁻ᵀ: the τ-gradient of t1 and t2 coordinates.
    const double i11 = m22 / det, i12 = -m21 / det, i21 = -m12 / det, i22 = m11 / det; // (M⁻¹)ᵀ
    const double g1 = i11 * cur.g1 + i12 * cur.g2, g2 = i21 * cur.g1 + i22 * cur.g2;
    // Diagonal of M⁻ᵀ H M⁻¹: column k of M⁻¹ is (i1k, i2k) in the (t1, t2) basis.
    auto curvature = [&](double a, double b) {
        return cur.h11 * a * a + 2.0 * cur.h12 * a * b + cur.h22 * b * b;
    };
    const double c1 = curvature(i11, i12), c2 = curvature(i21, i22);
    const double d1 = power_law_target(kinks[0].tau, kinks[0].q, g1, c1) - kinks[0].tau;
    const double d2 = count == 2 ? power_law_target(kinks[1].tau, kinks[1].q, g2, c2) - kinks[1].tau
                                 : (c2 > 0.0 ? -g2 / c2 : 0.0);
    // δ = M⁻¹ (d1, d2) in the (t1, t2) basis.
    const Vec3 step = (i11 * d1 + i21 * d2) * cur.t1 + (i12 * d1 + i22 * d2) * cur.t2;
    const double len = length(step);
    out = normalized(cur.n + (len > k_max_turn ? k_max_turn / len : 1.0) * step);
    return is_finite(out);
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
    bool kink_failed = false;
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
        Vec3 trial = normalized(cur.n + scale * cur.step);
        bool by_kink = false;
        if (q.target == PenetrationTarget::LeastOverlap && !kink_failed) {
            // Newton's step across a face plane overshoots: the plane's own model places it.
            std::array<Kink, 2> kinks;
            const int count = nearest_kinks(q, cur.n, kinks);
            bool crosses = false;
            for (int i = 0; i < count; ++i)
                crosses |= (dot(trial, kinks[static_cast<size_t>(i)].axis) > 0.0) !=
                           (kinks[static_cast<size_t>(i)].tau > 0.0);
            if (crosses)
                by_kink = kink_step(cur, kinks, count, trial);
        }
        const Sample next = evaluate(q, trial);
        if (improves(q, next, cur)) {
            cur = next;
            turn = k_max_turn;
            kink_failed = false;
        } else if (by_kink) {
            kink_failed = true;
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

namespace
{

// The radius of a collider that is an undeformed sphere [m], else 0.
double sphere_radius(const Collider& c)
{
    const ShapeDef& s = c.shape;
    const bool sphere = s.type == ShapeType::Superquadric && !c.deformed && s.epsilon1 == 1.0 &&
                        s.epsilon2 == 1.0 && s.radii.x == s.radii.y && s.radii.y == s.radii.z;
    return sphere ? s.radii.x : 0.0;
}

// Two spheres: the normal along the line of centres, where both targets' searches end (the line is
// the ray from centre to centre, and the overlap along it is the least). False when the centres
// coincide, where no direction is preferred.
bool sphere_pair(const BodyView& a, const BodyView& b, Penetration& out)
{
    const double ra = sphere_radius(*a.collider), rb = sphere_radius(*b.collider);
    if (!(ra > 0.0) || !(rb > 0.0))
        return false;
    const Vec3 ca = a.position - rotate(a.orientation, a.collider->com_shape);
    const Vec3 cb = b.position - rotate(b.orientation, b.collider->com_shape);
    const Vec3 d = ca - cb;
    const double len = length(d);
    if (!(len > 0.0) || !std::isfinite(len))
        return false;
    const Vec3 n = d / len;
    out = {.hit = ra + rb - len > 0.0,
           .converged = true,
           .depth = ra + rb - len, // < 0 apart, as the search's
           .normal = n,
           .on_a = ca - ra * n,
           .on_b = cb + rb * n};
    out.point = 0.5 * (out.on_a + out.on_b);
    return true;
}

} // namespace

Penetration find_penetration(const BodyView& a, const BodyView& b, const Vec3& warm, PenetrationTarget target)
{
    if (!is_finite(a.position) || !is_finite(a.orientation) || !is_finite(b.position) ||
        !is_finite(b.orientation))
        return {};
    if (Penetration spheres; sphere_pair(a, b, spheres))
        return spheres; // closed form: no support evaluations
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
